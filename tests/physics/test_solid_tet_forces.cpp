#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "kernels/solid/tet_forces.hpp"
#include "mesh/tet/tet_mesh.hpp"
#include "test_backend.hpp"

namespace amphora {
// A named namespace, not an anonymous one: CUDA does not support extended lambdas in
// anonymous namespaces (Kokkos issue #1547).
namespace test_solid_tet_forces_cases {

using kernels::solid::Hyperelastic;
using kernels::solid::Material;
using kernels::solid::Vec3;
using test::TestExecSpace;
using Nodes = Kokkos::View<double* [3], test::TestMemSpace>;
using Tets = Kokkos::View<int* [4], test::TestMemSpace>;

constexpr Hyperelastic models[] = {Hyperelastic::neo_hookean, Hyperelastic::corotated,
                                   Hyperelastic::st_venant_kirchhoff};

TEST(SolidStress, UniaxialNeoHookeanMatchesTheClosedFormAboveTheClamp) {
  const Material m{Hyperelastic::neo_hookean, 1.3, 2.1, 0.25};
  for (double s : {0.25, 0.4, 0.8, 1.0, 1.7, 3.0}) {
    const double exact = m.mu * s - (m.mu - m.lambda * std::log(s)) / s;
    const double P = kernels::solid::diagonal_stress(m, Vec3{{s, 1.0, 1.0}}).P[0];
    EXPECT_NEAR(P, exact, 1e-13 * std::max(1.0, std::abs(exact))) << "s = " << s;
  }
}

// The closed forms of neo-Hookean and St Venant-Kirchhoff (no SVD) give U P^ V^T to 1e-12 of
// its size where they apply, and refuse the corotated model and elements near the clamp.
TEST(SolidStress, ClosedFormMatchesTheDiagonalisedStress) {
  std::mt19937 g(11);
  std::uniform_real_distribution<double> u(-0.3, 0.3);
  int used = 0, refused = 0;
  for (const Hyperelastic model : models) {
    const Material m{model, 1.3, 2.1, 0.25};
    for (int k = 0; k < 200; ++k) {
      kernels::solid::Mat3 F = kernels::solid::Mat3::identity();
      const double scale = k < 100 ? 1.0 : 2.5;  // the second half reaches the clamp
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) F(i, j) += scale * u(g);
      const double J = kernels::solid::determinant(F);
      kernels::solid::Mat3 P;
      if (!kernels::solid::closed_form_stress(m, F, J, P)) {
        ++refused;
        continue;
      }
      ++used;
      EXPECT_NE(model, Hyperelastic::corotated);
      const kernels::solid::Svd3 d = kernels::solid::svd3(F);
      EXPECT_GT(d.s[2], m.s_clamp) << "only where no singular value is clamped";
      const auto ref = d.U *
                       kernels::solid::Mat3::diagonal(kernels::solid::diagonal_stress(m, d.s).P) *
                       kernels::solid::transpose(d.V);
      double err = 0.0;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) err = std::max(err, std::abs(P(i, j) - ref(i, j)));
      EXPECT_LT(err, 1e-12 * kernels::solid::frobenius(ref)) << "model " << int(model) << ", " << k;
    }
  }
  EXPECT_GT(used, 150);
  EXPECT_GT(refused, 200);
}

TEST(SolidStress, ContinuousAcrossTheClampAndFiniteWhenInverted) {
  for (Hyperelastic model : models) {
    const Material m{model, 1.0, 4.0, 0.25};
    const double c = m.s_clamp;
    for (int i = 0; i < 3; ++i) {
      Vec3 below{{0.9, 1.1, 1.2}}, above = below;
      below[i] = c * (1.0 - 1e-13), above[i] = c * (1.0 + 1e-13);
      const Vec3 pb = kernels::solid::diagonal_stress(m, below).P;
      const Vec3 pa = kernels::solid::diagonal_stress(m, above).P;
      for (int j = 0; j < 3; ++j)
        EXPECT_LE(std::abs(pa[j] - pb[j]), 1e-10 * std::abs(pa[j])) << "entry " << i;
      Vec3 inverted = below;
      inverted[i] = -0.5;  // through the clamp and past zero: finite and restoring
      const Vec3 p = kernels::solid::diagonal_stress(m, inverted).P;
      EXPECT_TRUE(std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]));
      if (model != Hyperelastic::st_venant_kirchhoff) {  // StVK softens: no restoring claim
        EXPECT_LT(p[i], 0.0) << "a compressed, inverted direction pulls back towards s > 0";
      }
    }
  }
}

