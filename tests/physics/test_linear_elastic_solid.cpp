// The linear elastic solid alone (physics/elastic_solid): second order in space and time on a
// manufactured solution with shear and pressure parts coupled through the cross derivatives,
// identical results on every backend and thread count, bad parameters refused.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "physics/elastic_solid/linear_elastic_solid.hpp"
#include "test_backend.hpp"

namespace {

using amphora::physics::elastic_solid::ElasticGrid;
using amphora::physics::elastic_solid::ElasticMaterial;
using amphora::physics::elastic_solid::LinearElasticSolid;
using Exec = amphora::test::TestExecSpace;

constexpr double kPi = 3.141592653589793;

/// u1 = a sin(kx) cos(ly + s) cos(wt), u2 = b cos(kx) sin(ly + s) cos(wt).
struct Manufactured {
  double a = 1.0, b = 0.5, k = 2 * kPi, l = 3.0, s = 0.4, w = 5.0;
  KOKKOS_INLINE_FUNCTION double operator()(double x, double y, double t, int c) const {
    return c == 0 ? a * amphora::kernels::math::sin(k * x) *
                        amphora::kernels::math::cos(l * y + s) * amphora::kernels::math::cos(w * t)
                  : b * amphora::kernels::math::cos(k * x) *
                        amphora::kernels::math::sin(l * y + s) * amphora::kernels::math::cos(w * t);
  }
};

/// Its traction on y = const: (sigma_xy, sigma_yy) = (mu (u1_y + u2_x), (lambda + 2 mu) u2_y +
/// lambda u1_x).
struct Traction {
  Manufactured u;
  ElasticMaterial m;
  double y = 0.0;
  KOKKOS_INLINE_FUNCTION double operator()(double x, double t, int c) const {
    using amphora::kernels::math::cos;
    using amphora::kernels::math::sin;
    const double ct = cos(u.w * t), ly = u.l * y + u.s;
    const double u1_y = -u.a * u.l * sin(u.k * x) * sin(ly) * ct;
    const double u1_x = u.a * u.k * cos(u.k * x) * cos(ly) * ct;
    const double u2_x = -u.b * u.k * sin(u.k * x) * sin(ly) * ct;
    const double u2_y = u.b * u.l * cos(u.k * x) * cos(ly) * ct;
    return c == 0 ? m.mu * (u1_y + u2_x) : (m.lambda + 2 * m.mu) * u2_y + m.lambda * u1_x;
  }
};

/// f = rho u_tt - div sigma(u) for the solution above (differentiated by hand).
struct Forcing {
  Manufactured u;
  ElasticMaterial m;
  KOKKOS_INLINE_FUNCTION double operator()(double x, double y, double t, int c) const {
    const double lm = m.lambda + m.mu, l2m = m.lambda + 2 * m.mu,
                 ct = amphora::kernels::math::cos(u.w * t);
    if (c == 0) {
      const double u1 = u(x, y, t, 0);
      const double u2_xy = -u.b * u.k * u.l * amphora::kernels::math::sin(u.k * x) *
                           amphora::kernels::math::cos(u.l * y + u.s) * ct;
      return -m.rho * u.w * u.w * u1 - (-l2m * u.k * u.k * u1 - m.mu * u.l * u.l * u1 + lm * u2_xy);
    }
    const double u2 = u(x, y, t, 1);
    const double u1_xy = -u.a * u.k * u.l * amphora::kernels::math::cos(u.k * x) *
                         amphora::kernels::math::sin(u.l * y + u.s) * ct;
    return -m.rho * u.w * u.w * u2 - (-m.mu * u.k * u.k * u2 - l2m * u.l * u.l * u2 + lm * u1_xy);
  }
};

ElasticMaterial material() {
  ElasticMaterial m;
  m.rho = 2.0;
  m.lambda = 3.0;
  m.mu = 1.5;
  return m;
}

/// Max-norm displacement error at t = 0.5 on an n x n/2 grid of the unit-by-half box, the
/// bottom row Dirichlet or (traction = true) driven by the exact traction.
double error_at(int n, bool traction = false) {
  ElasticGrid g;
  g.nx = n;
  g.ny = n / 2;
  g.hx = 1.0 / n;
  g.hy = 0.5 / g.ny;
  const ElasticMaterial m = material();
  const double t_end = 0.5;
  const int steps = static_cast<int>(
      std::ceil(t_end / (0.8 * amphora::physics::elastic_solid::elastic_wave_dt_limit(g, m))));
  LinearElasticSolid<Exec> solid(g, m, t_end / steps);
  const Manufactured exact;
  const Forcing force{exact, m};
  solid.set_state(0.0, exact);
  for (int s = 0; s < steps; ++s) {
    solid.set_forcing(force);
    if (traction) {
      solid.step_with_bottom_traction(Traction{exact, m, 0.0}, exact);
    } else {
      solid.step(exact);
    }
  }
  auto u = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), solid.displacement());
  double e = 0;
  for (int j = 0; j <= g.ny; ++j)
    for (int i = 0; i < g.nx; ++i)
      for (int c = 0; c < 2; ++c)
        e = std::max(e, std::abs(u(j + 1, i, c) - exact(i * g.hx, j * g.hy, solid.time(), c)));
  return e;
}

