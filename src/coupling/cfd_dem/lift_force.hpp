#pragma once
// The shear lift on a sphere of unresolved CFD-DEM: Saffman's (J. Fluid Mech. 22 (1965) 385;
// corrigendum 31 (1968) 624) with Mei's finite-Reynolds factor (Int. J. Multiphase Flow 18
// (1992) 145), as Crowe et al. give it (Multiphase Flows with Droplets and Particles, 2nd ed.,
// CRC 2011; 1.615 = 6.46 / 4):
//   F_L = 1.615 d^2 sqrt(rho mu / |w|) f(Re_p, beta) (u - v) x w,   w = curl u,
//   Re_p = rho |u - v| d / mu, Re_w = rho |w| d^2 / mu, beta = Re_w / (2 Re_p),
//   f = (1 - 0.3314 sqrt(beta)) exp(-Re_p / 10) + 0.3314 sqrt(beta)   (Re_p <= 40),
//   f = 0.0524 sqrt(beta Re_p)                                        (Re_p > 40).
// A sphere lagging the fluid (u - v along the flow) is lifted towards the faster fluid.
// Point-wise and device-safe.
#include "kernels/kokkos_compat.hpp"

namespace amphora::coupling::cfd_dem {

/// Mei's ratio f of the lift to Saffman's at slip Reynolds number re > 0 and beta > 0.
KOKKOS_INLINE_FUNCTION double mei_lift_factor(double re, double beta) {
  const double a = 0.3314 * kernels::math::sqrt(beta);
  if (re <= 40.0) return (1.0 - a) * kernels::math::exp(-0.1 * re) + a;
  return 0.0524 * kernels::math::sqrt(beta * re);
}

/// L = the Saffman-Mei lift on a sphere of diameter d in a fluid of density rho and dynamic
/// viscosity mu, at slip u - v and vorticity w (zero where either vanishes).
KOKKOS_INLINE_FUNCTION void saffman_mei_lift(double rho, double mu, double d, const double slip[3],
                                             const double w[3], double L[3]) {
  const double s = kernels::math::sqrt(slip[0] * slip[0] + slip[1] * slip[1] + slip[2] * slip[2]);
  const double wn = kernels::math::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
  for (int c = 0; c < 3; ++c) L[c] = 0.0;
  if (!(s > 0.0) || !(wn > 0.0)) return;
  const double re = rho * s * d / mu, re_w = rho * wn * d * d / mu;
  const double k =
      1.615 * d * d * kernels::math::sqrt(rho * mu / wn) * mei_lift_factor(re, 0.5 * re_w / re);
  L[0] = k * (slip[1] * w[2] - slip[2] * w[1]);
  L[1] = k * (slip[2] * w[0] - slip[0] * w[2]);
  L[2] = k * (slip[0] * w[1] - slip[1] * w[0]);
}

}  // namespace amphora::coupling::cfd_dem
