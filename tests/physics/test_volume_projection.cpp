#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "kernels/solid/node_volumes.hpp"
#include "kernels/solid/volume_gradient_matrix.hpp"
#include "mesh/tet/shape_meshes.hpp"
#include "physics/solid_fem/tet_solid.hpp"
#include "physics/solid_fem/volume_projection.hpp"
#include "test_backend.hpp"

namespace amphora {
// A named namespace, not an anonymous one: CUDA does not support extended lambdas in
// anonymous namespaces (Kokkos issue #1547).
namespace test_volume_projection_cases {

using physics::solid_fem::Hyperelastic;
using physics::solid_fem::Material;
using physics::solid_fem::TetSolid;
using physics::solid_fem::TetSolidOptions;
using physics::solid_fem::VolumeOptions;
using physics::solid_fem::VolumeProjection;
using physics::solid_fem::VolumeReport;
using test::TestExecSpace;
using Mem = test::TestMemSpace;
using Nodes = Kokkos::View<double* [3], Mem>;
using Scalars = Kokkos::View<double*, Mem>;

/// A ball of radius 1 (cells across its diameter) on the device, with its positions jiggled
/// by `amplitude` times the mean edge length (a fixed seed).
struct Ball {
  explicit Ball(int cells, double amplitude = 0.0, unsigned seed = 7) {
    mesh = mesh::tet::ball_tet_mesh(1.0, cells);
    auto v = mesh::tet::to_views<Mem>(mesh);
    tets = v.tets, X = v.nodes;
    x = Nodes("x", mesh.n_nodes());
    auto h = Kokkos::create_mirror(X);  // a copy even on the host: X stays the rest state
    Kokkos::deep_copy(h, X);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const double edge = 2.0 / cells;
    for (int i = 0; i < mesh.n_nodes(); ++i)
      for (int d = 0; d < 3; ++d) h(i, d) += amplitude * edge * u(rng);
    Kokkos::deep_copy(x, h);
  }
  int n() const { return mesh.n_nodes(); }
  mesh::tet::TetMesh mesh;
  Kokkos::View<int* [4], Mem> tets;
  Nodes X, x;
};

Nodes random_nodes(int n, unsigned seed) {
  Nodes a("a", n);
  auto h = Kokkos::create_mirror(a);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d) h(i, d) = u(rng);
  Kokkos::deep_copy(a, h);
  return a;
}

/// The one-ring volumes at x, on the host.
std::vector<double> ring_volumes(const Ball& b, const Nodes& x) {
  Scalars vol("vol", b.mesh.n_tets()), V("V", b.n());
  Kokkos::View<double* [4][3], Mem> grad("grad", b.mesh.n_tets());
  TestExecSpace exec;
  kernels::solid::tet_volume_gradients(exec, b.tets, x, vol, grad);
  kernels::solid::node_volumes(exec, b.tets, vol, V);
  auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), V);
  return std::vector<double>(h.data(), h.data() + h.extent(0));
}

TEST(NodeVolumes, AddUpToTheVolumeAndTheirGradientMatchesFiniteDifferences) {
  const Ball b(4, 0.1);
  TestExecSpace exec;
  const int n = b.n(), m = b.mesh.n_tets();
  Scalars vol("vol", m), Bu("Bu", n), p("p", n);
  Kokkos::View<double* [4][3], Mem> grad("grad", m);
  kernels::solid::tet_volume_gradients(exec, b.tets, b.x, vol, grad);
  const std::vector<double> V = ring_volumes(b, b.x);
  double total = 0.0, rest = 0.0;
  for (double v : V) total += v;
  auto xh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), b.x);
  mesh::tet::TetMesh moved = b.mesh;
  for (int i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d) moved.nodes[i][d] = xh(i, d);
  for (int t = 0; t < m; ++t) rest += mesh::tet::tet_volume(moved, t);
  EXPECT_NEAR(total, rest, 1e-13 * rest);

  // B u against the central difference of V(x + h u); V is cubic in x, so the difference is
  // exact but for the h^2 term and round-off.
  const Nodes u = random_nodes(n, 3);
  kernels::solid::volume_gradient_apply(exec, b.tets, grad, u, Bu);
  const double h = 1e-5;
  Nodes xp("xp", n), xm("xm", n);
  auto up = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), u);
  auto hp = Kokkos::create_mirror(xp), hm = Kokkos::create_mirror(xm);
  for (int i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d)
      hp(i, d) = xh(i, d) + h * up(i, d), hm(i, d) = xh(i, d) - h * up(i, d);
  Kokkos::deep_copy(xp, hp);
  Kokkos::deep_copy(xm, hm);
  const std::vector<double> Vp = ring_volumes(b, xp), Vm = ring_volumes(b, xm);
  auto Buh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), Bu);
  double worst = 0.0, scale = 0.0;
  for (int i = 0; i < n; ++i) {
    worst = std::max(worst, std::abs(Buh(i) - (Vp[i] - Vm[i]) / (2.0 * h)));
    scale = std::max(scale, std::abs(Buh(i)));
  }
  EXPECT_LT(worst, 1e-8 * scale);

  // B^T is B's adjoint: p . (B u) = (B^T p) . u.
  auto ph = Kokkos::create_mirror(p);
  for (int i = 0; i < n; ++i) ph(i) = std::sin(1.0 + i);
  Kokkos::deep_copy(p, ph);
  Nodes BTp("BTp", n);
  kernels::solid::volume_gradient_transpose_apply(exec, b.tets, grad, p, BTp);
  auto BTph = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), BTp);
  double left = 0.0, right = 0.0, size = 0.0;
  for (int i = 0; i < n; ++i) {
    left += ph(i) * Buh(i), size += std::abs(ph(i) * Buh(i));
    for (int d = 0; d < 3; ++d) right += BTph(i, d) * up(i, d);
  }
  EXPECT_NEAR(left, right, 1e-13 * size);
}

