#pragma once
// Glass spheres settling in water (the settling tests, one and two way): the properties and the
// terminal velocity of Dallavalle's drag, C_d = (0.63 + 4.8 / sqrt(Re))^2 (Di Felice's at
// eps = 1).
#include <cmath>
#include <utility>

namespace amphora::coupling::cfd_dem::settling_sphere {

constexpr double kRhoF = 1000.0, kMu = 1e-3, kRhoP = 2500.0, kG = 9.81;

/// Diameter and terminal speed of a sphere settling at Reynolds number re: the balance
/// C_d rho v^2 pi d^2 / 8 = (rho_p - rho) g pi d^3 / 6 with v = Re mu / (rho d) gives
/// d^3 = 3 C_d Re^2 mu^2 / (4 rho (rho_p - rho) g).
inline std::pair<double, double> terminal(double re) {
  const double cd = std::pow(0.63 + 4.8 / std::sqrt(re), 2);
  const double d = std::cbrt(3 * cd * re * re * kMu * kMu / (4 * kRhoF * (kRhoP - kRhoF) * kG));
  return {d, re * kMu / (kRhoF * d)};
}

}  // namespace amphora::coupling::cfd_dem::settling_sphere
