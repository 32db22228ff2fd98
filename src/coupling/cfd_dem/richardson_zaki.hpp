#pragma once
// The references a fluidised bed is checked against: a single sphere's terminal velocity under
// a drag closure at eps = 1, and Richardson and Zaki's expansion U / U_t = eps^n (Trans. Inst.
// Chem. Eng. 32 (1954) 35; n with their wall correction in d / D).
#include <cmath>

#include "coupling/cfd_dem/drag_models.hpp"

namespace amphora::coupling::cfd_dem {

/// The speed at which a lone sphere's drag (closure `model` at eps = 1) carries its weight less
/// buoyancy: beta(U) U = pi d^3 / 6 (rho_p - rho) g. Bisection to 1e-12 relative.
inline double terminal_velocity(DragModel model, double rho, double mu, double d, double rho_p,
                                double g) {
  const double weight = M_PI * d * d * d / 6.0 * (rho_p - rho) * g;
  double lo = 0.0, hi = 1.0;
  while (drag_coefficient(model, rho, mu, d, 1.0, hi) * hi < weight) hi *= 2.0;
  for (int k = 0; k < 200 && hi - lo > 1e-12 * hi; ++k) {
    const double mid = 0.5 * (lo + hi);
    (drag_coefficient(model, rho, mu, d, 1.0, mid) * mid < weight ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

/// Richardson and Zaki's exponent n at the terminal Reynolds number re_t for spheres of
/// diameter d in a column of diameter D.
inline double richardson_zaki_exponent(double re_t, double d_over_D) {
  if (re_t < 0.2) return 4.65 + 19.5 * d_over_D;
  if (re_t < 1.0) return (4.35 + 17.5 * d_over_D) * std::pow(re_t, -0.03);
  if (re_t < 200.0) return (4.45 + 18.0 * d_over_D) * std::pow(re_t, -0.1);
  if (re_t < 500.0) return 4.45 * std::pow(re_t, -0.1);
  return 2.39;
}

/// The bed's void fraction at superficial velocity u: (u / U_t)^(1 / n).
inline double richardson_zaki_void_fraction(double u, double u_t, double n) {
  return std::pow(u / u_t, 1.0 / n);
}

}  // namespace amphora::coupling::cfd_dem
