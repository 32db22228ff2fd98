#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "kernels/solid/tet_stiffness.hpp"
#include "mesh/tet/tet_mesh.hpp"
#include "test_backend.hpp"

namespace amphora {
// A named namespace, not an anonymous one: CUDA does not support extended lambdas in
// anonymous namespaces (Kokkos issue #1547).
namespace test_solid_stiffness_cases {

using kernels::solid::Hyperelastic;
using kernels::solid::Material;
using test::TestExecSpace;
using Mem = test::TestMemSpace;
using Nodes = Kokkos::View<double* [3], Mem>;
using Host = std::vector<double>;  // 3 entries per node

constexpr Hyperelastic models[] = {Hyperelastic::neo_hookean, Hyperelastic::corotated,
                                   Hyperelastic::st_venant_kirchhoff};

Nodes to_nodes(const Host& h) {
  Nodes v("v", h.size() / 3);
  auto m = Kokkos::create_mirror(v);
  for (size_t i = 0; i < h.size(); ++i) m(i / 3, i % 3) = h[i];
  Kokkos::deep_copy(v, m);
  return v;
}
Host to_host(const Nodes& v) {
  auto m = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), v);
  Host h(3 * v.extent(0));
  for (size_t i = 0; i < h.size(); ++i) h[i] = m(i / 3, i % 3);
  return h;
}
double dot(const Host& a, const Host& b) {
  double s = 0.0;
  for (size_t i = 0; i < a.size(); ++i) s += a[i] * b[i];
  return s;
}

/// A box of tetrahedra, its rest shape and a current shape given by `map` of the rest nodes.
struct Body {
  mesh::tet::TetMeshViews<Mem> rest;
  kernels::solid::TetRestShapes<Mem> shapes;
  Nodes x;
  template <class Map>
  Body(const mesh::tet::TetMesh& m, Map map) : rest(mesh::tet::to_views<Mem>(m)) {
    shapes = kernels::solid::tet_rest_shapes(TestExecSpace(), rest.nodes, rest.tets);
    Host h;
    for (const auto& p : m.nodes) {
      const auto q = map(p);
      h.insert(h.end(), q.begin(), q.end());
    }
    x = to_nodes(h);
  }
  int n() const { return static_cast<int>(x.extent(0)); }

  Host forces(const Material& mat, const Nodes& at) const {
    Nodes f("f", n());
    Kokkos::View<double*, Mem> J("J", rest.tets.extent(0));
    kernels::solid::tet_forces(TestExecSpace(), mat, shapes, rest.tets, at, f, J);
    return to_host(f);
  }
  /// K dx at x (and, through diag_out, K's diagonal).
  Host apply(const Material& mat, bool definite, const Host& dx, Host* diag_out = nullptr) const {
    const TestExecSpace exec;
    const auto k = kernels::solid::allocate_stiffness<Mem>(int(rest.tets.extent(0)));
    Nodes diag("diag", n()), out("out", n());
    kernels::solid::tet_stiffness(exec, mat, shapes, rest.tets, x, definite, k, diag);
    kernels::solid::tet_stiffness_apply(exec, shapes, rest.tets, k, to_nodes(dx), out);
    if (diag_out) *diag_out = to_host(diag);
    return to_host(out);
  }
};

std::array<double, 3> stretched(const std::array<double, 3>& p) {
  return {1.2 * p[0] + 0.15 * p[1] + 0.05 * std::sin(2.0 * p[2]), 0.85 * p[1] + 0.1 * p[0] * p[2],
          1.05 * p[2] - 0.1 * p[0] + 0.05 * p[1] * p[1]};
}
/// Mirrored through z = 0.5, flattened to 30 % and sheared: every element inverted.
std::array<double, 3> inverted(const std::array<double, 3>& p) {
  return {p[0] + 0.2 * p[2], p[1] - 0.1 * p[0] * p[2], 0.5 - 0.3 * (p[2] - 0.5) + 0.05 * p[0]};
}

Host random_vector(int n, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Host h(3 * n);
  for (double& v : h) v = u(gen);
  return h;
}

// Above the clamp the stiffness is the exact derivative: K dx = -(f(x + h dx) - f(x - h dx))/2h
// to the central difference's O(h^2).
TEST(SolidStiffness, MatchesCentralDifferencesOfTheForces) {
  const Body b(mesh::tet::box_tet_mesh({2, 2, 2}, {0, 0, 0}, {1, 1, 1}), stretched);
  const Host dx = random_vector(b.n(), 7);
  const Host x = to_host(b.x);
  const double h = 1e-6;
  Host xp = x, xm = x;
  for (size_t i = 0; i < x.size(); ++i) xp[i] += h * dx[i], xm[i] -= h * dx[i];
  for (Hyperelastic model : models) {
    const Material m{model, 1.0, 3.0, 0.25};
    const Host K = b.apply(m, false, dx), fp = b.forces(m, to_nodes(xp)),
               fm = b.forces(m, to_nodes(xm));
    double err = 0.0;
    for (size_t i = 0; i < K.size(); ++i) {
      const double d = K[i] + (fp[i] - fm[i]) / (2.0 * h);
      err += d * d;
    }
    EXPECT_LT(std::sqrt(err / dot(K, K)), 1e-7) << int(model);
  }
}

TEST(SolidStiffness, DiagonalIsTheOperatorsDiagonal) {
  const Body b(mesh::tet::box_tet_mesh({1, 1, 1}, {0, 0, 0}, {1, 1, 1}), inverted);
  for (bool definite : {false, true}) {
    const Material m{Hyperelastic::neo_hookean, 1.0, 3.0, 0.25};
    Host diag;
    b.apply(m, definite, Host(3 * b.n(), 0.0), &diag);
    for (int i = 0; i < 3 * b.n(); ++i) {
      Host e(3 * b.n(), 0.0);
      e[i] = 1.0;
      EXPECT_NEAR(b.apply(m, definite, e)[i], diag[i], 1e-12 * std::abs(diag[i])) << i;
    }
  }
}

// The definite part is symmetric positive semi-definite on inverted elements too.
TEST(SolidStiffness, DefinitePartIsSymmetricPositiveSemiDefiniteWhenInverted) {
  const Body b(mesh::tet::box_tet_mesh({2, 2, 2}, {0, 0, 0}, {1, 1, 1}), inverted);
  for (Hyperelastic model : models) {
    const Material m{model, 1.0, 3.0, 0.25};
    for (unsigned seed = 1; seed <= 10; ++seed) {
      const Host u = random_vector(b.n(), seed), w = random_vector(b.n(), 100 + seed);
      const Host Ku = b.apply(m, true, u), Kw = b.apply(m, true, w);
      const double scale = std::sqrt(dot(Ku, Ku) * dot(w, w));
      EXPECT_NEAR(dot(w, Ku), dot(u, Kw), 1e-12 * scale);
      EXPECT_GE(dot(u, Ku), -1e-12 * scale) << int(model) << " seed " << seed;
    }
  }
}

}  // namespace test_solid_stiffness_cases
}  // namespace amphora
