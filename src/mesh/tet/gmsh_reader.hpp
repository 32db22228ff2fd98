#pragma once
// Reads the linear tetrahedra (element type 4) and their nodes from a Gmsh MSH 4.1 ASCII file
// (https://gmsh.info/doc/texinfo/gmsh.html#MSH-file-format); other elements (points, lines,
// triangles) are skipped. Node tags are renumbered 0..n-1 in the order they appear.
#include <string>

#include "mesh/tet/tet_mesh.hpp"

namespace amphora::mesh::tet {

/// Throws std::invalid_argument "path:line: what" for an unreadable file, another version or
/// the binary form, a truncated section, an element naming a node the file lacks, or no
/// tetrahedra at all. Element orientation is not checked here (TetSolid lists inverted ones).
TetMesh read_gmsh(const std::string& path);

}  // namespace amphora::mesh::tet
