#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Dense>

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

/// The body's stretches up to a rigid motion: the square roots of the eigenvalues of its
/// nodes' second moment about their mean over those of the rest positions (a cube: equal),
/// ascending. A uniform deformation F of the cube gives F's singular values.
std::array<double, 3> stretches(const Solid& s) {
  auto moments = [](const auto& x) {
    const double n = double(x.extent(0));
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (size_t i = 0; i < x.extent(0); ++i) c += Eigen::Vector3d(x(i, 0), x(i, 1), x(i, 2)) / n;
    Eigen::Matrix3d C = Eigen::Matrix3d::Zero();
    for (size_t i = 0; i < x.extent(0); ++i) {
      const Eigen::Vector3d d = Eigen::Vector3d(x(i, 0), x(i, 1), x(i, 2)) - c;
      C += d * d.transpose() / n;
    }
    return Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(C).eigenvalues();
  };
  const Eigen::Vector3d m =
      moments(Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), s.positions()));
  const Eigen::Vector3d m0 =
      moments(Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), s.rest_positions()));
  return {std::sqrt(m[0] / m0[0]), std::sqrt(m[1] / m0[1]), std::sqrt(m[2] / m0[2])};
}

// A cube stretched uniformly by F = diag(a, a^-1/2, a^-1/2) and released: with yield strain
// y, the first flow leaves F_e on the yield surface and F_p = F^g, g = 1 - y / |dev log F|
// (kernels/solid/plastic_flow.hpp); the cube then relaxes elastically (damped, within the
// yield) to its new rest shape F_p: lengths a^g and a^-g/2, stress free, volume kept.
TEST(TetSolid, PlasticCubeKeepsThePredictedPermanentStretch) {
  const double a = 1.4, y = 0.1;
  TetSolidOptions o = options(0.25, 1.0);
  o.plastic.yield = y;
  Solid s(unit_cube(3), o);
  set_state(
      s,
      [&](const std::array<double, 3>& p) {
        return std::array<double, 3>{a * p[0], p[1] / std::sqrt(a), p[2] / std::sqrt(a)};
      },
      [](const std::array<double, 3>&) {
        return std::array<double, 3>{0.0, 0.0, 0.0};
      });
  const double e0 = s.elastic_energy();
  const double dt = s.stable_dt(0.4);
  for (int n = 0; n * dt < 30.0; ++n) s.step(dt);
  const double g = 1.0 - y / (std::log(a) * std::sqrt(1.5));
  const double Lx = std::pow(a, g), Ly = std::pow(a, -0.5 * g);
  const std::array<double, 3> l = stretches(s);
  std::printf(
      "plastic cube: stretches %.6f %.6f %.6f (predicted %.6f %.6f), elastic energy "
      "%.3g of %.3g, max plastic strain %.6f\n",
      l[0], l[1], l[2], Ly, Lx, s.elastic_energy(), e0, s.max_plastic_strain());
  EXPECT_NEAR(l[0], Ly, 2e-3 * Ly);
  EXPECT_NEAR(l[1], Ly, 2e-3 * Ly);
  EXPECT_NEAR(l[2], Lx, 2e-3 * Lx);
  EXPECT_LT(s.elastic_energy(), 1e-4 * e0) << "stress free in its new shape";
  EXPECT_NEAR(s.volume() / s.rest_volume(), 1.0, 1e-3);
  EXPECT_NEAR(s.max_plastic_strain(), std::log(a) * std::sqrt(1.5) - y, 2e-3);
}

/// Positions F X + c and velocities L X + w (a uniform deformation and velocity gradient).
void set_affine(Solid& s, const double F[3][3], const double L[3][3]) {
  set_state(
      s,
      [&](const std::array<double, 3>& p) {
        std::array<double, 3> x{0.1, -0.2, 0.3};
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j) x[i] += F[i][j] * p[j];
        return x;
      },
      [&](const std::array<double, 3>& p) {
        std::array<double, 3> v{0.5, 0.2, -0.1};
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j) v[i] += L[i][j] * p[j];
        return v;
      });
}

