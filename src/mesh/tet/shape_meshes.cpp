#include "mesh/tet/shape_meshes.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>

namespace amphora::mesh::tet {

namespace {

constexpr double kPi = 3.14159265358979323846;

/// Merges points closer than tol: the index of each point's node and the nodes.
std::pair<std::vector<int>, std::vector<Point>> merge_points(const std::vector<Point>& pts,
                                                             double tol) {
  using Key = std::array<long long, 3>;
  std::map<Key, std::vector<int>> grid;  // node indices by cell of side 4 tol
  std::vector<Point> nodes;
  std::vector<int> id(pts.size());
  auto key_of = [&](const Point& p) {
    return Key{std::llround(std::floor(p[0] / (4.0 * tol))),
               std::llround(std::floor(p[1] / (4.0 * tol))),
               std::llround(std::floor(p[2] / (4.0 * tol)))};
  };
  for (size_t i = 0; i < pts.size(); ++i) {
    const Key k = key_of(pts[i]);
    int found = -1;
    for (int n = 0; n < 27 && found < 0; ++n) {
      const auto it = grid.find({k[0] + n % 3 - 1, k[1] + (n / 3) % 3 - 1, k[2] + n / 9 - 1});
      if (it == grid.end()) continue;
      for (int j : it->second)
        if (std::abs(nodes[j][0] - pts[i][0]) <= tol && std::abs(nodes[j][1] - pts[i][1]) <= tol &&
            std::abs(nodes[j][2] - pts[i][2]) <= tol)
          found = j;
    }
    if (found < 0) {
      found = static_cast<int>(nodes.size());
      nodes.push_back(pts[i]);
      grid[k].push_back(found);
    }
    id[i] = found;
  }
  return {id, nodes};
}

double extent_of(const std::vector<Hex>& hexes) {
  double lo = 1e300, hi = -1e300;
  for (const auto& h : hexes)
    for (const auto& p : h)
      for (double c : p) lo = std::min(lo, c), hi = std::max(hi, c);
  return hi - lo;
}

// The six faces of a lexicographic hexahedron, each as a cycle of corners.
constexpr int kFaces[6][4] = {{0, 2, 6, 4}, {1, 3, 7, 5}, {0, 1, 5, 4},
                              {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 5, 7, 6}};

Point mean(const TetMesh& m, const int* ids, int n) {
  Point c{0.0, 0.0, 0.0};
  for (int i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d) c[d] += m.nodes[ids[i]][d] / n;
  return c;
}

Point normalised(Point q, double r) {
  const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
  for (double& c : q) c *= r / n;
  return q;
}

/// The point (u, v, s) of the cubed-sphere shell block on face `sign` e_axis: s = 0 on the
/// inner cube of half-width a (equispaced u, v), s = 1 on the sphere (equiangular u, v).
Point shell_point(int axis, double sign, double u, double v, double s, double a, double r) {
  Point e, q;
  e[axis] = q[axis] = sign;
  e[(axis + 1) % 3] = u, q[(axis + 1) % 3] = std::tan(0.25 * kPi * u);
  e[(axis + 2) % 3] = v, q[(axis + 2) % 3] = std::tan(0.25 * kPi * v);
  const Point out = normalised(q, r);
  Point p;
  for (int d = 0; d < 3; ++d) p[d] = (1.0 - s) * a * e[d] + s * out[d];
  return p;
}

/// The hexahedra of the ball of radius r (or, with `planar`, of the disk in the x-y plane, one
/// cell thick in z from 0 to 1): an inner cube (square) of n cells per side, shell blocks of m
/// radial layers.
std::vector<Hex> cubed_ball(double r, int n, int m, bool planar) {
  const double a = 0.4 * r;
  std::vector<Hex> hexes;
  auto lin = [n](int i) { return -1.0 + 2.0 * i / n; };
  const int nz = planar ? 1 : n;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        Hex h;
        for (int c = 0; c < 8; ++c)
          h[c] = {a * lin(i + c % 2), a * lin(j + (c / 2) % 2),
                  planar ? double(c / 4) : a * lin(k + c / 4)};
        hexes.push_back(h);
      }
  const int axes = planar ? 2 : 3;
  for (int axis = 0; axis < axes; ++axis)
    for (double sign : {-1.0, 1.0})
      for (int k = 0; k < m; ++k)
        for (int j = 0; j < nz; ++j)
          for (int i = 0; i < n; ++i) {
            Hex h;
            for (int c = 0; c < 8; ++c) {
              const double u = lin(i + c % 2), s = double(k + c / 4) / m;
              if (planar) {  // the square's side 'sign e_axis' (in the x-y plane), extruded in z
                Point p =
                    shell_point(axis, sign, axis == 0 ? u : 0.0, axis == 0 ? 0.0 : u, s, a, r);
                p[2] = double(j + (c / 2) % 2);
                h[c] = p;
              } else {
                h[c] = shell_point(axis, sign, u, lin(j + (c / 2) % 2), s, a, r);
              }
            }
            hexes.push_back(h);
          }
  return hexes;
}

}  // namespace

