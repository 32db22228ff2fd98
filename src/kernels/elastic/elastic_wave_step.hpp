#pragma once
// One leapfrog step of the 2D linear elastic wave equation in displacement form,
//   rho u_tt = div sigma + f,  sigma = lambda (div u) I + mu (grad u + grad u^T),
// i.e. rho u1_tt = (lambda + 2 mu) u1_xx + mu u1_yy + (lambda + mu) u2_xy + f1 and the same
// with the roles of x and y swapped for u2, on a uniform node grid periodic in x: centred
// second differences and the 4-point cross difference (second order in space), leapfrog in
// time (second order; stable for dt below elastic_wave_dt_limit). Rows first_row .. ny-1: the
// top row is the caller's (Dirichlet data); the bottom row is too (first_row = 1) or is updated
// like the interior from a ghost row the caller filled from a traction condition (first_row = 0).
#include "kernels/spaces.hpp"

namespace amphora::kernels::elastic {

/// Node fields (storage row j + 1 for grid row j, column i, component c): grid rows -1..ny
/// (row -1 the ghost line below the bottom boundary), columns 0..nx-1 (periodic in x).
template <class MemSpace>
using NodeField = Kokkos::View<double** [2], Kokkos::LayoutRight, MemSpace>;

struct ElasticGrid {
  int nx = 0, ny = 0;  ///< columns (periodic) and cells in y (rows 0..ny)
  double hx = 0, hy = 0;
};

struct ElasticMaterial {
  double rho = 1, lambda = 1, mu = 1;
  KOKKOS_INLINE_FUNCTION double cp() const { return math::sqrt((lambda + 2 * mu) / rho); }
  KOKKOS_INLINE_FUNCTION double cs() const { return math::sqrt(mu / rho); }
};

/// Von Neumann limit of the scheme (the symbol's largest eigenvalue bounded by
/// 4 [(lambda + 2 mu)/rho] (1/hx^2 + 1/hy^2)): dt <= 1 / (cp sqrt(1/hx^2 + 1/hy^2)).
inline double elastic_wave_dt_limit(const ElasticGrid& g, const ElasticMaterial& m) {
  return 1.0 / (m.cp() * std::sqrt(1.0 / (g.hx * g.hx) + 1.0 / (g.hy * g.hy)));
}

/// u_new = 2 u - u_old + dt^2 (div sigma(u) + f) / rho on grid rows first_row..ny-1.
template <class ExecSpace, class MemSpace>
void elastic_wave_step(const ExecSpace& exec, const ElasticGrid& g, const ElasticMaterial& m,
                       double dt, const NodeField<MemSpace>& u_old, const NodeField<MemSpace>& u,
                       const NodeField<MemSpace>& f, const NodeField<MemSpace>& u_new,
                       int first_row = 1) {
  const int nx = g.nx;
  const double cxx = (m.lambda + 2 * m.mu) / (g.hx * g.hx), cyy = m.mu / (g.hy * g.hy);
  const double sxx = m.mu / (g.hx * g.hx), syy = (m.lambda + 2 * m.mu) / (g.hy * g.hy);
  const double cxy = (m.lambda + m.mu) / (4 * g.hx * g.hy);
  const double a = dt * dt / m.rho;
  Kokkos::parallel_for(
      "amphora::kernels::elastic::wave_step",
      Kokkos::MDRangePolicy<ExecSpace, Kokkos::Rank<2>>(exec, {first_row + 1, 0}, {g.ny + 1, nx}),
      KOKKOS_LAMBDA(int j, int i) {  // j: storage row
        const int e = i + 1 < nx ? i + 1 : 0, w = i > 0 ? i - 1 : nx - 1;
        auto second = [&](int c, double kx, double ky) {
          return kx * (u(j, e, c) - 2 * u(j, i, c) + u(j, w, c)) +
                 ky * (u(j + 1, i, c) - 2 * u(j, i, c) + u(j - 1, i, c));
        };
        auto cross = [&](int c) {
          return cxy * (u(j + 1, e, c) - u(j - 1, e, c) - u(j + 1, w, c) + u(j - 1, w, c));
        };
        const double div0 = second(0, cxx, cyy) + cross(1);
        const double div1 = second(1, sxx, syy) + cross(0);
        u_new(j, i, 0) = 2 * u(j, i, 0) - u_old(j, i, 0) + a * (div0 + f(j, i, 0));
        u_new(j, i, 1) = 2 * u(j, i, 1) - u_old(j, i, 1) + a * (div1 + f(j, i, 1));
      });
}

}  // namespace amphora::kernels::elastic
