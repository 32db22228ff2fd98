// The self-induced velocity's table (coupling/cfd_dem/self_induced_velocity.hpp): the Oseen
// factor's limits, and the discrete Stokes response it builds from one load at a node against
// a direct solve of a force spread from a point inside a cell.
#include <cmath>
#include <cstdio>
#include <vector>

#include "coupling/cfd_dem/particle_mesh.hpp"
#include "coupling/cfd_dem/self_induced_velocity.hpp"
#include "coupling/cfd_dem/void_fraction.hpp"
#include "test_backend.hpp"

namespace amphora::coupling::cfd_dem {
namespace test_cfd_dem_self_induced {

using Exec = test::TestExecSpace;
using Flow = physics::ins_fem::InsSolver<3, Exec>;

/// S -> 1 as Re -> 0 (the Stokes response) and S -> 3 pi / (4 sqrt(pi / 2) Re) as Re -> oo
/// (I(a) -> pi / a), monotone between.
TEST(CfdDemSelfInduced, OseenFactorLimits) {
  EXPECT_NEAR(oseen_screening(1e-5), 1.0, 1e-4);
  const double far = 3.0 * M_PI / (4.0 * std::sqrt(M_PI / 2.0));
  EXPECT_NEAR(oseen_screening(1e4) * 1e4 / far, 1.0, 1e-3);
  double last = 1.0;
  for (double re = 1e-2; re < 1e4; re *= 2.0) {
    const double s = oseen_screening(re);
    EXPECT_LT(s, last) << "Re " << re;
    last = s;
  }
}

mesh::hex::StructuredHexMesh<3> walled_box(int cells, double h) {
  mesh::hex::StructuredHexMesh<3> m;
  m.cells = {cells, cells, cells};
  m.upper = {cells * h, 1.5 * cells * h, 0.75 * cells * h};  // cells h, 1.5 h, 0.75 h
  return m;
}

/// A force spread from a point inside a cell near the centre of a walled box, the steady
/// Stokes velocity read back there, against W F / rho from the response of the same box to
/// loads at its centre node: the same within the walls' variation over a cell. Cells of three
/// widths, so that the three directions' solves are all used.
TEST(CfdDemSelfInduced, TableMatchesADirectSolve) {
  const int cells = 16;
  const double h = 2e-4, nu = 1e-6;
  const auto m = walled_box(cells, h);
  physics::ins_fem::InsOptions o;
  o.model = physics::ins_fem::FlowModel::vans_a;
  o.nu = nu;
  o.tolerance = 1e-12;
  Flow flow(m, 1, o);
  const VoidFraction<3, Exec> vf(flow.space(), VoidFractionOptions{});
  SelfInducedVelocity t;
  t.basis = vf.basis();
  t.nu = nu;
  walled_box_response<Exec>(t.basis.h, nu, cells, t.g);

  const double x[3] = {(cells / 2 + 0.3) * h, (cells / 2 - 0.6) * 1.5 * h,
                       (cells / 2 + 0.15) * 0.75 * h};
  const double f[3] = {1.0, -0.5, 0.3};
  const double scale = 1e-6 * nu * h;  // a load whose advection is nil
  const long n = flow.n_dofs();
  Kokkos::View<double*[3], Kokkos::LayoutRight, Exec::memory_space> px("x", 1), pf("f", 1),
      pu("u", 1);
  const auto hx = Kokkos::create_mirror_view(px), hf = Kokkos::create_mirror_view(pf);
  for (int c = 0; c < 3; ++c) hx(0, c) = x[c], hf(0, c) = scale * f[c];
  Kokkos::deep_copy(px, hx);
  Kokkos::deep_copy(pf, hf);
  Flow::Vector load("load", 3 * n), ones("eps", n), zeros("drag", n);
  kernels::blas1::fill(Exec(), ones, 1.0);
  spread(Exec(), vf.basis(), pf, 3, px, 1, load);
  flow.set_void_fraction(ones);
  flow.set_drag(zeros);
  flow.set_particle_load(load);
  ASSERT_TRUE(flow.solve_steady(1e-6, 5).converged);
  interpolate(Exec(), vf.basis(), flow.velocity(), 3, px, 1, pu);
  const auto u = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), pu);

  double W[9];
  t.response(x, W);
  double norm = 0.0, diff = 0.0;
  for (int a = 0; a < 3; ++a) {
    const double w = W[3 * a] * f[0] + W[3 * a + 1] * f[1] + W[3 * a + 2] * f[2];
    std::printf("u_%d: direct %.6e, table %.6e\n", a, u(0, a) / scale, w);
    norm += w * w, diff += (u(0, a) / scale - w) * (u(0, a) / scale - w);
    EXPECT_GT(W[4 * a], 0.0);
  }
  EXPECT_LT(std::sqrt(diff / norm), 0.01);
  // The equivalent Gaussian width (what the Oseen factor takes), in cells of h.
  const double sigma = std::sqrt(2.0 / M_PI) / (6.0 * M_PI * nu * (W[0] + W[4] + W[8]) / 3.0);
  std::printf("equivalent Gaussian width %.3f h\n", sigma / h);
}

