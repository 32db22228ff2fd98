#pragma once
// An unstructured tetrahedral mesh on the host (node coordinates and positively oriented
// elements), the generators for simple shapes, and its copy into device Views.
#include <array>
#include <vector>

#include "kernels/spaces.hpp"

namespace amphora::mesh::tet {

struct TetMesh {
  std::vector<std::array<double, 3>> nodes;
  std::vector<std::array<int, 4>> tets;  ///< positively oriented: det[x1-x0, x2-x0, x3-x0] > 0
  int n_nodes() const { return static_cast<int>(nodes.size()); }
  int n_tets() const { return static_cast<int>(tets.size()); }
};

/// The box [lower, upper] on cells[0] x cells[1] x cells[2] cubes, each split into the six
/// Kuhn tetrahedra around its main diagonal (conforming across cubes without alternation).
TetMesh box_tet_mesh(const std::array<int, 3>& cells, const std::array<double, 3>& lower,
                     const std::array<double, 3>& upper);

/// The signed volume of element e (positive for a positively oriented element).
double tet_volume(const TetMesh& m, int e);
/// The signed volume of the tetrahedron on the nodes t of m.
double tet_volume(const TetMesh& m, const std::array<int, 4>& t);

/// The boundary triangles (faces of exactly one element), ordered so that their normals point
/// out of the mesh. Throws std::invalid_argument naming the first non-manifold place: a face
/// of more than two elements, or a boundary edge not on exactly two boundary triangles.
std::vector<std::array<int, 3>> boundary_faces(const TetMesh& m);

/// V - E + F of a closed triangulated surface: 2 for each sphere, 0 for each torus.
int euler_characteristic(const std::vector<std::array<int, 3>>& faces);

template <class MemSpace>
struct TetMeshViews {
  Kokkos::View<double* [3], MemSpace> nodes;
  Kokkos::View<int* [4], MemSpace> tets;
};

template <class MemSpace>
TetMeshViews<MemSpace> to_views(const TetMesh& m) {
  TetMeshViews<MemSpace> v{Kokkos::View<double* [3], MemSpace>("tet::nodes", m.n_nodes()),
                           Kokkos::View<int* [4], MemSpace>("tet::tets", m.n_tets())};
  auto x = Kokkos::create_mirror_view(v.nodes);
  auto t = Kokkos::create_mirror_view(v.tets);
  for (int i = 0; i < m.n_nodes(); ++i)
    for (int d = 0; d < 3; ++d) x(i, d) = m.nodes[i][d];
  for (int e = 0; e < m.n_tets(); ++e)
    for (int c = 0; c < 4; ++c) t(e, c) = m.tets[e][c];
  Kokkos::deep_copy(v.nodes, x);
  Kokkos::deep_copy(v.tets, t);
  return v;
}

}  // namespace amphora::mesh::tet
