#include "mesh/hex/structured_hex_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace amphora::mesh::hex {

template <int dim>
void StructuredHexMesh<dim>::validate() const {
  for (int d = 0; d < dim; ++d) {
    if (cells[d] < 1)
      throw std::invalid_argument("mesh: cells[" + std::to_string(d) +
                                  "] = " + std::to_string(cells[d]) + ", must be at least 1");
    if (!(upper[d] > lower[d]))
      throw std::invalid_argument("mesh: upper[" + std::to_string(d) + "] must exceed lower[" +
                                  std::to_string(d) + "]");
    if ((faces[2 * d] == FaceCondition::periodic) != (faces[2 * d + 1] == FaceCondition::periodic))
      throw std::invalid_argument("mesh: direction " + std::to_string(d) +
                                  " is periodic on one face only; periodic faces come in pairs");
    if (periodic(d) && deformation) check_periodic_match(d);
  }
}

// The deformation must move both faces of a periodic pair by the same translation: the cell
// corners of the lower face, shifted by the period, must land on those of the upper face.
template <int dim>
void StructuredHexMesh<dim>::check_periodic_match(int d) const {
  const int a = (d + 1) % dim, b = dim == 3 ? (d + 2) % dim : d;
  const int na = cells[a], nb = dim == 3 ? cells[b] : 0;
  Point3 shift{0.0, 0.0, 0.0};
  double size = 0.0;
  for (int e = 0; e < dim; ++e) size = std::max(size, upper[e] - lower[e]);
  for (int i = 0; i <= na; ++i)
    for (int j = 0; j <= nb; ++j) {
      Point3 x = lower;
      x[a] = lower[a] + (upper[a] - lower[a]) * i / na;
      if constexpr (dim == 3) x[b] = lower[b] + (upper[b] - lower[b]) * j / nb;
      Point3 y = x;
      y[d] = upper[d];
      const Point3 px = deformation(x), py = deformation(y);
      for (int e = 0; e < dim; ++e) {
        const double s = py[e] - px[e];
        if (i == 0 && j == 0) shift[e] = s;
        if (std::abs(s - shift[e]) > 1e-10 * size)
          throw std::invalid_argument(
              "mesh: the periodic faces of direction " + std::to_string(d) +
              " do not match under the deformation (the corner at box coordinate " +
              std::to_string(x[a]) + " along direction " + std::to_string(a) +
              " is off its image by " + std::to_string(std::abs(s - shift[e])) + ")");
      }
    }
}

template <int dim>
StructuredHexMesh<dim> StructuredHexMesh<dim>::refined() const {
  StructuredHexMesh m = *this;
  for (int d = 0; d < dim; ++d) m.cells[d] *= 2;
  return m;
}

template <int dim>
StructuredHexMesh<dim> StructuredHexMesh<dim>::coarsened() const {
  StructuredHexMesh m = *this;
  for (int d = 0; d < dim; ++d) {
    if (cells[d] % 2 != 0)
      throw std::invalid_argument("mesh: cannot coarsen " + std::to_string(cells[d]) +
                                  " cells in direction " + std::to_string(d) + " (odd)");
    m.cells[d] /= 2;
  }
  return m;
}

template <int dim>
StructuredHexMesh<dim> unit_cube(int n, FaceCondition all_faces) {
  StructuredHexMesh<dim> m;
  for (int d = 0; d < dim; ++d) m.cells[d] = n;
  m.faces.fill(all_faces);
  return m;
}

std::function<Point3(const Point3&)> sinusoidal_deformation(int dim, double amplitude) {
  return [dim, amplitude](const Point3& X) {
    constexpr double pi = 3.14159265358979323846;
    double bump = std::sin(pi * X[0]) * std::sin(pi * X[1]);
    if (dim == 3) bump *= std::sin(pi * X[2]);
    Point3 x = X;
    for (int d = 0; d < dim; ++d)
      x[d] += amplitude * bump * std::cos(1.3 * d + 2.0 * X[(d + 1) % dim]);
    return x;
  };
}

std::function<Point3(const Point3&)> sinusoidal_deformation(int dim, double amplitude,
                                                            const Point3& lower,
                                                            const Point3& upper) {
  const auto unit = sinusoidal_deformation(dim, amplitude);
  return [dim, unit, lower, upper](const Point3& x) {
    Point3 s = x;
    for (int d = 0; d < dim; ++d) s[d] = (x[d] - lower[d]) / (upper[d] - lower[d]);
    const Point3 y = unit(s);
    Point3 out = x;
    for (int d = 0; d < dim; ++d) out[d] = lower[d] + (upper[d] - lower[d]) * y[d];
    return out;
  };
}

template struct StructuredHexMesh<2>;
template struct StructuredHexMesh<3>;
template StructuredHexMesh<2> unit_cube<2>(int, FaceCondition);
template StructuredHexMesh<3> unit_cube<3>(int, FaceCondition);

}  // namespace amphora::mesh::hex
