#pragma once
// What a module hands the writers: blocks of output fields, blocks of state for checkpoints,
// and named diagnostics. Plain host data, so the HDF5, XDMF and CSV writers need no physics.
#include <string>
#include <utility>
#include <vector>

namespace amphora {

using NamedArray = std::pair<std::string, std::vector<double>>;

/// One block of output owned by this rank: a rectilinear grid (node coordinates per
/// direction, length 1 for an unused direction, fields stored x fastest), a set of points
/// (`points`: x, y, z hold each point's coordinates, fields one value per point), or a
/// curvilinear grid (`curvilinear`: nodes[0] x nodes[1] x nodes[2] nodes, x fastest, x, y, z
/// hold every node's coordinates; curved high-order meshes), or a tetrahedral mesh (`tets`: 4
/// node indices per element, 0-based; x, y, z hold every node's coordinates; fields of one
/// value per element are cell data).
struct OutputBlock {
  std::string name;
  std::vector<double> x, y, z;
  std::vector<NamedArray> fields;
  bool points = false;
  bool curvilinear = false;
  std::vector<double> tets;  ///< connectivity as doubles (the files hold doubles; exact < 2^53)
  long nodes[3] = {1, 1, 1};
};

/// Named arrays of one block of state, enough to continue bit for bit.
struct StateBlock {
  std::string name;
  std::vector<NamedArray> arrays;
};

using Diagnostics = std::vector<std::pair<std::string, double>>;

}  // namespace amphora
