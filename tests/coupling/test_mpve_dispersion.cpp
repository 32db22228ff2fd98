// The MP-VE dispersion relation (viscous fluid on an elastic solid, Banks, Henshaw & Schwendeman
// 2014): Newton finds the root the FSI issue quotes as a check of the derivation, the mode
// solves the interface system, and continuation follows the root through a density change and
// back to where it started.
#include <cmath>

#include "coupling/fsi/beam_channel_wave.hpp"
#include "coupling/fsi/mpve_traveling_wave.hpp"
#include "test_backend.hpp"

namespace amphora::fsi {
namespace {

// k = 2 pi, H = 1, Hbar = 0.5, rho = 1, mu = 0.01, cp = sqrt(3), cs = 1 (lambda = mu = rho_bar),
// rho_bar = 0.05: omega ~ 1.42227 - 0.37955 i (the check value, 5 decimals).
const MpveParameters check{2 * M_PI, 1.0, 0.5, 1.0, 0.01, 0.05, 0.05, 0.05};

TEST(MpveDispersion, NewtonFindsTheQuotedRoot) {
  const DispersionRoot r = solve_mpve_dispersion(check, Complex(1.4, -0.4));
  ASSERT_TRUE(r.converged) << r.iterations;
  EXPECT_NEAR(r.omega.real(), 1.42227, 5e-6) << r.omega;
  EXPECT_NEAR(r.omega.imag(), -0.37955, 5e-6) << r.omega;
  std::printf("MP-VE check: omega = %.8f %+.8f i after %d Newton iterations\n", r.omega.real(), r.omega.imag(),
              r.iterations);
}

TEST(MpveDispersion, ModeSolvesTheInterfaceSystem) {
  const Complex w = solve_mpve_dispersion(check, Complex(1.4, -0.4)).omega;
  const auto c = mpve_mode(check, w);
  const auto M = mpve_matrix(check, w);
  double residual = 0, scale = 0;
  for (int r = 0; r < 8; ++r) {
    Complex s = 0;
    for (int j = 0; j < 8; ++j) {
      s += M[8 * r + j] * c[j];
      scale = std::max(scale, std::abs(M[8 * r + j] * c[j]));
    }
    residual = std::max(residual, std::abs(s));
  }
  EXPECT_LT(residual, 1e-8 * scale);
  // normalised to vbar(0) = alpha F - i k G = 1
  const double cp2 = (check.lambda_bar + 2 * check.mu_bar) / check.rho_bar;
  const Complex a = std::sqrt(check.k * check.k - w * w / cp2);
  EXPECT_NEAR(std::abs(a * c[5] - Complex(0, check.k) * c[6] - 1.0), 0.0, 1e-12);
}

TEST(MpveDispersion, ContinuationFollowsTheRootThereAndBack) {
  const Complex w0 = solve_mpve_dispersion(check, Complex(1.4, -0.4)).omega;
  MpveParameters heavy = check;
  heavy.rho_bar = 0.5, heavy.lambda_bar = 0.5, heavy.mu_bar = 0.5;  // same wave speeds, 10x denser
  const DispersionRoot there = continue_mpve_dispersion(check, w0, heavy, 20);
  ASSERT_TRUE(there.converged);
  EXPECT_GT(std::abs(there.omega - w0), 1e-2);  // the root moved
  const DispersionRoot back = continue_mpve_dispersion(heavy, there.omega, check, 20);
  ASSERT_TRUE(back.converged);
  EXPECT_LT(std::abs(back.omega - w0), 1e-9 * std::abs(w0));
  std::printf("MP-VE rho_bar = 0.5: omega = %.6f %+.6f i\n", there.omega.real(), there.omega.imag());
}

}  // namespace
}  // namespace amphora::fsi

// The inviscid beam-channel relation omega^2 = (K + T k^2 + B k^4) / (rho_h + rho/(k tanh kH)).
TEST(BeamChannelWave, AddedMassLowersTheBeamFrequency) {
  amphora::beam::BeamParameters p;
  p.rho_h = 0.1;
  p.tension = 1.0;
  const double k = 2 * 3.141592653589793;
  // Evaluated independently (Python, math module): 12.342387852994754.
  EXPECT_NEAR(amphora::fsi::beam_channel_frequency(p, k, 1.0, 1.0), 12.342387852994754, 1e-12);
  // Without fluid it is the beam's own frequency; a deep channel adds rho / k.
  EXPECT_NEAR(amphora::fsi::beam_channel_frequency(p, k, 1.0, 0.0),
              amphora::beam::beam_frequency(p, k), 1e-12);
  EXPECT_NEAR(amphora::fsi::channel_added_mass(k, 50.0, 2.0), 2.0 / k, 1e-12);
}
