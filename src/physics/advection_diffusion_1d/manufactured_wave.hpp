#pragma once
// Manufactured solution u = A exp(-gamma t) sin(k x - omega t) + B of
// u_t + a u_x = nu u_xx + f, with f chosen so that it is exact:
//   f = A exp(-gamma t) [ (nu k^2 - gamma) sin(theta) + (a k - omega) cos(theta) ].
#include "kernels/kokkos_compat.hpp"

namespace amphora::advection_diffusion_1d {

struct ManufacturedWave {
  double a, nu, amplitude, offset, k, omega, gamma;

  KOKKOS_INLINE_FUNCTION double value(double x, double t) const {
    return amplitude * math::exp(-gamma * t) * math::sin(k * x - omega * t) + offset;
  }
  KOKKOS_INLINE_FUNCTION double derivative(double x, double t) const {
    return amplitude * k * math::exp(-gamma * t) * math::cos(k * x - omega * t);
  }
  KOKKOS_INLINE_FUNCTION double operator()(double x, double t) const {  // the source f
    const double th = k * x - omega * t;
    return amplitude * math::exp(-gamma * t) *
           ((nu * k * k - gamma) * math::sin(th) + (a * k - omega) * math::cos(th));
  }
};

}  // namespace amphora::advection_diffusion_1d