void expect_second_order(bool traction) {
  double previous = 0;
  for (int n : {16, 32, 64, 128}) {
    const double e = error_at(n, traction);
    if (n > 16) {
      const double order = std::log2(previous / e);
      std::printf("%s n %4d  max error %.3e  order %.3f\n", traction ? "traction" : "dirichlet", n,
                  e, order);
      if (n >= 64) {
        EXPECT_NEAR(order, 2.0, 0.2) << "n = " << n;
      }
    }
    previous = e;
  }
}

TEST(LinearElasticSolid, ManufacturedSolutionConvergesAtSecondOrder) { expect_second_order(false); }

TEST(LinearElasticSolid, TractionBoundaryConvergesAtSecondOrder) { expect_second_order(true); }

/// The n = 32 run of error_at on execution space E, copied to the host.
template <class E>
auto run_on(int n) {
  ElasticGrid g{n, n / 2, 1.0 / n, 0.5 / (n / 2)};
  const ElasticMaterial m = material();
  const double t_end = 0.5;
  const int steps = static_cast<int>(
      std::ceil(t_end / (0.8 * amphora::physics::elastic_solid::elastic_wave_dt_limit(g, m))));
  LinearElasticSolid<E> solid(g, m, t_end / steps);
  const Manufactured exact;
  solid.set_state(0.0, exact);
  for (int s = 0; s < steps; ++s) {
    solid.set_forcing(Forcing{exact, m});
    solid.step(exact);
  }
  return Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), solid.displacement());
}

TEST(LinearElasticSolid, ResultDoesNotDependOnTheBackendOrThreadCount) {
  // The stencil reads only the previous levels and sums in a fixed order: this backend at any
  // thread count agrees with the Serial one to round-off (the compiler may contract or
  // vectorise the two instantiations differently, so not bit for bit).
#ifdef KOKKOS_ENABLE_SERIAL
  const auto mine = run_on<Exec>(32);
  const auto serial = run_on<Kokkos::Serial>(32);
  double scale = 0;
  for (size_t k = 0; k < serial.size(); ++k) scale = std::max(scale, std::abs(serial.data()[k]));
  for (size_t k = 0; k < mine.size(); ++k)
    ASSERT_NEAR(mine.data()[k], serial.data()[k], 1e-13 * scale) << k;
#else
  GTEST_SKIP() << "no Serial backend to compare with";
#endif
}

TEST(LinearElasticSolid, RefusesBadParametersAndUnstableSteps) {
  ElasticGrid g{32, 16, 1.0 / 32, 0.5 / 32};
  ElasticMaterial m = material();
  const double limit = amphora::physics::elastic_solid::elastic_wave_dt_limit(g, m);
  EXPECT_THROW(LinearElasticSolid<Exec>(g, m, 1.01 * limit), std::invalid_argument);
  EXPECT_NO_THROW(LinearElasticSolid<Exec>(g, m, 0.99 * limit));
  m.mu = 0;
  EXPECT_THROW(LinearElasticSolid<Exec>(g, m, 1e-4), std::invalid_argument);
  m = material();
  m.rho = -1;
  EXPECT_THROW(LinearElasticSolid<Exec>(g, m, 1e-4), std::invalid_argument);
}

}  // namespace
