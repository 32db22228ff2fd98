#pragma once
// Particles and the flow's Q_k fields (Cartesian cells): the fluid's values, gradients and
// Laplacians at the particles, and the particles' forces spread to the nodes as a load,
// through the basis functions of the cell holding each particle (QkPointBasis). Since the
// basis is a partition of unity, each component of a spread force sums over the nodes to the
// particles' total: what the particles receive, the fluid gives back, to round-off.
#include <Kokkos_Core.hpp>

#include "kernels/spaces.hpp"
#include "kernels/sumfac/qk_point_basis.hpp"

namespace amphora::coupling::cfd_dem {

/// out(i, c) = sum_j f(c n_dofs + j) phi_j(x_i) for the first n points and c < components
/// (f blocked by component; out a View (n, >= components)).
template <int dim, class ExecSpace, class Field, class Points, class Out>
void interpolate(const ExecSpace& exec, const kernels::sumfac::QkPointBasis<dim>& basis,
                 const Field& f, int components, const Points& x, int n, const Out& out) {
  const long n_dofs = basis.lattice.n_dofs();
  Kokkos::parallel_for(
      "amphora::cfd_dem::interpolate", kernels::RangePolicy<ExecSpace>(exec, 0, n),
      KOKKOS_LAMBDA(int i) {
        const double p[3] = {x(i, 0), x(i, 1), x(i, 2)};
        double s[3] = {0, 0, 0};
        basis.for_each(p, [&](long j, double phi) {
          for (int c = 0; c < components; ++c) s[c] += f(c * n_dofs + j) * phi;
        });
        for (int c = 0; c < components; ++c) out(i, c) = s[c];
      });
}

/// out(i, a) = d f / d x_a at x_i for a scalar field f and the first n points.
template <int dim, class ExecSpace, class Field, class Points, class Out>
void interpolate_gradient(const ExecSpace& exec, const kernels::sumfac::QkPointBasis<dim>& basis,
                          const Field& f, const Points& x, int n, const Out& out) {
  Kokkos::parallel_for(
      "amphora::cfd_dem::interpolate_gradient", kernels::RangePolicy<ExecSpace>(exec, 0, n),
      KOKKOS_LAMBDA(int i) {
        const double p[3] = {x(i, 0), x(i, 1), x(i, 2)};
        double s[3] = {0, 0, 0};
        basis.for_each_gradient(p, [&](long j, const double* g) {
          for (int a = 0; a < dim; ++a) s[a] += f(j) * g[a];
        });
        for (int a = 0; a < dim; ++a) out(i, a) = s[a];
      });
}

/// out(i, .) = curl u at x_i for a 3D velocity u blocked by component (as in interpolate) and
/// the first n points.
template <class ExecSpace, class Field, class Points, class Out>
void interpolate_curl(const ExecSpace& exec, const kernels::sumfac::QkPointBasis<3>& basis,
                      const Field& u, const Points& x, int n, const Out& out) {
  const long n_dofs = basis.lattice.n_dofs();
  Kokkos::parallel_for(
      "amphora::cfd_dem::interpolate_curl", kernels::RangePolicy<ExecSpace>(exec, 0, n),
      KOKKOS_LAMBDA(int i) {
        const double p[3] = {x(i, 0), x(i, 1), x(i, 2)};
        double G[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};  // G[c][a] = d u_c / d x_a
        basis.for_each_gradient(p, [&](long j, const double* g) {
          for (int c = 0; c < 3; ++c)
            for (int a = 0; a < 3; ++a) G[c][a] += u(c * n_dofs + j) * g[a];
        });
        out(i, 0) = G[2][1] - G[1][2];
        out(i, 1) = G[0][2] - G[2][0];
        out(i, 2) = G[1][0] - G[0][1];
      });
}

/// out(i, c) = Laplacian of component c of f at x_i (f blocked by component as in
/// interpolate) for the first n points and c < components.
template <int dim, class ExecSpace, class Field, class Points, class Out>
void interpolate_laplacian(const ExecSpace& exec, const kernels::sumfac::QkPointBasis<dim>& basis,
                           const Field& f, int components, const Points& x, int n, const Out& out) {
  const long n_dofs = basis.lattice.n_dofs();
  Kokkos::parallel_for(
      "amphora::cfd_dem::interpolate_laplacian", kernels::RangePolicy<ExecSpace>(exec, 0, n),
      KOKKOS_LAMBDA(int i) {
        const double p[3] = {x(i, 0), x(i, 1), x(i, 2)};
        double s[3] = {0, 0, 0};
        basis.for_each_laplacian(p, [&](long j, double lap) {
          for (int c = 0; c < components; ++c) s[c] += f(c * n_dofs + j) * lap;
        });
        for (int c = 0; c < components; ++c) out(i, c) = s[c];
      });
}

/// b(c n_dofs + j) += F(i, c) phi_j(x_i) for the first n points and c < components (atomic:
/// the last bits of the sums follow the threads).
template <int dim, class ExecSpace, class Forces, class Points, class Load>
void spread(const ExecSpace& exec, const kernels::sumfac::QkPointBasis<dim>& basis, const Forces& F,
            int components, const Points& x, int n, const Load& b) {
  const long n_dofs = basis.lattice.n_dofs();
  Kokkos::parallel_for(
      "amphora::cfd_dem::spread", kernels::RangePolicy<ExecSpace>(exec, 0, n),
      KOKKOS_LAMBDA(int i) {
        const double p[3] = {x(i, 0), x(i, 1), x(i, 2)};
        double f[3] = {0, 0, 0};
        for (int c = 0; c < components; ++c) f[c] = F(i, c);
        basis.for_each(p, [&](long j, double phi) {
          for (int c = 0; c < components; ++c) Kokkos::atomic_add(&b(c * n_dofs + j), f[c] * phi);
        });
      });
}

}  // namespace amphora::coupling::cfd_dem
