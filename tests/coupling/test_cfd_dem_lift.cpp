// The Saffman-Mei shear lift (coupling/cfd_dem/lift_force.hpp): Saffman's force in his own
// setting and form, its direction, Mei's two regimes, and nothing without slip or shear.
#include <cmath>

#include <gtest/gtest.h>

#include "coupling/cfd_dem/lift_force.hpp"

namespace amphora::coupling::cfd_dem {
namespace {

constexpr double rho = 1000.0, mu = 1e-3, d = 1e-4;

TEST(SaffmanMeiLift, IsSaffmansForceAtSmallReynoldsNumbers) {
  // Saffman (1965) with his 1968 corrigendum: a sphere of radius a lagging a shear flow
  // u = (G y, 0, 0) by U feels 6.46 mu a^2 U sqrt(G / nu) towards the faster fluid (+y).
  const double G = 10.0, U = 1e-9, a = 0.5 * d, nu = mu / rho;
  const double slip[3] = {U, 0.0, 0.0}, w[3] = {0.0, 0.0, -G};  // curl u = -G z
  double L[3];
  saffman_mei_lift(rho, mu, d, slip, w, L);
  const double saffman = 6.46 * mu * a * a * U * std::sqrt(G / nu);
  // Re_p = 1e-7, Re_w = 0.1: Mei's factor is 1 - 0.3314 sqrt(beta) (1 - exp(-Re_p / 10)),
  // 1 - 2.3e-6
  EXPECT_NEAR(L[1] / saffman, 1.0, 1e-5);
  EXPECT_EQ(L[0], 0.0);
  EXPECT_EQ(L[2], 0.0);
}

TEST(SaffmanMeiLift, IsNormalToSlipAndVorticity) {
  const double slip[3] = {0.3, -0.2, 0.1}, w[3] = {2.0, 5.0, -1.0};
  double L[3];
  saffman_mei_lift(rho, mu, d, slip, w, L);
  const double norm = std::sqrt(L[0] * L[0] + L[1] * L[1] + L[2] * L[2]);
  EXPECT_GT(norm, 0.0);
  EXPECT_NEAR((L[0] * slip[0] + L[1] * slip[1] + L[2] * slip[2]) / norm, 0.0, 1e-15);
  EXPECT_NEAR((L[0] * w[0] + L[1] * w[1] + L[2] * w[2]) / norm, 0.0, 1e-14);
}

TEST(SaffmanMeiLift, MeisFactorFallsWithTheSlipReynoldsNumber) {
  // Re_p <= 40: from 1 towards 0.3314 sqrt(beta) as exp(-Re_p / 10); above 40, Mei's
  // 0.0524 sqrt(beta Re_p). At fixed shear (beta Re_p = Re_w / 2) the lift above 40 grows
  // only as the slip: F / |slip| is the same at every Re_p there.
  EXPECT_NEAR(mei_lift_factor(1e-9, 2.0), 1.0, 1e-9);
  for (double beta : {0.005, 0.05, 0.4}) {
    double last = 2.0;
    for (double re = 0.5; re <= 40.0; re *= 2.0) {
      const double f = mei_lift_factor(re, beta);
      EXPECT_LT(f, last) << re;
      EXPECT_GT(f, 0.3314 * std::sqrt(beta)) << re;
      last = f;
    }
  }
  const double re_w = 4.0;
  EXPECT_NEAR(mei_lift_factor(60.0, 0.5 * re_w / 60.0), mei_lift_factor(90.0, 0.5 * re_w / 90.0),
              1e-15);
}

TEST(SaffmanMeiLift, VanishesWithoutSlipOrShear) {
  const double none[3] = {0.0, 0.0, 0.0}, some[3] = {0.1, 0.2, 0.3};
  double L[3];
  saffman_mei_lift(rho, mu, d, none, some, L);
  EXPECT_EQ(L[0] * L[0] + L[1] * L[1] + L[2] * L[2], 0.0);
  saffman_mei_lift(rho, mu, d, some, none, L);
  EXPECT_EQ(L[0] * L[0] + L[1] * L[1] + L[2] * L[2], 0.0);
}

}  // namespace
}  // namespace amphora::coupling::cfd_dem
