#pragma once
// The cell shapes the matrix-free tests run on: Cartesian (no map), an affine shear of the box,
// or the smooth sinusoidal curving of mesh::hex::sinusoidal_deformation.
#include <stdexcept>
#include <string>

#include "mesh/hex/structured_hex_mesh.hpp"

namespace amphora::test {

/// Sets m's deformation for `shape` = "cartesian", "affine" or "curved".
template <int dim>
void deform(mesh::hex::StructuredHexMesh<dim>& m, const std::string& shape) {
  if (shape == "affine") {
    m.deformation = [](const mesh::hex::Point3& X) {
      return mesh::hex::Point3{X[0] + 0.2 * X[1] + 0.1 * X[2], 0.1 * X[0] + 1.1 * X[1],
                               0.3 * X[1] + 0.9 * X[2]};
    };
    m.affine_deformation = true;
  } else if (shape == "curved") {
    m.deformation = mesh::hex::sinusoidal_deformation(dim, 0.05);
  } else if (shape != "cartesian") {
    throw std::invalid_argument("deform: unknown shape " + shape);
  }
}

}  // namespace amphora::test