TEST(NodeVolumes, TheAssembledGradientMatchesTheElementWiseOne) {
  const Ball b(4, 0.1);
  TestExecSpace exec;
  const int n = b.n(), m = b.mesh.n_tets();
  Scalars vol("vol", m), Bu("Bu", n), Mu("Mu", n), p("p", n), w("w", n), D("D", n);
  Kokkos::View<double* [4][3], Mem> grad("grad", m);
  kernels::solid::tet_volume_gradients(exec, b.tets, b.x, vol, grad);
  auto B = kernels::solid::volume_gradient_graph(b.tets, n);
  kernels::solid::assemble_volume_gradient(exec, grad, B);
  const Nodes u = random_nodes(n, 9), BTp("BTp", n), MTp("MTp", n), none("normal", n);
  kernels::solid::volume_gradient_apply(exec, b.tets, grad, u, Bu);
  kernels::solid::volume_gradient_matrix_apply(exec, B, u, Mu);
  auto ph = Kokkos::create_mirror(p);
  for (int i = 0; i < n; ++i) ph(i) = std::cos(0.3 * i);
  Kokkos::deep_copy(p, ph);
  Kokkos::deep_copy(w, 1.0);
  kernels::solid::volume_gradient_transpose_apply(exec, b.tets, grad, p, BTp);
  kernels::solid::volume_gradient_transpose_weighted(exec, B, w, none, p, MTp);
  auto bu = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), Bu);
  auto mu = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), Mu);
  auto bt = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), BTp);
  auto mt = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), MTp);
  double scale = 0.0, tscale = 0.0;
  for (int i = 0; i < n; ++i) {
    scale = std::max(scale, std::abs(bu(i)));
    for (int d = 0; d < 3; ++d) tscale = std::max(tscale, std::abs(bt(i, d)));
  }
  for (int i = 0; i < n; ++i) {
    EXPECT_NEAR(mu(i), bu(i), 1e-13 * scale) << "node " << i;
    for (int d = 0; d < 3; ++d) EXPECT_NEAR(mt(i, d), bt(i, d), 1e-13 * tscale) << "node " << i;
  }
  // The diagonal of B B^T (W = I) against e_i . B B^T e_i for a few nodes.
  kernels::solid::volume_operator_diagonal(exec, B, w, none, D);
  auto Dh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), D);
  for (int i : {0, n / 3, n - 1}) {
    for (int k = 0; k < n; ++k) ph(k) = k == i;
    Kokkos::deep_copy(p, ph);
    kernels::solid::volume_gradient_transpose_apply(exec, b.tets, grad, p, BTp);
    kernels::solid::volume_gradient_apply(exec, b.tets, grad, BTp, Bu);
    Kokkos::deep_copy(bu, Bu);
    EXPECT_NEAR(Dh(i), bu(i), 1e-12 * bu(i)) << "node " << i;
  }
}

/// Unit masses, no pins (but the nodes with x < -0.6 where `pin`), no planes.
struct FreeBody {
  FreeBody(const Ball& b, bool pin) : mass("mass", b.n()), pinned("pinned", b.n()) {
    Kokkos::deep_copy(mass, 1.0);
    auto X = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), b.X);
    auto ph = Kokkos::create_mirror(pinned);
    for (int i = 0; i < b.n(); ++i) ph(i) = pin && X(i, 0) < -0.6;
    Kokkos::deep_copy(pinned, ph);
  }
  Scalars mass;
  Kokkos::View<char*, Mem> pinned;
};

