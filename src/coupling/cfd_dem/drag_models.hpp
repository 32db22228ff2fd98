#pragma once
// Drag closures of unresolved CFD-DEM: the force of the fluid on one sphere in a suspension,
// F_d = beta (u_f - u_p), as a function of the local void fraction eps and the slip. Point-wise
// and device-safe; the scene chooses the closure by name.
//
// Re = rho eps |u_f - u_p| d / mu is the particle Reynolds number of the superficial slip.
// - Di Felice (Int. J. Multiphase Flow 20 (1994) 153): beta = (1/2) C_d rho (pi d^2 / 4)
//   eps^(2 - chi) |u_f - u_p|, C_d = (0.63 + 4.8 / sqrt(Re))^2 (Dallavalle),
//   chi = 3.7 - 0.65 exp(-(1.5 - log10 Re)^2 / 2).
// - Rong, Dong & Yu (Chem. Eng. Sci. 99 (2013) 44): Di Felice's form with
//   chi = 2.65 (eps + 1) - (5.3 - 3.5 eps) eps^2 exp(-(1.5 - log10 Re)^2 / 2).
// - Beetstra, van der Hoef & Kuipers (AIChE J. 53 (2007) 489): beta = 3 pi mu d eps F(phi, Re),
//   phi = 1 - eps, F = 10 phi / eps^2 + eps^2 (1 + 1.5 sqrt(phi))
//   + 0.413 Re / (24 eps^2) (1 / eps + 3 phi eps + 8.4 Re^-0.343) / (1 + 10^(3 phi) Re^-(1 + 4 phi)
//   / 2).
// - Gidaspow (Multiphase Flow and Fluidization, 1994): Ergun below eps = 0.8, Wen & Yu above;
//   per unit volume beta_v = 150 phi^2 mu / (eps d^2) + 1.75 phi rho |u_r| / d, or
//   (3/4) C_d eps phi rho |u_r| / d eps^-2.65 with C_d = 24 / Re (1 + 0.15 Re^0.687) (0.44
//   above Re = 1000); per particle beta = beta_v V_p / phi.
// All four tend to Stokes' 3 pi mu d at eps = 1 and small Re (Di Felice and Rong to 2.88 pi mu d:
// 4.8^2 = 23.04 in place of 24). The pressure-gradient (buoyancy) force is not part of beta.
#include <optional>
#include <string>

#include "kernels/kokkos_compat.hpp"

namespace amphora::coupling::cfd_dem {

enum class DragModel : int { di_felice = 0, rong = 1, beetstra = 2, gidaspow = 3 };

/// The closure of a name ("di_felice", "rong", "beetstra", "gidaspow"), or none.
std::optional<DragModel> drag_model_from_name(const std::string& name);
/// The names drag_model_from_name accepts, comma-separated (for error messages).
const char* drag_model_names();

namespace drag_detail {

KOKKOS_INLINE_FUNCTION double log10_of(double x) {
  return kernels::math::log(x) / 2.302585092994046;
}

/// Di Felice's form with exponent chi: C_d |u_r| written as (0.63 sqrt|u_r| + 4.8 sqrt(|u_r| /
/// Re))^2, finite as the slip vanishes.
KOKKOS_INLINE_FUNCTION double voidage_form(double rho, double mu, double d, double eps, double slip,
                                           double chi) {
  const double slip_over_re = mu / (rho * eps * d);
  const double s = 0.63 * kernels::math::sqrt(slip) + 4.8 * kernels::math::sqrt(slip_over_re);
  const double area = 0.25 * M_PI * d * d;
  return 0.5 * s * s * rho * area * kernels::math::pow(eps, 2.0 - chi);
}

KOKKOS_INLINE_FUNCTION double bump(double re) {
  const double a = 1.5 - log10_of(re);
  return kernels::math::exp(-0.5 * a * a);
}

}  // namespace drag_detail

/// beta [kg/s] of one sphere of diameter d in a fluid of density rho and dynamic viscosity mu,
/// at void fraction eps in (0, 1] and slip speed |u_f - u_p| >= 0.
KOKKOS_INLINE_FUNCTION double drag_coefficient(DragModel model, double rho, double mu, double d,
                                               double eps, double slip) {
  using namespace drag_detail;
  namespace m = kernels::math;
  const double re = kernels::math::max(rho * eps * slip * d / mu, 1e-30);
  const double phi = 1.0 - eps;
  switch (model) {
    case DragModel::di_felice: return voidage_form(rho, mu, d, eps, slip, 3.7 - 0.65 * bump(re));
    case DragModel::rong:
      return voidage_form(rho, mu, d, eps, slip,
                          2.65 * (eps + 1.0) - (5.3 - 3.5 * eps) * eps * eps * bump(re));
    case DragModel::beetstra: {
      const double e2 = eps * eps;
      const double inertial =
          0.413 * re / (24.0 * e2) * (1.0 / eps + 3.0 * phi * eps + 8.4 * m::pow(re, -0.343)) /
          (1.0 + m::pow(10.0, 3.0 * phi) * m::pow(re, -0.5 * (1.0 + 4.0 * phi)));
      const double f = 10.0 * phi / e2 + e2 * (1.0 + 1.5 * m::sqrt(phi)) + inertial;
      return 3.0 * M_PI * mu * d * eps * f;
    }
    case DragModel::gidaspow:
    default: {
      const double volume = M_PI * d * d * d / 6.0;
      if (eps < 0.8) {  // Ergun, per unit bed volume divided by the solid fraction
        return (150.0 * phi * mu / (eps * d * d) + 1.75 * rho * slip / d) * volume;
      }
      // Wen & Yu: C_d |u_r| = 24 mu / (rho eps d) (1 + 0.15 Re^0.687), finite at zero slip
      const double cd_slip = re < 1000.0
                                 ? 24.0 * mu / (rho * eps * d) * (1.0 + 0.15 * m::pow(re, 0.687))
                                 : 0.44 * slip;
      return 0.75 * cd_slip * eps * rho / d * m::pow(eps, -2.65) * volume;
    }
  }
}

}  // namespace amphora::coupling::cfd_dem
