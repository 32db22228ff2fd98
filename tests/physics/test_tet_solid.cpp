#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "kernels/solid/svd3.hpp"
#include "physics/solid_fem/tet_solid.hpp"
#include "test_backend.hpp"

namespace amphora {
// A named namespace, not an anonymous one: CUDA does not support extended lambdas in
// anonymous namespaces (Kokkos issue #1547).
namespace test_tet_solid_cases {

using physics::solid_fem::Hyperelastic;
using physics::solid_fem::Material;
using physics::solid_fem::TetSolid;
using physics::solid_fem::TetSolidOptions;
using test::TestExecSpace;
using Solid = TetSolid<TestExecSpace>;

mesh::tet::TetMesh unit_cube(int n) {
  return mesh::tet::box_tet_mesh({n, n, n}, {0, 0, 0}, {1, 1, 1});
}

TetSolidOptions options(double s_clamp, double damping) {
  TetSolidOptions o;
  o.material = Material{Hyperelastic::neo_hookean, 1.0, 2.0, s_clamp};
  o.damping = damping;
  return o;
}

/// Sets every node's position and velocity from functions of its rest position.
template <class Position, class Velocity>
void set_state(Solid& s, Position x_of, Velocity v_of) {
  auto X = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), s.rest_positions());
  auto x = Kokkos::create_mirror(s.positions());
  auto v = Kokkos::create_mirror(s.velocities());
  for (size_t i = 0; i < X.extent(0); ++i) {
    const std::array<double, 3> p{X(i, 0), X(i, 1), X(i, 2)};
    const auto xi = x_of(p), vi = v_of(p);
    for (int d = 0; d < 3; ++d) x(i, d) = xi[d], v(i, d) = vi[d];
  }
  Kokkos::deep_copy(s.positions(), x);
  Kokkos::deep_copy(s.velocities(), v);
  s.update_forces();
}

/// The largest relative drift of kinetic + elastic energy over [0, T] at step dt.
double energy_drift(double dt, double T) {
  Solid s(unit_cube(3), options(0.25, 0.0));
  set_state(
      s, [](const std::array<double, 3>& p) { return p; },
      [](const std::array<double, 3>& p) {
        return std::array<double, 3>{0.3 * (p[0] - 0.5), -0.2 * (p[1] - 0.5),
                                     0.2 * std::sin(3.0 * p[0]) * p[2]};
      });
  const double e0 = s.kinetic_energy() + s.elastic_energy();
  double drift = 0.0;
  const int steps = static_cast<int>(std::lround(T / dt));
  for (int n = 0; n < steps; ++n) {
    s.step(dt);
    drift = std::max(drift, std::abs(s.kinetic_energy() + s.elastic_energy() - e0) / e0);
  }
  return drift;
}

TEST(TetSolid, UndampedStepConservesEnergyToSecondOrder) {
  const double dt = Solid(unit_cube(3), options(0.25, 0.0)).stable_dt(0.25);
  const double d1 = energy_drift(dt, 2.0), d2 = energy_drift(0.5 * dt, 2.0);
  const double order = std::log2(d1 / d2);
  EXPECT_GT(order, 1.8) << "drift " << d1 << " at dt, " << d2 << " at dt/2";
  EXPECT_LT(order, 2.3);
  EXPECT_LT(d1, 1e-2);
}

/// The cube mirrored through z = 0.5 and flattened to 30 % of its height: every element
/// inverted (det F = -0.3), at rest.
void squash(Solid& s) {
  set_state(
      s,
      [](const std::array<double, 3>& p) {
        return std::array<double, 3>{p[0], p[1], 0.5 - 0.3 * (p[2] - 0.5)};
      },
      [](const std::array<double, 3>&) {
        return std::array<double, 3>{0.0, 0.0, 0.0};
      });
}

/// The largest |s_i - 1| over the elements: 0 for a rigid motion of the rest shape.
double largest_strain(const Solid& s) {
  auto X = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), s.rest_positions());
  auto x = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), s.positions());
  auto t = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), s.tets());
  double worst = 0.0;
  for (size_t e = 0; e < t.extent(0); ++e) {
    kernels::solid::Mat3 Dm, Ds;
    for (int c = 1; c < 4; ++c)
      for (int d = 0; d < 3; ++d) {
        Dm(d, c - 1) = X(t(e, c), d) - X(t(e, 0), d);
        Ds(d, c - 1) = x(t(e, c), d) - x(t(e, 0), d);
      }
    const auto r = kernels::solid::svd3(Ds * kernels::solid::inverse(Dm));
    for (int i = 0; i < 3; ++i) worst = std::max(worst, std::abs(r.s[i] - 1.0));
  }
  return worst;
}