TEST(VolumeProjection, PositionCorrectionReachesTheToleranceInFewNewtonSteps) {
  Ball b(4, 0.05);
  const FreeBody body(b, true);
  auto before = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), b.x);
  VolumeOptions o;
  o.tolerance = 1e-10;
  VolumeProjection<TestExecSpace> proj(b.tets, b.X, o);
  proj.set_weights(body.mass, body.pinned, {}, b.x, b.x, 0.0);
  const VolumeReport r = proj.correct_positions(b.x);
  std::printf("per-node volume error %.2e -> %.2e in %d corrections, %d CR iterations\n",
              r.error_before, r.error, r.corrections, r.cr_iterations);
  EXPECT_GT(r.error_before, 1e-2);
  EXPECT_TRUE(r.converged);
  EXPECT_LE(r.error, o.tolerance);
  EXPECT_LE(r.corrections, 4);  // Newton: quadratic once close
  auto after = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), b.x);
  auto pinned = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), body.pinned);
  int held = 0;
  for (int i = 0; i < b.n(); ++i)
    if (pinned(i)) {
      ++held;
      for (int d = 0; d < 3; ++d) EXPECT_EQ(after(i, d), before(i, d));
    }
  EXPECT_GT(held, 0);
}

TEST(VolumeProjection, ProjectedVelocitiesKeepEveryNodeVolumeAndLoseEnergy) {
  Ball b(4, 0.05);
  const FreeBody body(b, false);
  VolumeOptions o;
  o.cr_tolerance = 1e-10;
  VolumeProjection<TestExecSpace> proj(b.tets, b.X, o);
  proj.set_weights(body.mass, body.pinned, {}, b.x, b.x, 0.0);
  VolumeReport r = proj.correct_positions(b.x);
  const Nodes v = random_nodes(b.n(), 5);
  auto v0 = Kokkos::create_mirror(v);  // a copy even on the host
  Kokkos::deep_copy(v0, v);
  proj.project_velocities(b.x, v, r);
  auto v1 = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), v);
  double e0 = 0.0, e1 = 0.0;
  for (int i = 0; i < b.n(); ++i)
    for (int d = 0; d < 3; ++d) e0 += v0(i, d) * v0(i, d), e1 += v1(i, d) * v1(i, d);
  std::printf("velocity projection: max |B v|_i / V_0i = %.2e, |v|^2 %.3f -> %.3f\n", r.rate, e0,
              e1);
  EXPECT_TRUE(r.converged);
  EXPECT_LT(r.rate, 1e-7);  // the random field's own rate is O(1) per unit volume
  EXPECT_LT(e1, e0);        // an M-orthogonal projection
  // A rigid motion is divergence-free: the projection leaves it (to the solver's tolerance).
  auto x = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), b.x);
  for (int i = 0; i < b.n(); ++i) {
    v0(i, 0) = 1.0 - x(i, 1), v0(i, 1) = 0.5 + x(i, 0), v0(i, 2) = -2.0;
  }
  Kokkos::deep_copy(v, v0);
  proj.project_velocities(b.x, v, r);
  Kokkos::deep_copy(v1, v);
  for (int i = 0; i < b.n(); ++i)
    for (int d = 0; d < 3; ++d) EXPECT_NEAR(v1(i, d), v0(i, d), 1e-9);
}

TEST(VolumeProjection, NodesOnAPlaneSlideAlongIt) {
  // A unit cube on the ground z = 0, its nodes jiggled (those on the ground along it only).
  const mesh::tet::TetMesh cube = mesh::tet::box_tet_mesh({4, 4, 4}, {0, 0, 0}, {1, 1, 1});
  const auto views = mesh::tet::to_views<Mem>(cube);
  const int n = cube.n_nodes();
  Nodes x("x", n);
  auto h = Kokkos::create_mirror(x);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-0.02, 0.02);
  for (int i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d)
      h(i, d) = cube.nodes[i][d] + (d == 2 && cube.nodes[i][2] == 0.0 ? 0.0 : u(rng));
  Kokkos::deep_copy(x, h);
  Scalars mass("mass", n);
  Kokkos::deep_copy(mass, 1.0);
  Kokkos::View<char*, Mem> pinned("pinned", n);
  kernels::solid::BoundingPlanes ground;
  ground.d = 0.0;
  VolumeOptions o;
  o.contact_gap = 1e-12;
  VolumeProjection<TestExecSpace> proj(views.tets, views.nodes, o);
  proj.set_weights(mass, pinned, ground, x, x, 0.0);
  const VolumeReport r = proj.correct_positions(x);
  EXPECT_TRUE(r.converged);
  EXPECT_LE(r.error, o.tolerance);
  auto after = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), x);
  int on = 0, slid = 0;
  for (int i = 0; i < n; ++i)
    if (cube.nodes[i][2] == 0.0) {
      ++on;
      EXPECT_EQ(after(i, 2), 0.0) << "node " << i;
      slid += after(i, 0) != h(i, 0) || after(i, 1) != h(i, 1);
    }
  EXPECT_EQ(on, 25);
  EXPECT_GT(slid, 0);
}

