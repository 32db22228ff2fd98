#pragma once
// Explicit centred finite-difference step for u_t + a u_x = nu u_xx + f on a uniform 1D grid
// (forward Euler in time, D0 for advection, D+D- for diffusion; Henshaw, Overture talk,
// ../shared/seeds/000). The source is a point-wise functor f(x, t), so the loop knows no physics.
#include "kernels/spaces.hpp"

namespace amphora::kernels::stencil {

/// Stability limit of the scheme above (von Neumann): dt <= h^2 / (2 nu) and dt <= 2 nu / a^2.
KOKKOS_INLINE_FUNCTION double advection_diffusion_ftcs_dt_limit(double a, double nu, double h) {
  const double diffusive = h * h / (2.0 * nu);
  const double advective = a != 0.0 ? 2.0 * nu / (a * a) : diffusive;
  return math::min(diffusive, advective);
}

template <class ExecSpace, class ConstView, class View, class Source>
void advection_diffusion_ftcs(const ExecSpace& exec, const ConstView& u_old, const View& u_new,
                              int first, int last, double x0, double dx, double a, double nu,
                              double t, double dt, const Source& source) {
  const double c_adv = -a * dt / (2.0 * dx);
  const double c_dif = nu * dt / (dx * dx);
  Kokkos::parallel_for(
      "amphora::stencil::advection_diffusion_ftcs", RangePolicy<ExecSpace>(exec, first, last),
      KOKKOS_LAMBDA(int i) {
        const double um = u_old(i - 1), u0 = u_old(i), up = u_old(i + 1);
        u_new(i) =
            u0 + c_adv * (up - um) + c_dif * (up - 2.0 * u0 + um) + dt * source(x0 + i * dx, t);
      });
}

}  // namespace amphora::kernels::stencil
