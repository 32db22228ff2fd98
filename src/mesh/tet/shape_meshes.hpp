#pragma once
// Tetrahedral meshes of curved shapes from block-structured hexahedra: a ball (an inner cube
// and six shell blocks mapped onto the sphere, as a cubed sphere), a torus (the same disk
// section swept around the ring) and a cylinder (the disk extruded). Every hexahedron is split into
// 24 tetrahedra around its centre and its face centres, which conforms across blocks of any
// orientation; the centres of boundary faces are projected onto the exact surface.
#include <array>
#include <functional>
#include <vector>

#include "mesh/tet/tet_mesh.hpp"

namespace amphora::mesh::tet {

using Point = std::array<double, 3>;
/// A hexahedron's corners in lexicographic order: corner i + 2 j + 4 k at (i, j, k) in {0, 1}^3.
using Hex = std::array<Point, 8>;

/// The 24-tetrahedra split of the hexahedra; corners closer than 1e-9 of the mesh's extent
/// are one node. `project` (if given) moves each boundary face centre onto the surface.
TetMesh tets_from_hexes(const std::vector<Hex>& hexes,
                        const std::function<Point(const Point&)>& project = nullptr);

/// The ball of `radius` about `centre`, about `cells` cells across its diameter (>= 2).
TetMesh ball_tet_mesh(double radius, int cells, const Point& centre = {0.0, 0.0, 0.0});

/// The torus about the z axis through `centre`: the tube of radius `tube` around the circle of
/// radius `ring` (> tube), about `cells` cells across the tube's diameter (>= 2), and as many
/// around the ring as keep the cells about as long as wide.
TetMesh torus_tet_mesh(double ring, double tube, int cells, const Point& centre = {0.0, 0.0, 0.0});

/// The cylinder of `radius` along the x axis from centre - length/2 to centre + length/2,
/// about `cells` cells across its diameter (>= 2) and as many along it as keep them about
/// as long as wide.
TetMesh cylinder_tet_mesh(double radius, double length, int cells,
                          const Point& centre = {0.0, 0.0, 0.0});

}  // namespace amphora::mesh::tet