/// Explicit steps of a ball squeezed along z between plates to 60 % of its height at 1 m/s
/// and released: the largest |V / V_0 - 1| over the run, and the largest per-node error
/// after any step's correction.
struct SqueezeResult {
  double volume_drift = 0.0, node_error = 0.0;
  bool converged = true;
};
SqueezeResult squeeze(bool preserve) {
  TetSolidOptions o;
  o.material =
      physics::solid_fem::material_from_young_poisson(Hyperelastic::neo_hookean, 1e5, 0.3, 0.25);
  o.density = 1000.0;
  o.volume_preserving = preserve;
  const double r = 0.05;
  TetSolid<TestExecSpace> s(mesh::tet::ball_tet_mesh(r, 4), o);
  const double dt = s.stable_dt(0.5), speed = 1.0, t1 = 0.4 * r / speed;
  SqueezeResult out;
  for (double t = 0.0; t < 3.0 * t1; t += dt) {
    kernels::solid::BoundingPlanes p;
    const double end = t + dt;
    if (end < 2.0 * t1) {
      const double half = r - speed * (end <= t1 ? end : 2.0 * t1 - end);
      const double v = t + 0.5 * dt < t1 ? speed : -speed;
      p.lo = -half, p.v_lo = v, p.hi = half, p.v_hi = -v;
    }
    s.set_plates(p);
    s.step(dt);
    out.volume_drift = std::max(out.volume_drift, std::abs(s.volume() / s.rest_volume() - 1.0));
    if (preserve) {
      out.node_error = std::max(out.node_error, s.volume_report().error);
      out.converged = out.converged && s.volume_report().converged;
    }
  }
  return out;
}

TEST(VolumeProjection, SqueezedBallKeepsItsVolume) {
  const SqueezeResult with = squeeze(true), without = squeeze(false);
  std::printf(
      "squeeze to 60 %% and release: volume drift %.2e with the projection (per node "
      "%.2e), %.2e without\n",
      with.volume_drift, with.node_error, without.volume_drift);
  EXPECT_TRUE(with.converged);
  EXPECT_LE(with.node_error, VolumeOptions{}.tolerance);
  EXPECT_LT(with.volume_drift, 1e-3);
  EXPECT_GT(without.volume_drift, 1e-2);  // the compressible model alone loses volume
}

TEST(VolumeProjection, RecoveryTimeDecaysTheErrorExponentially) {
  // A ball squashed to 90 % along z (a 10 % volume error) at rest, the error recovered over
  // tau by the velocity projection alone: it decays as (1 - dt/tau)^n ~ exp(-t/tau).
  TetSolidOptions o;
  o.material =
      physics::solid_fem::material_from_young_poisson(Hyperelastic::neo_hookean, 1e5, 0.3, 0.25);
  o.density = 1000.0;
  o.volume_preserving = true;
  o.volume.recovery_time = 2e-3;
  TetSolid<TestExecSpace> s(mesh::tet::ball_tet_mesh(0.05, 4), o);
  auto x = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), s.positions());
  for (size_t i = 0; i < x.extent(0); ++i) x(i, 2) *= 0.9;
  Kokkos::deep_copy(s.positions(), x);
  s.update_forces();
  const double e0 = s.volume() / s.rest_volume() - 1.0, dt = s.stable_dt(0.5);
  const int steps = static_cast<int>(std::lround(2.0 * o.volume.recovery_time / dt));
  for (int n = 0; n < steps; ++n) s.step(dt);
  const double e1 = s.volume() / s.rest_volume() - 1.0;
  const double expected = std::pow(1.0 - dt / o.volume.recovery_time, steps) * e0;
  std::printf("volume error %.4f -> %.5f after %d steps (expected %.5f)\n", e0, e1, steps,
              expected);
  EXPECT_NEAR(e1, expected, 0.03 * std::abs(expected));  // second-order terms of the drift
}

}  // namespace test_volume_projection_cases
}  // namespace amphora
