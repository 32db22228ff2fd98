#include "mesh/tet/tet_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>

namespace amphora::mesh::tet {

namespace {

double signed_volume6(const TetMesh& m, const std::array<int, 4>& t) {
  double D[3][3];
  for (int c = 0; c < 3; ++c)
    for (int i = 0; i < 3; ++i) D[i][c] = m.nodes[t[c + 1]][i] - m.nodes[t[0]][i];
  return D[0][0] * (D[1][1] * D[2][2] - D[1][2] * D[2][1]) -
         D[0][1] * (D[1][0] * D[2][2] - D[1][2] * D[2][0]) +
         D[0][2] * (D[1][0] * D[2][1] - D[1][1] * D[2][0]);
}

}  // namespace

TetMesh box_tet_mesh(const std::array<int, 3>& cells, const std::array<double, 3>& lower,
                     const std::array<double, 3>& upper) {
  for (int d = 0; d < 3; ++d)
    if (cells[d] < 1 || !(upper[d] > lower[d]))
      throw std::invalid_argument("box_tet_mesh: direction " + std::to_string(d) +
                                  " needs at least one cell and upper > lower");
  TetMesh m;
  const int nx = cells[0] + 1, ny = cells[1] + 1, nz = cells[2] + 1;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        m.nodes.push_back({lower[0] + (upper[0] - lower[0]) * i / cells[0],
                           lower[1] + (upper[1] - lower[1]) * j / cells[1],
                           lower[2] + (upper[2] - lower[2]) * k / cells[2]});
  const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (int k = 0; k < cells[2]; ++k)
    for (int j = 0; j < cells[1]; ++j)
      for (int i = 0; i < cells[0]; ++i)
        for (const auto& p : perms) {
          // The path 000 -> e_p0 -> e_p0 + e_p1 -> 111 through the cube's corners.
          std::array<int, 3> c{i, j, k};
          std::array<int, 4> t;
          t[0] = (c[2] * ny + c[1]) * nx + c[0];
          for (int s = 0; s < 3; ++s) {
            ++c[p[s]];
            t[s + 1] = (c[2] * ny + c[1]) * nx + c[0];
          }
          if (signed_volume6(m, t) < 0.0) std::swap(t[2], t[3]);
          m.tets.push_back(t);
        }
  return m;
}

double tet_volume(const TetMesh& m, int e) { return signed_volume6(m, m.tets[e]) / 6.0; }
double tet_volume(const TetMesh& m, const std::array<int, 4>& t) {
  return signed_volume6(m, t) / 6.0;
}

std::vector<std::array<int, 3>> boundary_faces(const TetMesh& m) {
  // Face c of a positive element, opposite its corner c, ordered with the outward normal.
  constexpr int kFace[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  std::map<std::array<int, 3>, std::pair<int, std::array<int, 3>>> seen;  // sorted -> (count, face)
  for (const auto& t : m.tets)
    for (const auto& f : kFace) {
      const std::array<int, 3> face{t[f[0]], t[f[1]], t[f[2]]};
      auto key = face;
      std::sort(key.begin(), key.end());
      auto& entry = seen[key];
      if (++entry.first > 2)
        throw std::invalid_argument("non-manifold mesh: the face of nodes " +
                                    std::to_string(key[0]) + " " + std::to_string(key[1]) + " " +
                                    std::to_string(key[2]) + " belongs to more than two elements");
      entry.second = face;
    }
  std::vector<std::array<int, 3>> out;
  std::map<std::pair<int, int>, int> edges;
  for (const auto& [key, entry] : seen) {
    if (entry.first != 1) continue;
    out.push_back(entry.second);
    for (int i = 0; i < 3; ++i) ++edges[std::minmax(entry.second[i], entry.second[(i + 1) % 3])];
  }
  for (const auto& [e, count] : edges)
    if (count != 2)
      throw std::invalid_argument("non-manifold mesh: the boundary edge of nodes " +
                                  std::to_string(e.first) + " " + std::to_string(e.second) +
                                  " is on " + std::to_string(count) +
                                  " boundary faces (a closed surface has 2)");
  return out;
}

int euler_characteristic(const std::vector<std::array<int, 3>>& faces) {
  std::set<int> vertices;
  std::set<std::pair<int, int>> edges;
  for (const auto& f : faces)
    for (int i = 0; i < 3; ++i) {
      vertices.insert(f[i]);
      edges.insert(std::minmax(f[i], f[(i + 1) % 3]));
    }
  return static_cast<int>(vertices.size()) - static_cast<int>(edges.size()) +
         static_cast<int>(faces.size());
}

}  // namespace amphora::mesh::tet
