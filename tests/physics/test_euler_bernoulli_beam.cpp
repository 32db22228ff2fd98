// The Euler–Bernoulli beam alone (physics/beam): second order in space and time on exact
// solutions, exact energy conservation when unloaded, bad parameters refused.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <stdexcept>

#include "physics/beam/euler_bernoulli_beam.hpp"

namespace test_euler_bernoulli_beam {

using amphora::physics::beam::BeamParameters;
using amphora::physics::beam::EulerBernoulliBeam;

constexpr double kPi = 3.141592653589793;

BeamParameters beam(int points) {
  BeamParameters p;
  p.length = 1.0;
  p.rho_h = 2.0;
  p.spring = 3.0;
  p.tension = 1.5;
  p.stiffness = 0.02;
  p.points = points;
  return p;
}

using Field = std::function<double(double x, double t)>;

/// Max-norm displacement error at t_end of a run from the exact state, with load `load`.
double error_at(int points, double t_end, const Field& eta, const Field& v, const Field& load) {
  const BeamParameters p = beam(points);
  const int steps = points;  // dt = t_end / points: dt and h shrink together
  EulerBernoulliBeam b(p, t_end / steps);
  auto sample = [&](const Field& g, double t) {
    std::vector<double> out(points);
    for (int i = 0; i < points; ++i) out[i] = g(i * b.spacing(), t);
    return out;
  };
  b.set_state(0.0, sample(eta, 0.0), sample(v, 0.0), sample(load, 0.0));
  for (int s = 1; s <= steps; ++s) b.step(sample(load, s * b.dt()));
  const auto exact = sample(eta, b.time());
  double e = 0;
  for (int i = 0; i < points; ++i) e = std::max(e, std::abs(b.displacement()[i] - exact[i]));
  return e;
}

void expect_second_order(const Field& eta, const Field& v, const Field& load) {
  double previous = 0;
  for (int points : {20, 40, 80, 160}) {
    const double e = error_at(points, 1.0, eta, v, load);
    if (points > 20) {
      const double order = std::log2(previous / e);
      std::printf("points %4d  max error %.3e  order %.3f\n", points, e, order);
      if (points >= 80) {
        EXPECT_NEAR(order, 2.0, 0.2) << "points " << points << " error " << e;
      }
    }
    previous = e;
  }
}

TEST(EulerBernoulliBeam, FreeTravelingWaveConvergesAtSecondOrder) {
  // eta = cos(k x - omega t) with omega^2 = (K + T k^2 + B k^4) / rho_h.
  const double k = 2 * kPi, w = amphora::physics::beam::beam_frequency(beam(8), k);
  expect_second_order([=](double x, double t) { return std::cos(k * x - w * t); },
                      [=](double x, double t) { return w * std::sin(k * x - w * t); },
                      [](double, double) { return 0.0; });
}

TEST(EulerBernoulliBeam, LoadedStandingWaveConvergesAtSecondOrder) {
  // eta = sin(2 k x) cos(3 t): the load rho_h eta_tt + K eta - T eta_xx + B eta_xxxx drives it.
  const BeamParameters p = beam(8);
  const double k = 4 * kPi;
  const double factor = -9 * p.rho_h + p.spring + p.tension * k * k + p.stiffness * k * k * k * k;
  expect_second_order(
      [=](double x, double t) { return std::sin(k * x) * std::cos(3 * t); },
      [=](double x, double t) { return -3 * std::sin(k * x) * std::sin(3 * t); },
      [=](double x, double t) { return factor * std::sin(k * x) * std::cos(3 * t); });
}

TEST(EulerBernoulliBeam, UnloadedEnergyIsConserved) {
  // Newmark's average-acceleration rule conserves h/2 (rho_h v.v + eta.A eta) exactly: a
  // growing interface energy in a coupled run is then the coupling's, not the beam's.
  const int n = 64;
  EulerBernoulliBeam b(beam(n), 3e-3);
  std::vector<double> eta(n), v(n), zero(n, 0.0);
  for (int i = 0; i < n; ++i) {
    const double x = i * b.spacing();
    eta[i] = std::exp(-100 * (x - 0.5) * (x - 0.5));
    v[i] = std::sin(6 * kPi * x);
  }
  b.set_state(0.0, eta, v, zero);
  const double e0 = b.energy();
  for (int s = 0; s < 2000; ++s) b.step(zero);
  EXPECT_NEAR(b.energy(), e0, 1e-11 * e0);
  double moved = 0;
  for (int i = 0; i < n; ++i) moved = std::max(moved, std::abs(b.displacement()[i] - eta[i]));
  EXPECT_GT(moved, 0.1);  // the beam did move
}

TEST(EulerBernoulliBeam, RefusesBadParameters) {
  BeamParameters p = beam(32);
  p.rho_h = 0;
  EXPECT_THROW(EulerBernoulliBeam(p, 1e-3), std::invalid_argument);
  p = beam(32);
  p.stiffness = -1;
  EXPECT_THROW(EulerBernoulliBeam(p, 1e-3), std::invalid_argument);
  p = beam(4);
  EXPECT_THROW(EulerBernoulliBeam(p, 1e-3), std::invalid_argument);
  EXPECT_THROW(EulerBernoulliBeam(beam(32), 0.0), std::invalid_argument);
}

}  // namespace test_euler_bernoulli_beam
