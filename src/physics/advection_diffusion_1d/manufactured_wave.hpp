#pragma once
// Manufactured solution u = A exp(-gamma t) sin(k x - omega t) + B of
// u_t + a u_x = nu u_xx + f, with f chosen so that it is exact:
//   f = A exp(-gamma t) [ (nu k^2 - gamma) sin(theta) + (a k - omega) cos(theta) ].
#include "kernels/kokkos_compat.hpp"

namespace amphora::physics::advection_diffusion_1d {

struct ManufacturedWave {
  double a, nu, amplitude, offset, k, omega, gamma;

  KOKKOS_INLINE_FUNCTION double value(double x, double t) const {
    return amplitude * kernels::math::exp(-gamma * t) * kernels::math::sin(k * x - omega * t) +
           offset;
  }
  KOKKOS_INLINE_FUNCTION double derivative(double x, double t) const {
    return amplitude * k * kernels::math::exp(-gamma * t) * kernels::math::cos(k * x - omega * t);
  }
  KOKKOS_INLINE_FUNCTION double operator()(double x, double t) const {  // the source f
    const double th = k * x - omega * t;
    return amplitude * kernels::math::exp(-gamma * t) *
           ((nu * k * k - gamma) * kernels::math::sin(th) +
            (a * k - omega) * kernels::math::cos(th));
  }
};

}  // namespace amphora::physics::advection_diffusion_1d