TEST(SolidStress, JacobianMatchesFiniteDifferences) {
  for (Hyperelastic model : models) {
    const Material m{model, 1.0, 3.0, 0.25};
    // Above the clamp (below it, dP_ds is the clamped point's, tested in the next case).
    for (const Vec3& s : {Vec3{{1.2, 0.9, 0.7}}, Vec3{{1.1, 0.8, 0.3}}, Vec3{{2.3, 0.5, 0.26}}}) {
      const auto d = kernels::solid::diagonal_stress(m, s);
      for (int j = 0; j < 3; ++j) {
        const double h = 1e-6;
        Vec3 sp = s, sm = s;
        sp[j] += h, sm[j] -= h;
        const Vec3 pp = kernels::solid::diagonal_stress(m, sp).P;
        const Vec3 pm = kernels::solid::diagonal_stress(m, sm).P;
        for (int i = 0; i < 3; ++i)
          EXPECT_NEAR(d.dP_ds(i, j), (pp[i] - pm[i]) / (2 * h),
                      1e-6 * (1 + std::abs(d.dP_ds(i, j))))
              << "model " << int(model) << " entry (" << i << ", " << j << ")";
      }
    }
  }
}

TEST(SolidStress, BelowTheClampTheJacobianIsExactInTheClampedEntries) {
  for (Hyperelastic model : models) {
    const Material m{model, 1.0, 3.0, 0.25};
    const Vec3 s{{1.1, 0.8, -0.3}};
    const auto d = kernels::solid::diagonal_stress(m, s);
    const double h = 1e-6;
    Vec3 sp = s, sm = s;
    sp[2] += h, sm[2] -= h;
    const Vec3 pp = kernels::solid::diagonal_stress(m, sp).P;
    const Vec3 pm = kernels::solid::diagonal_stress(m, sm).P;
    for (int i = 0; i < 3; ++i)
      EXPECT_NEAR(d.dP_ds(i, 2), (pp[i] - pm[i]) / (2 * h), 1e-7 * (1 + std::abs(d.dP_ds(i, 2))));
  }
}

/// Nodal forces (host copy) and det F per element at positions x.
struct Forces {
  std::vector<std::array<double, 3>> f;
  std::vector<double> J;
};

Forces forces_at(const Material& m, const Nodes& X, const Tets& tets, const Nodes& x) {
  const TestExecSpace exec;
  const auto rest = kernels::solid::tet_rest_shapes(exec, X, tets);
  Nodes f("f", x.extent(0));
  Kokkos::View<double*, test::TestMemSpace> J("J", tets.extent(0));
  kernels::solid::tet_forces(exec, m, rest, tets, x, f, J);
  const auto fh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), f);
  const auto Jh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), J);
  Forces r;
  for (size_t i = 0; i < fh.extent(0); ++i) r.f.push_back({fh(i, 0), fh(i, 1), fh(i, 2)});
  r.J.assign(Jh.data(), Jh.data() + Jh.extent(0));
  return r;
}

/// The mesh's nodes moved by x -> R x + t with a rotation about an oblique axis.
mesh::tet::TetMesh rotated(mesh::tet::TetMesh m, double angle) {
  const double a[3] = {1.0 / std::sqrt(3.0), 1.0 / std::sqrt(3.0), 1.0 / std::sqrt(3.0)};
  const double c = std::cos(angle), s = std::sin(angle);
  for (auto& p : m.nodes) {  // Rodrigues' formula
    const double dot = a[0] * p[0] + a[1] * p[1] + a[2] * p[2];
    const double cr[3] = {a[1] * p[2] - a[2] * p[1], a[2] * p[0] - a[0] * p[2],
                          a[0] * p[1] - a[1] * p[0]};
    for (int d = 0; d < 3; ++d) p[d] = p[d] * c + cr[d] * s + a[d] * dot * (1 - c) + 0.3 * d;
  }
  return m;
}