/// The walls of a box of M cells lower the response by about c / M; the table's 2 g_2M - g_M
/// removes that: from boxes of 8 and 16 cells and from boxes of 12 and 24 it agrees within 1 %
/// at a node and at a cell's centre, where the boxes alone differ by 10-25 %. Printed: W_xx.
TEST(CfdDemSelfInduced, UnboundedResponseFromTwoBoxes) {
  const int cells = 8;
  mesh::hex::StructuredHexMesh<3> m;
  m.cells = {cells, cells, cells};
  m.upper = {1.0 * cells, 1.0 * cells, 1.0 * cells};
  physics::ins_fem::InsOptions o;
  o.model = physics::ins_fem::FlowModel::vans_a;
  Flow flow(m, 1, o);
  const VoidFraction<3, Exec> vf(flow.space(), VoidFractionOptions{});
  const double nu = 1.0, node[3] = {4.0, 4.0, 4.0}, mid[3] = {4.5, 4.5, 4.5};
  double at[2][2];  // [table][point]
  for (int k = 0; k < 2; ++k) {
    const SelfInducedVelocity t = self_induced_velocity<Exec>(vf.basis(), nu, 8 + 4 * k);
    double W[9];
    t.response(node, W);
    at[k][0] = W[0];
    t.response(mid, W);
    at[k][1] = W[0];
    std::printf(
        "boxes of %d and %d cells: W_xx at a node %.5f, at a cell's centre %.5f "
        "(nu h = 1)\n",
        8 + 4 * k, 16 + 8 * k, at[k][0], at[k][1]);
  }
  {  // along a line through cell centres in x and y (the settling tests' path), printed
    const SelfInducedVelocity t = self_induced_velocity<Exec>(vf.basis(), nu, 8);
    for (int k = 0; k <= 8; ++k) {
      const double x[3] = {4.5, 4.5, 4.0 + k / 8.0};
      double w[9];
      t.response(x, w);
      std::printf("x = y = 4.5, z = 4 + %.3f: W_zz %.5f, W_xx %.5f\n", k / 8.0, w[8], w[0]);
    }
  }
  SelfInducedVelocity box;
  box.basis = vf.basis();
  walled_box_response<Exec>(box.basis.h, nu, 16, box.g);
  double W[9];
  box.response(mid, W);
  std::printf("the box of 16 cells alone: W_xx at a cell's centre %.5f\n", W[0]);
  for (int p = 0; p < 2; ++p) EXPECT_NEAR(at[0][p] / at[1][p], 1.0, 0.01) << "point " << p;
  EXPECT_LT(W[0], 0.9 * at[1][1]);
}

/// A constant force towed at speed U down a walled box (8 x 8 x 32 cells, h = nu = 1, CFL 0.1,
/// transient tau), spread each step at its position (a line of cell centres): the velocity read
/// back there over its last 4 of 16 cells, against the table's W F times the Oseen factor. The
/// factor's width (SelfInducedVelocity::oseen_width) was set from this run at Re_h = U h / nu =
/// 50; Re_h = 5 checks it where the screening is partial. Within 8 % at both (the Gaussian
/// alone, oseen_width = 1, gave 1.24 and 1.51 times the discrete response).
TEST(CfdDemSelfInduced, TowedForceScreening) {
  for (const double re_h : {5.0, 50.0}) {
    mesh::hex::StructuredHexMesh<3> m;
    m.cells = {8, 8, 32};
    m.upper = {8.0, 8.0, 32.0};
    physics::ins_fem::InsOptions o;
    o.model = physics::ins_fem::FlowModel::vans_a;
    o.nu = 1.0;
    o.tolerance = 1e-10;
    o.transient_tau = true;
    Flow flow(m, 1, o);
    const VoidFraction<3, Exec> vf(flow.space(), VoidFractionOptions{});
    const SelfInducedVelocity t = self_induced_velocity<Exec>(vf.basis(), 1.0, 8);
    const long n = flow.n_dofs();
    Flow::Vector load("load", 3 * n), ones("eps", n), zeros("drag", n);
    kernels::blas1::fill(Exec(), ones, 1.0);
    flow.set_void_fraction(ones);
    flow.set_drag(zeros);
    const double U = re_h, dt = 0.1 / U, F = 1e-6;  // F per unit mass, along -z: nil advection
    Kokkos::View<double*[3], Kokkos::LayoutRight, Exec::memory_space> px("x", 1), pf("f", 1),
        pu("u", 1);
    const auto hx = Kokkos::create_mirror_view(px), hf = Kokkos::create_mirror_view(pf);
    double read = 0.0, stokes = 0.0, model = 0.0;
    const int steps = 160, last = 40;  // 16 cells; the last 4
    for (int s = 0; s <= steps; ++s) {
      const double x[3] = {4.5, 4.5, 28.0 - U * dt * s};
      for (int c = 0; c < 3; ++c) hx(0, c) = x[c], hf(0, c) = c == 2 ? -F : 0.0;
      Kokkos::deep_copy(px, hx);
      Kokkos::deep_copy(pf, hf);
      kernels::blas1::fill(Exec(), load, 0.0);
      spread(Exec(), vf.basis(), pf, 3, px, 1, load);
      flow.set_particle_load(load);
      ASSERT_TRUE(flow.step(dt).converged);
      if (s < steps - last) continue;
      interpolate(Exec(), vf.basis(), flow.velocity(), 3, px, 1, pu);
      const auto u = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), pu);
      double W[9];
      t.response(x, W);
      read += -u(0, 2) / F, stokes += W[8], model += W[8] * t.screening(W, U);
    }
    std::printf("towed at Re_h %g: read back / Stokes response %.4f, the model's %.4f\n", re_h,
                read / stokes, model / stokes);
    EXPECT_NEAR(model / read, 1.0, 0.08) << "Re_h " << re_h;
  }
}

}  // namespace test_cfd_dem_self_induced
}  // namespace amphora::coupling::cfd_dem