TEST(TetSolid, InvertibleFemRecoversASquashedInvertedCube) {
  Solid s(unit_cube(3), options(0.25, 1.0));
  squash(s);
  EXPECT_NEAR(s.min_det_F(), -0.3, 1e-12);
  const double dt = s.stable_dt(0.4);
  double min_j = -1.0;
  for (int n = 0; n * dt < 20.0; ++n) {
    s.step(dt);
    ASSERT_EQ(s.first_nonfinite_node(), -1) << "step " << n;
    min_j = s.min_det_F();
  }
  EXPECT_GT(min_j, 0.99);
  EXPECT_LT(largest_strain(s), 0.01) << "the rest shape, up to a rigid motion, within 1 %";
}

TEST(TetSolid, StandardFemReportsTheInvertedCube) {
  Solid s(unit_cube(3), options(0.0, 1.0));
  squash(s);
  EXPECT_GE(s.first_nonfinite_node(), 0) << "log J < 0: the standard model cannot continue";
}

TetSolidOptions implicit_options(double damping) {
  TetSolidOptions o = options(0.25, damping);
  o.implicit = true;
  o.newton.tolerance = 1e-9;
  return o;
}

// Backward Euler is unconditionally stable and pulls the inverted cube back at a step far over
// the explicit limit; kinetic + elastic energy never grows (undamped, it dissipates).
TEST(TetSolid, BackwardEulerRecoversTheInvertedCubeFarOverTheExplicitLimit) {
  Solid s(unit_cube(3), implicit_options(0.0));
  squash(s);
  const double dt = 20.0 * s.stable_dt(1.0), e0 = s.kinetic_energy() + s.elastic_energy();
  double e = e0;
  int newton = 0;
  for (int n = 0; n < 60; ++n) {
    s.step(dt);
    ASSERT_TRUE(s.newton_report().converged) << "step " << n;
    newton += s.newton_report().iterations;
    const double e_new = s.kinetic_energy() + s.elastic_energy();
    EXPECT_LE(e_new, e * (1.0 + 1e-9)) << "step " << n;
    e = e_new;
  }
  std::printf(
      "backward Euler at 20x the explicit limit: %d Newton iterations in 60 steps, "
      "energy %.3e of the initial, min det F %.4f, largest strain %.2e\n",
      newton, e / e0, s.min_det_F(), largest_strain(s));
  EXPECT_GT(s.min_det_F(), 0.95);
  EXPECT_LT(largest_strain(s), 0.05);
}

/// Positions at T of the unit cube released from a 10 % stretch along x, stepped at dt.
std::vector<double> released_stretch(double dt, double T) {
  Solid s(unit_cube(2), implicit_options(0.0));
  set_state(
      s,
      [](const std::array<double, 3>& p) {
        return std::array<double, 3>{1.1 * p[0], p[1] + 0.05 * p[0] * p[2], p[2]};
      },
      [](const std::array<double, 3>&) {
        return std::array<double, 3>{0.0, 0.0, 0.0};
      });
  const int steps = static_cast<int>(std::lround(T / dt));
  for (int n = 0; n < steps; ++n) s.step(T / steps);
  auto x = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), s.positions());
  return std::vector<double>(x.data(), x.data() + x.size());
}

TEST(TetSolid, BackwardEulerIsFirstOrderInTime) {
  const double T = 0.5;
  const std::vector<double> ref = released_stretch(T / 4096, T);
  double err[3];
  for (int k = 0; k < 3; ++k) {
    const std::vector<double> x = released_stretch(T / (32 << k), T);
    err[k] = 0.0;
    for (size_t i = 0; i < x.size(); ++i) err[k] = std::max(err[k], std::abs(x[i] - ref[i]));
  }
  std::printf("backward Euler, largest position error at T/32, T/64, T/128: %.3e %.3e %.3e\n",
              err[0], err[1], err[2]);
  for (int k = 0; k < 2; ++k) {
    const double order = std::log2(err[k] / err[k + 1]);
    EXPECT_GT(order, 0.8) << err[k] << " -> " << err[k + 1];
    EXPECT_LT(order, 1.25) << err[k] << " -> " << err[k + 1];
  }
}