TEST(SolidTetForces, RestStateGivesZeroForceInAnyOrientation) {
  const auto box = mesh::tet::box_tet_mesh({3, 2, 2}, {0, 0, 0}, {1.5, 1.0, 0.8});
  for (Hyperelastic model : models)
    for (double rest_angle : {0.0, 0.7})
      for (double angle : {0.0, 1.1, 2.9}) {
        const auto X = mesh::tet::to_views<test::TestMemSpace>(rotated(box, rest_angle));
        const auto x = mesh::tet::to_views<test::TestMemSpace>(rotated(box, rest_angle + angle));
        const Forces r = forces_at(Material{model, 1.0, 10.0, 0.25}, X.nodes, X.tets, x.nodes);
        for (const auto& f : r.f)
          for (double v : f) EXPECT_NEAR(v, 0.0, 1e-13);  // stresses ~ 10, areas ~ 0.1
        for (double J : r.J) EXPECT_NEAR(J, 1.0, 1e-13);
      }
}

/// One tetrahedron with node 3 pushed through the opposite face to z = -0.5.
struct InvertedTet {
  Nodes X{"X", 4}, x{"x", 4};
  Tets tets{"tets", 1};
  InvertedTet() {
    const double rest[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    auto Xh = Kokkos::create_mirror(X);  // a copy on every backend: X stays the rest shape
    auto th = Kokkos::create_mirror_view(tets);
    for (int i = 0; i < 4; ++i) {
      th(0, i) = i;
      for (int d = 0; d < 3; ++d) Xh(i, d) = rest[i][d];
    }
    Kokkos::deep_copy(X, Xh);
    Kokkos::deep_copy(tets, th);
    Xh(3, 2) = -0.5;
    Kokkos::deep_copy(x, Xh);
  }
};

TEST(SolidTetForces, StandardFemBreaksDownOnAnInvertedElement) {
  InvertedTet t;
  const Forces r = forces_at(Material{Hyperelastic::neo_hookean, 1.0, 1.0, 0.0}, t.X, t.tets, t.x);
  EXPECT_NEAR(r.J[0], -0.5, 1e-14);
  bool finite = true;
  for (const auto& f : r.f)
    for (double v : f) finite = finite && std::isfinite(v);
  EXPECT_FALSE(finite) << "log J of an inverted element must show up as a non-finite force";
}

TEST(SolidTetForces, InvertibleFemPushesAnInvertedElementBack) {
  InvertedTet t;
  const Material m{Hyperelastic::neo_hookean, 1.0, 1.0, 0.25};
  auto xh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), t.x);
  double J_prev = -0.5;
  int recovered = -1;
  for (int step = 0; step < 3000; ++step) {  // damped (gradient-flow) steps x += a f
    Kokkos::deep_copy(t.x, xh);
    const Forces r = forces_at(m, t.X, t.tets, t.x);
    if (step > 0 && J_prev < 0.9) {
      EXPECT_GT(r.J[0], J_prev) << "step " << step << ": det F must rise";
    }
    if (recovered < 0 && r.J[0] > 0.0) recovered = step;
    J_prev = r.J[0];
    for (int i = 0; i < 4; ++i)
      for (int d = 0; d < 3; ++d) {
        ASSERT_TRUE(std::isfinite(r.f[i][d]));
        xh(i, d) += 0.02 * r.f[i][d];
      }
  }
  EXPECT_GE(recovered, 0) << "the element never left inversion";
  EXPECT_NEAR(J_prev, 1.0, 1e-3) << "recovers its rest volume";
}

}  // namespace test_solid_tet_forces_cases
}  // namespace amphora
