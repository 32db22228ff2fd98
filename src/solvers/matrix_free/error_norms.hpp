#pragma once
// L2 and H1-seminorm errors of a Q_k field against an exact solution, by Gauss quadrature with
// k + 2 points per direction on the (possibly curved) cells. `Exact` is a device-callable type
// with value(const double* x) and gradient(const double* x, double* g).
#include <algorithm>
#include <cmath>

#include "kernels/sumfac/cell_operator_kernel.hpp"
#include "solvers/matrix_free/degree_dispatch.hpp"
#include "mesh/hex/qk_space.hpp"

namespace amphora::solvers::matrix_free {

struct ErrorNorms {
  double l2 = 0.0;        ///< ||u_h - u||_L2
  double h1semi = 0.0;    ///< ||grad(u_h - u)||_L2
  double integral = 0.0;  ///< int (u_h - u) dx
  double volume = 0.0;    ///< |Omega|
  /// ||u_h - u - c||_L2 with the best constant c (a pressure known up to a constant).
  double l2_mean_free() const {
    return std::sqrt(std::max(0.0, l2 * l2 - integral * integral / volume));
  }
};

// A named function per degree: CUDA's extended lambdas may not be defined inside a generic
// lambda (the degree dispatch's).
namespace error_norms_detail {
/// The squared L2 and H1-seminorm errors (l2, h1), the error's integral and the volume with n_p
/// nodes and n_q Gauss points per direction.
template <int dim, int n_p, int n_q, class ExecSpace, class Exact>
void squared_errors(const ExecSpace& exec, const mesh::hex::QkSpace<dim, ExecSpace>& space,
                    const Kokkos::View<double*, typename ExecSpace::memory_space>& u,
                    const Exact& exact, double& l2, double& h1, double& mean, double& vol) {
  using K = kernels::sumfac::CellOperatorKernel<dim, n_p, n_q, ExecSpace,
                                                kernels::sumfac::LaplacePoint<dim>>;
  using T = typename K::T;
  K kern;
  kern.lattice = space.lattice();
  kern.shape = kernels::sumfac::ShapeData<n_p, n_q>::create(kernels::sumfac::QuadratureKind::gauss);
  kern.coordinates = space.coordinates();
  const double* src = u.data();
  Kokkos::parallel_reduce(
      "amphora::error_norms", kernels::RangePolicy<ExecSpace>(exec, 0, kern.lattice.n_batches()),
      KOKKOS_LAMBDA(int b, double& e0, double& e1, double& e2, double& e3) {
        typename K::Scratch s;
        T uloc[K::n_dofs], x[dim * K::n_points];
        const long n_nodes = kern.lattice.n_nodes();
        for (int a = 0; a < dim; ++a) {  // Jacobian rows and physical points
          kern.gather_nodes(kern.coordinates.data() + a * n_nodes, b, s.nodal);
          K::Eval::values(kern.shape, s.nodal, x + a * K::n_points, s.tmp);
          K::Eval::gradients(kern.shape, x + a * K::n_points, s.jac + a * dim * K::n_points);
        }
        kern.gather_unconstrained(src, b, uloc);
        K::Eval::values(kern.shape, uloc, s.v, s.tmp);
        K::Eval::gradients(kern.shape, s.v, s.grad);
        const int active = kern.lattice.active_lanes(b);
        for (int q = 0; q < K::n_points; ++q) {
          T J[dim * dim], inv[dim * dim];
          for (int e = 0; e < dim * dim; ++e) J[e] = s.jac[e * K::n_points + q];
          const T det = kernels::sumfac::inverse<dim>(J, inv);
          const double w = K::Eval::weight(kern.shape, q);
          for (int l = 0; l < active; ++l) {
            double xp[3] = {0.0, 0.0, 0.0}, g[3] = {0.0, 0.0, 0.0};
            for (int a = 0; a < dim; ++a) xp[a] = x[a * K::n_points + q][l];
            exact.gradient(xp, g);
            const double d0 = s.v[q][l] - exact.value(xp);
            double d1 = 0.0;
            for (int a = 0; a < dim; ++a) {  // grad u_h = J^-T grad_ref u_h
              double gh = 0.0;
              for (int c = 0; c < dim; ++c)
                gh += inv[c * dim + a][l] * s.grad[c * K::n_points + q][l];
              d1 += (gh - g[a]) * (gh - g[a]);
            }
            e0 += w * det[l] * d0 * d0;
            e1 += w * det[l] * d1;
            e2 += w * det[l] * d0;
            e3 += w * det[l];
          }
        }
      },
      l2, h1, mean, vol);
}
}  // namespace error_norms_detail

template <int dim, class ExecSpace, class Exact>
ErrorNorms error_norms(const ExecSpace& exec, const mesh::hex::QkSpace<dim, ExecSpace>& space,
                       const Kokkos::View<double*, typename ExecSpace::memory_space>& u,
                       const Exact& exact) {
  ErrorNorms result;
  const int k = space.degree();
  dispatch_degree(k, k + 2, [&](auto np_c, auto nq_c) {
    double l2 = 0.0, h1 = 0.0;
    error_norms_detail::squared_errors<dim, decltype(np_c)::value, decltype(nq_c)::value>(
        exec, space, u, exact, l2, h1, result.integral, result.volume);
    result.l2 = std::sqrt(l2);
    result.h1semi = std::sqrt(h1);
  });
  return result;
}

}  // namespace amphora::solvers::matrix_free

// PREFIX template error_norms<DIM, E, EXACT>, at file scope: with PREFIX extern, the
// declaration of an instance that one .cpp compiles (with PREFIX empty) for every includer.
#define AMPHORA_ERROR_NORMS_INSTANCE(PREFIX, DIM, E, EXACT)  \
  PREFIX template amphora::solvers::matrix_free::ErrorNorms  \
  amphora::solvers::matrix_free::error_norms<DIM, E, EXACT>( \
      const E&, const amphora::mesh::hex::QkSpace<DIM, E>&,  \
      const Kokkos::View<double*, typename E::memory_space>&, const EXACT&);