/// The static manufactured solution u = eps (phi, phi, phi), phi = sin(pi x) sin(pi y)
/// sin(pi z), on the unit cube (u = 0 on its faces) of n^3 cubes: the body force b = -div
/// sigma(u) of linear elasticity (mu = 1, lambda = 2, small strain) as nodal loads b(X_i) V_i,
/// the boundary pinned, one backward-Euler step with dt = 1e8 (static). Returns the discrete
/// L2 error of the displacement relative to the solution's.
double manufactured_error(int n) {
  constexpr double pi = 3.14159265358979323846, eps = 1e-4, mu = 1.0, lambda = 2.0;
  TetSolidOptions o = implicit_options(0.0);
  o.newton.tolerance = 1e-10;
  Solid s(unit_cube(n), o);
  auto X = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), s.rest_positions());
  auto m = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), s.masses());  // = V_i
  auto pinned = Kokkos::create_mirror(s.pinned());
  Solid::Nodes loads("loads", s.n_nodes());
  auto f = Kokkos::create_mirror(loads);
  auto u_exact = [&](int i) {
    return eps * std::sin(pi * X(i, 0)) * std::sin(pi * X(i, 1)) * std::sin(pi * X(i, 2));
  };
  for (int i = 0; i < s.n_nodes(); ++i) {
    bool boundary = false;
    double sn[3], cs[3];
    for (int d = 0; d < 3; ++d) {
      boundary = boundary || X(i, d) < 1e-12 || X(i, d) > 1.0 - 1e-12;
      sn[d] = std::sin(pi * X(i, d)), cs[d] = std::cos(pi * X(i, d));
    }
    pinned(i) = boundary;
    // div sigma_a = mu lap u_a + (mu + lambda) d_a (div u), with u_b = eps phi for every b.
    for (int a = 0; a < 3; ++a) {
      double grad_div = 0.0;  // sum_b d_a d_b phi
      for (int b = 0; b < 3; ++b) {
        double term = pi * pi;
        for (int d = 0; d < 3; ++d)
          term *= (d == a) == (d == b) ? (d == a ? -sn[d] : sn[d]) : cs[d];
        grad_div += term;
      }
      const double phi = sn[0] * sn[1] * sn[2];
      f(i, a) = -eps * (mu * (-3.0 * pi * pi * phi) + (mu + lambda) * grad_div) * m(i);
    }
  }
  Kokkos::deep_copy(s.pinned(), pinned);
  Kokkos::deep_copy(loads, f);
  s.set_external_forces(loads);
  s.step(1e8);
  EXPECT_TRUE(s.newton_report().converged);
  auto x = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), s.positions());
  double err = 0.0, norm = 0.0;
  for (int i = 0; i < s.n_nodes(); ++i)
    for (int d = 0; d < 3; ++d) {
      const double e = x(i, d) - X(i, d) - u_exact(i);
      err += m(i) * e * e, norm += m(i) * u_exact(i) * u_exact(i);
    }
  return std::sqrt(err / norm);
}

// Linear tetrahedra converge at order 2 in L2 (the elastic operator, static).
TEST(TetSolid, ManufacturedStaticSolutionConvergesAtOrderTwo) {
  const double e4 = manufactured_error(4), e8 = manufactured_error(8), e16 = manufactured_error(16);
  std::printf(
      "manufactured solution, relative L2 displacement error at 4, 8, 16 cells: %.3e "
      "%.3e %.3e\n",
      e4, e8, e16);
  for (double order : {std::log2(e4 / e8), std::log2(e8 / e16)}) {
    EXPECT_GT(order, 1.8);
    EXPECT_LT(order, 2.3);
  }
}

std::string error_of(const mesh::tet::TetMesh& m, const TetSolidOptions& o) {
  try {
    Solid s(m, o);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(TetSolid, BadInputIsRefusedWithOneClearLine) {
  auto m = unit_cube(2);
  std::swap(m.tets[5][1], m.tets[5][2]);  // inverted
  m.nodes.push_back(m.nodes[0]);
  m.tets[7][3] = m.n_nodes() - 1;  // node 0 twice: degenerate
  m.tets[7][0] = 0;
  EXPECT_EQ(error_of(m, options(0.25, 0.0)),
            "solid_fem: 2 inverted or degenerate rest element(s): 5 7");
  EXPECT_THROW(physics::solid_fem::material_from_young_poisson(Hyperelastic::neo_hookean, 1e6, 0.5),
               std::invalid_argument);
  const auto good =
      physics::solid_fem::material_from_young_poisson(Hyperelastic::corotated, 1e6, 0.3);
  EXPECT_NEAR(good.mu, 1e6 / 2.6, 1e-6);
  Solid s(unit_cube(2), options(0.25, 0.0));
  EXPECT_NO_THROW(s.check_time_step(s.stable_dt(1.0)));
  EXPECT_THROW(s.check_time_step(1.01 * s.stable_dt(1.0)), std::invalid_argument);
}

}  // namespace test_tet_solid_cases
}  // namespace amphora
