#include "mesh/tet/tet_mesh.hpp"

#include <algorithm>
#include <cmath>
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

}  // namespace amphora::mesh::tet