/// The Kelvin-Voigt forces alone (viscosity eta, mu tiny) at the state: f - f_elastic.
std::vector<double> damping_forces(double eta, const double F[3][3], const double L[3][3],
                                   double* power) {
  TetSolidOptions o = options(0.25, 0.0);
  Solid elastic(unit_cube(2), o);
  o.viscosity = eta;
  Solid viscous(unit_cube(2), o);
  set_affine(elastic, F, L);
  set_affine(viscous, F, L);
  viscous.update_forces();
  elastic.update_forces();
  auto fe = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), elastic.forces());
  auto fv = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), viscous.forces());
  auto v = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), viscous.velocities());
  std::vector<double> f;
  *power = 0.0;
  for (size_t i = 0; i < fv.extent(0); ++i)
    for (int d = 0; d < 3; ++d) {
      f.push_back(fv(i, d) - fe(i, d));
      *power += f.back() * v(i, d);
    }
  return f;
}

// Kelvin-Voigt damping: no force on a rigid motion (L = W F with W skew), and for a uniform
// velocity gradient the power of the forces is minus the dissipation eta/2 |dC/dt|^2 times
// the volume (dC/dt = dF^T F + F^T dF, dF = L F... here L is the gradient in the rest frame).
TEST(TetSolid, KelvinVoigtSparesRigidMotionAndDissipatesItsRate) {
  const double F[3][3] = {{1.2, 0.1, 0.0}, {-0.05, 0.9, 0.2}, {0.1, 0.0, 1.1}};
  const double W[3][3] = {{0.0, -0.7, 0.3}, {0.7, 0.0, -0.4}, {-0.3, 0.4, 0.0}};
  double L[3][3] = {};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) L[i][j] += W[i][k] * F[k][j];  // rigid: dF = W F
  double power = 0.0;
  const double eta = 0.3;
  for (double f : damping_forces(eta, F, L, &power)) EXPECT_NEAR(f, 0.0, 1e-14);
  const double G[3][3] = {{0.2, -0.1, 0.3}, {0.05, -0.3, 0.1}, {0.2, 0.4, 0.1}};
  damping_forces(eta, F, G, &power);
  double Cdot = 0.0;  // |dF^T F + F^T dF|^2 with dF = G
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double c = 0.0;
      for (int k = 0; k < 3; ++k) c += G[k][i] * F[k][j] + F[k][i] * G[k][j];
      Cdot += c * c;
    }
  EXPECT_NEAR(power, -0.5 * eta * Cdot, 1e-12 * eta * Cdot) << "unit cube: volume 1";
}

/// The angular momentum about the centre of mass.
std::array<double, 3> angular_momentum(const Solid& s) {
  auto x = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), s.positions());
  auto v = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), s.velocities());
  auto m = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), s.masses());
  std::array<double, 3> c{0, 0, 0}, L{0, 0, 0};
  double M = 0.0;
  for (size_t i = 0; i < x.extent(0); ++i) {
    M += m(i);
    for (int d = 0; d < 3; ++d) c[d] += m(i) * x(i, d);
  }
  for (int d = 0; d < 3; ++d) c[d] /= M;
  for (size_t i = 0; i < x.extent(0); ++i) {
    const double r[3] = {x(i, 0) - c[0], x(i, 1) - c[1], x(i, 2) - c[2]};
    L[0] += m(i) * (r[1] * v(i, 2) - r[2] * v(i, 1));
    L[1] += m(i) * (r[2] * v(i, 0) - r[0] * v(i, 2));
    L[2] += m(i) * (r[0] * v(i, 1) - r[1] * v(i, 0));
  }
  return L;
}

// A spinning, vibrating cube: Kelvin-Voigt damps the vibration (the elastic energy settles to
// the spin's steady stretch: its swing over the last time unit falls below 1 % of its mean,
// against more than 10 % undamped) and keeps the spin (angular momentum to round-off), where
// mass damping also stops the spin.
TEST(TetSolid, KelvinVoigtDampsVibrationNotSpin) {
  struct Result {
    double L0, L, swing;
  };
  auto run = [](double eta, double alpha) {
    TetSolidOptions o = options(0.25, alpha);
    o.viscosity = eta;
    Solid s(unit_cube(3), o);
    set_state(
        s,
        [](const std::array<double, 3>& p) {
          return std::array<double, 3>{1.1 * p[0], p[1], 0.95 * p[2]};
        },
        [](const std::array<double, 3>& p) {
          return std::array<double, 3>{-(p[1] - 0.5), p[0] - 0.55, 0.0};
        });
    Result r{angular_momentum(s)[2], 0.0, 0.0};
    const double dt = s.stable_dt(0.4), T = 10.0;
    double lo = 1e300, hi = 0.0, sum = 0.0;
    int count = 0;
    for (int n = 0; n * dt < T; ++n) {
      s.step(dt);
      if (n * dt < T - 1.0) continue;
      const double e = s.elastic_energy();
      lo = std::min(lo, e), hi = std::max(hi, e), sum += e, ++count;
    }
    r.L = angular_momentum(s)[2];
    r.swing = (hi - lo) / (sum / count);
    return r;
  };
  const Result kv = run(0.2, 0.0), none = run(0.0, 0.0), md = run(0.0, 0.3);
  std::printf(
      "spin L_z %.12g; Kelvin-Voigt: L_z %.12g, elastic energy swing %.3g; undamped: "
      "swing %.3g; mass damping: L_z %.6g\n",
      kv.L0, kv.L, kv.swing, none.swing, md.L);
  EXPECT_NEAR(kv.L, kv.L0, 1e-10 * std::abs(kv.L0)) << "spin kept";
  EXPECT_LT(kv.swing, 0.01) << "vibration damped";
  EXPECT_GT(none.swing, 0.1) << "undamped, it vibrates";
  EXPECT_LT(md.L, 0.1 * md.L0) << "mass damping stops the spin too";
}