TetMesh tets_from_hexes(const std::vector<Hex>& hexes,
                        const std::function<Point(const Point&)>& project) {
  std::vector<Point> corners;
  for (const auto& h : hexes) corners.insert(corners.end(), h.begin(), h.end());
  auto merged = merge_points(corners, 1e-9 * extent_of(hexes));
  const std::vector<int> id = std::move(merged.first);
  TetMesh m;
  m.nodes = std::move(merged.second);
  // Face centres, one node per distinct face (keyed by its sorted corners); boundary faces
  // (in one hexahedron only) projected.
  std::map<std::array<int, 4>, std::pair<int, int>> faces;  // key -> (count, first hex face)
  auto face_key = [&](size_t h, int f) {
    std::array<int, 4> k;
    for (int c = 0; c < 4; ++c) k[c] = id[8 * h + kFaces[f][c]];
    std::sort(k.begin(), k.end());
    return k;
  };
  for (size_t h = 0; h < hexes.size(); ++h)
    for (int f = 0; f < 6; ++f) ++faces[face_key(h, f)].first;
  for (auto& [key, entry] : faces) {
    Point c = mean(m, key.data(), 4);
    if (entry.first == 1 && project) c = project(c);
    entry.second = m.n_nodes();
    m.nodes.push_back(c);
  }
  for (size_t h = 0; h < hexes.size(); ++h) {
    const int* ids = &id[8 * h];
    const int centre = m.n_nodes();
    m.nodes.push_back(mean(m, ids, 8));
    for (int f = 0; f < 6; ++f) {
      const int fc = faces[face_key(h, f)].second;
      for (int e = 0; e < 4; ++e) {
        std::array<int, 4> t{ids[kFaces[f][e]], ids[kFaces[f][(e + 1) % 4]], fc, centre};
        if (tet_volume(m, t) < 0.0) std::swap(t[0], t[1]);
        m.tets.push_back(t);
      }
    }
  }
  return m;
}

TetMesh ball_tet_mesh(double radius, int cells, const Point& centre) {
  if (!(radius > 0.0) || cells < 2)
    throw std::invalid_argument("ball_tet_mesh: needs radius > 0 and cells >= 2");
  const int n = std::max(1, cells / 2), m = std::max(1, (n + 1) / 2);
  auto hexes = cubed_ball(radius, n, m, false);
  for (auto& h : hexes)
    for (auto& p : h)
      for (int d = 0; d < 3; ++d) p[d] += centre[d];
  return tets_from_hexes(hexes, [&](const Point& p) {
    Point q{p[0] - centre[0], p[1] - centre[1], p[2] - centre[2]};
    q = normalised(q, radius);
    return Point{q[0] + centre[0], q[1] + centre[1], q[2] + centre[2]};
  });
}

TetMesh torus_tet_mesh(double ring, double tube, int cells, const Point& centre) {
  if (!(tube > 0.0) || !(ring > tube) || cells < 2)
    throw std::invalid_argument("torus_tet_mesh: needs ring > tube > 0 and cells >= 2");
  const int n = std::max(1, cells / 2), m = std::max(1, (n + 1) / 2);
  // Cells across the section are about 2 tube / (n + 2 m) wide; as many around the ring.
  const int around = std::max(6, static_cast<int>(std::lround(kPi * ring * (n + 2 * m) / tube)));
  // The section's disk (x: radial offset, y: height) extruded in z by 'around' unit steps,
  // then wrapped around the ring: (p, q, k) -> ((ring + p) cos phi, (ring + p) sin phi, q).
  auto hexes = cubed_ball(tube, n, m, true);
  std::vector<Hex> ring_hexes;
  for (int k = 0; k < around; ++k)
    for (Hex h : hexes) {
      for (auto& p : h) {
        const double phi = 2.0 * kPi * (k + p[2]) / around;
        p = {centre[0] + (ring + p[0]) * std::cos(phi), centre[1] + (ring + p[0]) * std::sin(phi),
             centre[2] + p[1]};
      }
      ring_hexes.push_back(h);
    }
  return tets_from_hexes(ring_hexes, [&](const Point& p) {
    // The closest point of the tube's surface: along the section's radius.
    const double x = p[0] - centre[0], y = p[1] - centre[1], z = p[2] - centre[2];
    const double rho = std::hypot(x, y);
    const Point q = normalised({rho - ring, z, 0.0}, tube);
    return Point{centre[0] + (ring + q[0]) * x / rho, centre[1] + (ring + q[0]) * y / rho,
                 centre[2] + q[1]};
  });
}

TetMesh cylinder_tet_mesh(double radius, double length, int cells, const Point& centre) {
  if (!(radius > 0.0) || !(length > 0.0) || cells < 2)
    throw std::invalid_argument("cylinder_tet_mesh: needs radius > 0, length > 0 and cells >= 2");
  const int n = std::max(1, cells / 2), m = std::max(1, (n + 1) / 2);
  const int layers =
      std::max(1, static_cast<int>(std::lround(length * (n + 2 * m) / (2 * radius))));
  const double x0 = centre[0] - 0.5 * length, x1 = centre[0] + 0.5 * length;
  // The section's disk (x, y) extruded in z by unit steps, then (p, q, k) -> (x0 + k L /
  // layers, p, q) about the centre.
  const auto disk = cubed_ball(radius, n, m, true);
  std::vector<Hex> hexes;
  for (int k = 0; k < layers; ++k)
    for (Hex h : disk) {
      for (auto& p : h) p = {x0 + (k + p[2]) * length / layers, centre[1] + p[0], centre[2] + p[1]};
      hexes.push_back(h);
    }
  const double tol = 1e-9 * length;
  return tets_from_hexes(hexes, [&](const Point& p) {
    if (p[0] < x0 + tol || p[0] > x1 - tol) return p;  // on an end: flat already
    const Point q = normalised({p[1] - centre[1], p[2] - centre[2], 0.0}, radius);
    return Point{p[0], centre[1] + q[0], centre[2] + q[1]};
  });
}

}  // namespace amphora::mesh::tet
