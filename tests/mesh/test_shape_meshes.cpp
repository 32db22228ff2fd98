#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "mesh/tet/shape_meshes.hpp"
#include "test_backend.hpp"

namespace amphora {
namespace {

using mesh::tet::TetMesh;
constexpr double kPi = 3.14159265358979323846;

double mesh_volume(const TetMesh& m) {
  double v = 0.0;
  for (int e = 0; e < m.n_tets(); ++e) v += mesh::tet::tet_volume(m, e);
  return v;
}

/// The worst element quality 6 sqrt(2) V / l_max^3 (1 for the regular tetrahedron, 0 flat).
double worst_quality(const TetMesh& m) {
  double q = 1.0;
  for (int e = 0; e < m.n_tets(); ++e) {
    double lmax = 0.0;
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b) {
        const auto& p = m.nodes[m.tets[e][a]];
        const auto& r = m.nodes[m.tets[e][b]];
        lmax = std::max(lmax, std::hypot(p[0] - r[0], p[1] - r[1], p[2] - r[2]));
      }
    q = std::min(q, 6.0 * std::sqrt(2.0) * mesh::tet::tet_volume(m, e) / (lmax * lmax * lmax));
  }
  return q;
}

/// A closed, positively oriented mesh whose boundary nodes all satisfy `on_surface` to 1e-12.
template <class OnSurface>
void expect_closed_surface_on(const TetMesh& m, int euler, OnSurface distance) {
  for (int e = 0; e < m.n_tets(); ++e) ASSERT_GT(mesh::tet::tet_volume(m, e), 0.0) << e;
  const auto faces = mesh::tet::boundary_faces(m);
  EXPECT_EQ(mesh::tet::euler_characteristic(faces), euler);
  double worst = 0.0;
  for (const auto& f : faces)
    for (int n : f) worst = std::max(worst, std::abs(distance(m.nodes[n])));
  EXPECT_LT(worst, 1e-12);
}

// Linear elements on a curved boundary: the volume error falls as h^2.
TEST(ShapeMeshes, BallIsClosedOnItsSphereAndItsVolumeConvergesAtOrderTwo) {
  const double r = 0.7, exact = 4.0 / 3.0 * kPi * r * r * r;
  double err[3];
  const int cells[3] = {4, 8, 16};
  for (int i = 0; i < 3; ++i) {
    const TetMesh m = mesh::tet::ball_tet_mesh(r, cells[i], {0.1, -0.2, 0.3});
    expect_closed_surface_on(m, 2, [&](const mesh::tet::Point& p) {
      return std::hypot(p[0] - 0.1, p[1] + 0.2, p[2] - 0.3) - r;
    });
    err[i] = std::abs(mesh_volume(m) / exact - 1.0);
    std::printf("ball cells %2d: %6d tets, volume error %.3e, worst quality %.3f\n", cells[i],
                m.n_tets(), err[i], worst_quality(m));
    EXPECT_GT(worst_quality(m), 0.1);
  }
  for (int i = 0; i < 2; ++i) {
    const double order = std::log2(err[i] / err[i + 1]);
    EXPECT_GT(order, 1.8);
    EXPECT_LT(order, 2.3);
  }
}

TEST(ShapeMeshes, TorusIsClosedOnItsTubeAndItsVolumeConvergesAtOrderTwo) {
  const double R = 1.0, r = 0.3, exact = 2.0 * kPi * kPi * R * r * r;
  double err[2];
  const int cells[2] = {4, 8};
  for (int i = 0; i < 2; ++i) {
    const TetMesh m = mesh::tet::torus_tet_mesh(R, r, cells[i]);
    expect_closed_surface_on(m, 0, [&](const mesh::tet::Point& p) {
      return std::hypot(std::hypot(p[0], p[1]) - R, p[2]) - r;
    });
    err[i] = std::abs(mesh_volume(m) / exact - 1.0);
    std::printf("torus cells %d: %6d tets, volume error %.3e, worst quality %.3f\n", cells[i],
                m.n_tets(), err[i], worst_quality(m));
    EXPECT_GT(worst_quality(m), 0.1);
  }
  const double order = std::log2(err[0] / err[1]);
  EXPECT_GT(order, 1.8);
  EXPECT_LT(order, 2.3);
}

TEST(ShapeMeshes, CylinderIsClosedOnItsSurfaceAndItsVolumeConvergesAtOrderTwo) {
  const double r = 0.3, L = 1.2, exact = kPi * r * r * L;
  double err[2];
  const int cells[2] = {4, 8};
  for (int i = 0; i < 2; ++i) {
    const TetMesh m = mesh::tet::cylinder_tet_mesh(r, L, cells[i], {0.5, 0.1, 0.2});
    expect_closed_surface_on(m, 2, [&](const mesh::tet::Point& p) {
      // The distance to the closed surface: the side or an end, whichever is nearer.
      const double side = std::hypot(p[1] - 0.1, p[2] - 0.2) - r;
      const double end = std::abs(p[0] - 0.5) - 0.5 * L;
      return std::abs(side) < std::abs(end) ? side : end;
    });
    err[i] = std::abs(mesh_volume(m) / exact - 1.0);
    std::printf("cylinder cells %d: %6d tets, volume error %.3e, worst quality %.3f\n", cells[i],
                m.n_tets(), err[i], worst_quality(m));
    EXPECT_GT(worst_quality(m), 0.1);
  }
  const double order = std::log2(err[0] / err[1]);
  EXPECT_GT(order, 1.8);
  EXPECT_LT(order, 2.3);
}

std::string boundary_error(const TetMesh& m) {
  try {
    mesh::tet::boundary_faces(m);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(ShapeMeshes, NonManifoldMeshesAreNamed) {
  // Two unit cubes touching along one edge only.
  TetMesh two = mesh::tet::box_tet_mesh({1, 1, 1}, {0, 0, 0}, {1, 1, 1});
  const TetMesh b = mesh::tet::box_tet_mesh({1, 1, 1}, {1, 1, 0}, {2, 2, 1});
  const int shift = two.n_nodes();
  for (const auto& p : b.nodes) two.nodes.push_back(p);
  for (auto t : b.tets) {
    for (int& c : t) c += shift;
    two.tets.push_back(t);
  }
  // The cubes' shared edge x = y = 1: nodes 3 and 7 of the first, 0 and 4 of the second.
  for (auto& t : two.tets)
    for (int& c : t) c = c == shift ? 3 : c == shift + 4 ? 7 : c;
  EXPECT_EQ(boundary_error(two),
            "non-manifold mesh: the boundary edge of nodes 3 7 is on 4 boundary faces (a closed "
            "surface has 2)");
  // A third element on one face.
  TetMesh three = mesh::tet::box_tet_mesh({1, 1, 1}, {0, 0, 0}, {1, 1, 1});
  three.nodes.push_back({0.2, 0.2, 0.2});
  three.tets.push_back({three.tets[0][0], three.tets[0][2], three.tets[0][3], 8});  // interior face
  EXPECT_NE(boundary_error(three).find("belongs to more than two elements"), std::string::npos);
  EXPECT_EQ(boundary_error(mesh::tet::box_tet_mesh({2, 1, 1}, {0, 0, 0}, {2, 1, 1})), "");
}

}  // namespace
}  // namespace amphora
