// The viscous channel flow alone (physics/channel_flow/channel_stokes): second order in space
// and time on a manufactured solution with flow through both walls' data, a projected velocity
// discretely divergence-free to round-off, bad parameters refused; the impedance top (the
// fluid side of the AMP coupling) likewise, fed the solution's own characteristics, for heavy,
// moderate and very light solid impedances.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <optional>
#include <stdexcept>

#include "physics/channel_flow/channel_stokes.hpp"

namespace test_channel_stokes {

using amphora::physics::channel_flow::ChannelGrid;
using amphora::physics::channel_flow::ChannelStokes;
using amphora::physics::channel_flow::StokesData;
using amphora::physics::channel_flow::TopImpedance;

constexpr double kPi = 3.141592653589793;
double kMu = 0.1;  // the viscosity (the impedance cases lower it)
constexpr double kRho = 1.3, kK = 2 * kPi, kL = 3.0, kW = 2.0, kDepth = 0.5;

// Stream function psi = sin(kx) cos(ly) cos(wt): u = psi_y, v = -psi_x; p = cos(kx) sin(ly)
// sin(wt).
double u_exact(double x, double y, double t) {
  return -kL * std::sin(kK * x) * std::sin(kL * y) * std::cos(kW * t);
}
double v_exact(double x, double y, double t) {
  return -kK * std::cos(kK * x) * std::cos(kL * y) * std::cos(kW * t);
}
double p_exact(double x, double y, double t) {
  return std::cos(kK * x) * std::sin(kL * y) * std::sin(kW * t);
}

double u_y_exact(double x, double y, double t) {
  return -kL * kL * std::sin(kK * x) * std::cos(kL * y) * std::cos(kW * t);
}
double v_x_exact(double x, double y, double t) {
  return kK * kK * std::sin(kK * x) * std::cos(kL * y) * std::cos(kW * t);
}
double v_y_exact(double x, double y, double t) {
  return kK * kL * std::cos(kK * x) * std::sin(kL * y) * std::cos(kW * t);
}

StokesData data() {
  const double lap = -(kK * kK + kL * kL);  // lap u = lap * u for both components
  StokesData d;
  // f = rho v_t + grad p - mu lap v.
  d.fx = [lap](double x, double y, double t) {
    return kRho * kL * kW * std::sin(kK * x) * std::sin(kL * y) * std::sin(kW * t) -
           kK * std::sin(kK * x) * std::sin(kL * y) * std::sin(kW * t) -
           kMu * lap * u_exact(x, y, t);
  };
  d.fy = [lap](double x, double y, double t) {
    return kRho * kK * kW * std::cos(kK * x) * std::cos(kL * y) * std::sin(kW * t) +
           kL * std::cos(kK * x) * std::cos(kL * y) * std::sin(kW * t) -
           kMu * lap * v_exact(x, y, t);
  };
  d.u_bottom = [](double x, double t) { return u_exact(x, -kDepth, t); };
  d.u_top = [](double x, double t) { return u_exact(x, 0.0, t); };
  d.v_bottom = [](double x, double t) { return v_exact(x, -kDepth, t); };
  d.v_top = [](double x, double t) { return v_exact(x, 0.0, t); };
  return d;
}

struct Errors {
  double u, v, p, divergence;
};

Errors run(int n, std::optional<TopImpedance> top = std::nullopt) {
  ChannelGrid g;
  g.nx = n;
  g.ny = n / 2;
  g.length = 1.0;
  g.depth = kDepth;
  const double t_end = 0.5;
  const int steps = 2 * n;
  ChannelStokes s(g, kRho, kMu, t_end / steps, top);
  std::vector<double> u(size_t(g.nx) * g.ny), v(size_t(g.nx) * (g.ny + 1)), p(size_t(g.nx) * g.ny);
  for (int j = 0; j <= g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      v[size_t(j) * g.nx + i] = v_exact(s.v_x(i), s.v_y(j), 0.0);
      if (j == g.ny) continue;
      u[size_t(j) * g.nx + i] = u_exact(s.u_x(i), s.u_y(j), 0.0);
      p[size_t(j) * g.nx + i] = p_exact(s.v_x(i), s.u_y(j), -0.5 * s.dt());
    }
  std::vector<double>
      top_state;  // impedance top: u on the wall, the ghost v above it, p on the wall at -3dt/2
  if (top) {
    for (int i = 0; i < g.nx; ++i) top_state.push_back(u_exact(s.u_x(i), 0.0, 0.0));
  }
  s.set_state(0.0, u, v, p, top_state);
  StokesData d = data();
  if (top) {  // the characteristics sigma n + z v of the exact solution
    const TopImpedance z = *top;
    d.g_top_x = [z](double x, double t) {
      return kMu * (u_y_exact(x, 0, t) + v_x_exact(x, 0, t)) + z.z_shear * u_exact(x, 0, t);
    };
    d.g_top_y = [z](double x, double t) {
      return -p_exact(x, 0, t) + 2 * kMu * v_y_exact(x, 0, t) + z.z_normal * v_exact(x, 0, t);
    };
  }
  // The interface's normal velocity guessed by extrapolation in time of the fluid's own.
  std::vector<double> v_old(g.nx), v_now(g.nx);
  for (int i = 0; i < g.nx; ++i) {
    v_old[i] = v_exact(s.v_x(i), 0.0, -s.dt());
    v_now[i] = v_exact(s.v_x(i), 0.0, 0.0);
  }
  if (top)
    d.v_top = [&](double x, double) {
      const int i = int(std::floor(x * g.nx));
      return 2 * v_now[i] - v_old[i];
    };
  for (int k = 0; k < steps; ++k) {
    s.step(d);
    v_old = v_now;
    for (int i = 0; i < g.nx; ++i) v_now[i] = s.v()[size_t(g.ny) * g.nx + i];
  }
  Errors e{0, 0, 0, s.max_divergence()};
  const double tp = s.time() - 0.5 * s.dt();
  double mean = 0;  // a velocity top leaves p up to a constant; an impedance top fixes it
  if (!top)
    for (double x : s.p()) mean += x / s.p().size();
  for (int j = 0; j <= g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      e.v = std::max(e.v,
                     std::abs(s.v()[size_t(j) * g.nx + i] - v_exact(s.v_x(i), s.v_y(j), s.time())));
      if (j == g.ny) continue;
      e.u = std::max(e.u,
                     std::abs(s.u()[size_t(j) * g.nx + i] - u_exact(s.u_x(i), s.u_y(j), s.time())));
      e.p = std::max(
          e.p, std::abs(s.p()[size_t(j) * g.nx + i] - mean - p_exact(s.v_x(i), s.u_y(j), tp)));
    }
  return e;
}

void expect_second_order(std::optional<TopImpedance> top, double mu) {
  kMu = mu;
  Errors previous{};
  for (int n : {16, 32, 64, 128}) {
    const Errors e = run(n, top);
    EXPECT_LT(e.divergence, 1e-9) << "n = " << n;
    if (n > 16) {
      const double ou = std::log2(previous.u / e.u), ov = std::log2(previous.v / e.v),
                   op = std::log2(previous.p / e.p);
      std::printf("n %3d  u %.3e (%.2f)  v %.3e (%.2f)  p %.3e (%.2f)  max div %.1e\n", n, e.u, ou,
                  e.v, ov, e.p, op, e.divergence);
      if (n >= 64) {
        EXPECT_NEAR(ou, 2.0, 0.2);
        EXPECT_NEAR(ov, 2.0, 0.2);
        EXPECT_NEAR(op, 2.0, 0.2);
      }
    }
    previous = e;
  }
}

TEST(ChannelStokes, ManufacturedFlowConvergesAtSecondOrder) {
  expect_second_order(std::nullopt, 0.1);
}

TEST(ChannelStokes, ImpedanceTopConvergesAtSecondOrderForEveryImpedance) {
  // mu dt / (rho h^2) up to 0.25 (mu = 0.01) and 12 (mu = 0.5): the normal viscous stress's
  // share of the pressure increment is implicit, so light solids set no viscous step limit.
  for (double mu : {0.01, 0.5})
    for (double z : {1e3, 1.0, 1e-3}) {
      std::printf("impedance top, mu = %g, z_p = %g, z_s = %g\n", mu, z * std::sqrt(3.0), z);
      expect_second_order(TopImpedance{z * std::sqrt(3.0), z}, mu);
    }
}

TEST(ChannelStokes, RefusesBadParameters) {
  ChannelGrid g;
  EXPECT_THROW(ChannelStokes(g, 0.0, 0.1, 1e-3), std::invalid_argument);
  EXPECT_THROW(ChannelStokes(g, 1.0, -0.1, 1e-3), std::invalid_argument);
  EXPECT_THROW(ChannelStokes(g, 1.0, 0.1, 0.0), std::invalid_argument);
  EXPECT_THROW(ChannelStokes(g, 1.0, 0.1, 1e-3, TopImpedance{-1.0, 1.0}), std::invalid_argument);
}

}  // namespace test_channel_stokes
