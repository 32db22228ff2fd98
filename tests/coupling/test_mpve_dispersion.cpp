// The MP-VE dispersion relation (viscous fluid on an elastic solid, Banks, Henshaw & Schwendeman
// 2014): Newton finds the root the FSI issue quotes as a check of the derivation, the mode
// solves the interface system, and continuation follows the root through a density change and
// back to where it started.
#include <cmath>

#include "coupling/fsi/beam_channel_wave.hpp"
#include "coupling/fsi/mpve_traveling_wave.hpp"
#include "test_backend.hpp"

namespace amphora::coupling::fsi {
namespace {

// k = 2 pi, H = 1, Hbar = 0.5, rho = 1, mu = 0.01, cp = sqrt(3), cs = 1 (lambda = mu = rho_bar),
// rho_bar = 0.05: omega ~ 1.42227 - 0.37955 i (the check value, 5 decimals).
const MpveParameters check{2 * M_PI, 1.0, 0.5, 1.0, 0.01, 0.05, 0.05, 0.05};

TEST(MpveDispersion, NewtonFindsTheQuotedRoot) {
  const DispersionRoot r = solve_mpve_dispersion(check, Complex(1.4, -0.4));
  ASSERT_TRUE(r.converged) << r.iterations;
  EXPECT_NEAR(r.omega.real(), 1.42227, 5e-6) << r.omega;
  EXPECT_NEAR(r.omega.imag(), -0.37955, 5e-6) << r.omega;
  std::printf("MP-VE check: omega = %.8f %+.8f i after %d Newton iterations\n", r.omega.real(),
              r.omega.imag(), r.iterations);
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

TEST(MpveDispersion, ExactFieldsSatisfyTheEquationsAndInterfaceConditions) {
  // Checked independently of the derivation: the evaluated fields, differentiated by finite
  // differences, satisfy the momentum equations, incompressibility, no slip at y = -H, the
  // fixed solid at y = Hbar, and velocity and traction continuity at y = 0.
  const Complex w = solve_mpve_dispersion(check, Complex(1.4, -0.4)).omega;
  const auto c = mpve_mode(check, w);
  const double x = 0.3, t = 0.7, h = 1e-4;
  auto fl = [&](double xx, double yy, double tt) { return mpve_fluid(check, w, c, xx, yy, tt); };
  auto so = [&](double xx, double yy, double tt) { return mpve_solid(check, w, c, xx, yy, tt); };
  // Fluid at y = -0.4: rho u_t + p_x - mu lap u = 0 (and v), u_x + v_y = 0.
  {
    const double y = -0.4;
    auto d = [&](auto g, double dx, double dy, double dt) {
      return (g(x + dx, y + dy, t + dt) - g(x - dx, y - dy, t - dt)) / (2 * h);
    };
    auto lap = [&](auto g) {
      return (g(x + h, y, t) + g(x - h, y, t) + g(x, y + h, t) + g(x, y - h, t) - 4 * g(x, y, t)) /
             (h * h);
    };
    auto U = [&](double a, double b, double s) { return fl(a, b, s).u; };
    auto V = [&](double a, double b, double s) { return fl(a, b, s).v; };
    auto P = [&](double a, double b, double s) { return fl(a, b, s).p; };
    const double scale = std::abs(check.rho * d(U, 0, 0, h)) + std::abs(d(P, h, 0, 0)) + 1e-3;
    EXPECT_NEAR(check.rho * d(U, 0, 0, h) + d(P, h, 0, 0) - check.mu * lap(U), 0.0, 1e-5 * scale);
    EXPECT_NEAR(check.rho * d(V, 0, 0, h) + d(P, 0, h, 0) - check.mu * lap(V), 0.0, 1e-5 * scale);
    EXPECT_NEAR(d(U, h, 0, 0) + d(V, 0, h, 0), 0.0, 1e-6 * scale);
  }
  // Solid at y = 0.2: rho_bar ubar_tt = div sigma_bar.
  {
    const double y = 0.2;
    auto d = [&](auto g, double dx, double dy, double dt) {
      return (g(x + dx, y + dy, t + dt) - g(x - dx, y - dy, t - dt)) / (2 * h);
    };
    auto UT = [&](double a, double b, double s) { return so(a, b, s).ubar_t; };
    auto VT = [&](double a, double b, double s) { return so(a, b, s).vbar_t; };
    auto SXX = [&](double a, double b, double s) { return so(a, b, s).sxx; };
    auto SXY = [&](double a, double b, double s) { return so(a, b, s).sxy; };
    auto SYY = [&](double a, double b, double s) { return so(a, b, s).syy; };
    const double scale =
        std::abs(check.rho_bar * d(UT, 0, 0, h)) + std::abs(d(SXX, h, 0, 0)) + 1e-3;
    EXPECT_NEAR(check.rho_bar * d(UT, 0, 0, h) - d(SXX, h, 0, 0) - d(SXY, 0, h, 0), 0.0,
                1e-5 * scale);
    EXPECT_NEAR(check.rho_bar * d(VT, 0, 0, h) - d(SXY, h, 0, 0) - d(SYY, 0, h, 0), 0.0,
                1e-5 * scale);
  }
  const MpveFluidFields wall = fl(x, -check.H, t), f0 = fl(x, 0.0, t);
  const MpveSolidFields fixed = so(x, check.Hbar, t), s0 = so(x, 0.0, t);
  const double scale = std::abs(s0.vbar_t) + std::abs(s0.syy) + 1e-3;
  EXPECT_NEAR(wall.u, 0.0, 1e-10 * scale);
  EXPECT_NEAR(wall.v, 0.0, 1e-10 * scale);
  EXPECT_NEAR(fixed.ubar, 0.0, 1e-10 * scale);
  EXPECT_NEAR(fixed.vbar, 0.0, 1e-10 * scale);
  EXPECT_NEAR(f0.u, s0.ubar_t, 1e-10 * scale);
  EXPECT_NEAR(f0.v, s0.vbar_t, 1e-10 * scale);
  EXPECT_NEAR(f0.sxy, s0.sxy, 1e-10 * scale);
  EXPECT_NEAR(f0.syy, s0.syy, 1e-10 * scale);
  EXPECT_GT(std::abs(s0.vbar_t), 0.1);  // a real wave, not the zero solution
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
  std::printf("MP-VE rho_bar = 0.5: omega = %.6f %+.6f i\n", there.omega.real(),
              there.omega.imag());
}

}  // namespace
}  // namespace amphora::coupling::fsi

// The inviscid beam-channel relation omega^2 = (K + T k^2 + B k^4) / (rho_h + rho/(k tanh kH)).
TEST(BeamChannelWave, AddedMassLowersTheBeamFrequency) {
  amphora::physics::beam::BeamParameters p;
  p.rho_h = 0.1;
  p.tension = 1.0;
  const double k = 2 * 3.141592653589793;
  // Evaluated independently (Python, math module): 12.342387852994754.
  EXPECT_NEAR(amphora::coupling::fsi::beam_channel_frequency(p, k, 1.0, 1.0), 12.342387852994754,
              1e-12);
  // Without fluid it is the beam's own frequency; a deep channel adds rho / k.
  EXPECT_NEAR(amphora::coupling::fsi::beam_channel_frequency(p, k, 1.0, 0.0),
              amphora::physics::beam::beam_frequency(p, k), 1e-12);
  EXPECT_NEAR(amphora::coupling::fsi::channel_added_mass(k, 50.0, 2.0), 2.0 / k, 1e-12);
}