/// How far the centroid of a stiff cube set on a ramp of angle theta at rest has slid down
/// it after T (Coulomb friction mu; Kelvin-Voigt damping settles the landing's vibration).
double slide(double mu, double theta, double T) {
  TetSolidOptions o;
  o.material = Material{Hyperelastic::neo_hookean, 1e4, 2e4, 0.25};
  o.gravity[2] = -9.81;
  o.viscosity = 20.0;
  o.floor = 0.0;
  o.floor_tilt = theta;
  o.friction = mu;
  Solid s(unit_cube(3), o);
  const double c = std::cos(theta), sn = std::sin(theta);
  set_state(
      s,
      [&](const std::array<double, 3>& p) {  // rotated about y: the bottom face on the ramp
        return std::array<double, 3>{c * p[0] + sn * p[2], p[1], -sn * p[0] + c * p[2]};
      },
      [](const std::array<double, 3>&) {
        return std::array<double, 3>{0.0, 0.0, 0.0};
      });
  auto centroid_along = [&]() {
    auto x = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), s.positions());
    double sum = 0.0;
    for (size_t i = 0; i < x.extent(0); ++i) sum += c * x(i, 0) - sn * x(i, 2);
    return sum / double(x.extent(0));
  };
  const double start = centroid_along();
  const double dt = s.stable_dt(0.4);
  for (int n = 0; n * dt < T; ++n) s.step(dt);
  return centroid_along() - start;
}

// Coulomb friction on a ramp of 25 degrees (tan = 0.466): a cube slides with acceleration
// g (sin - mu cos) for mu = 0 and 0.3 (measured as the second difference of the distance at
// 0.5, 0.75 and 1 s, which leaves out the landing's transient) and stays for mu = 0.6.
TEST(TetSolid, FrictionOnARampSlidesAsCoulombSays) {
  const double theta = 25.0 * 3.14159265358979323846 / 180.0, g = 9.81;
  for (const double mu : {0.0, 0.3, 0.6}) {
    const double a = std::max(0.0, g * (std::sin(theta) - mu * std::cos(theta)));
    const double d1 = slide(mu, theta, 0.5), d2 = slide(mu, theta, 0.75),
                 d3 = slide(mu, theta, 1.0);
    const double measured = (d3 - 2.0 * d2 + d1) / (0.25 * 0.25);
    std::printf("mu %.1f: acceleration %.6f m/s^2, Coulomb %.6f; slid %.6f m by t = 1\n", mu,
                measured, a, d3);
    if (a > 0.0) {
      EXPECT_NEAR(measured, a, 0.005 * a) << "mu " << mu;
    } else {
      EXPECT_LT(std::abs(d3 - d1), 1e-6) << "stuck";
      EXPECT_LT(std::abs(d3), 1e-3) << "the elastic shear only";
    }
  }
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
  TetSolidOptions o = options(0.25, 0.0);
  o.viscosity = 1.0;
  o.implicit = true;
  EXPECT_EQ(error_of(unit_cube(2), o),
            "solid_fem: viscosity (Kelvin-Voigt damping) needs the explicit integrator; use "
            "damping (mass-proportional) with backward_euler");
  o.implicit = false;
  o.plastic.yield = 0.1;
  o.plastic.clamp = 1.0;
  EXPECT_EQ(error_of(unit_cube(2), o), "solid_fem: the plastic clamp must be > 1");
}

}  // namespace test_tet_solid_cases
}  // namespace amphora
