#include "mesh/box_decomposition.hpp"

#include <limits>
#include <sstream>

namespace amphora::mesh {

BoxDecomposition::BoxDecomposition(Index3 global_cells, std::array<bool, 3> periodic, int nranks,
                                   int min_block_cells, std::array<bool, 3> splittable)
    : global_(global_cells), periodic_(periodic) {
  for (int d = 0; d < 3; ++d) {
    if (global_[d] < 1) {
      throw DecompositionError("box decomposition: global cell count in direction " +
                               std::to_string(d) + " is " + std::to_string(global_[d]) +
                               ", must be >= 1");
    }
  }
  if (nranks < 1) throw DecompositionError("box decomposition: rank count must be >= 1");
  if (min_block_cells < 1) min_block_cells = 1;

  // Largest number of blocks per direction that keeps every block at least min_block_cells
  // wide; a direction that is not split may be thinner.
  Index3 max_blocks;
  for (int d = 0; d < 3; ++d)
    max_blocks[d] = splittable[d] ? std::max(1, global_[d] / min_block_cells) : 1;

  double best_surface = std::numeric_limits<double>::max();
  bool found = false;
  for (int px = 1; px <= nranks; ++px) {
    if (nranks % px || px > max_blocks[0]) continue;
    for (int py = 1; py <= nranks / px; ++py) {
      if ((nranks / px) % py || py > max_blocks[1]) continue;
      const int pz = nranks / px / py;
      if (pz > max_blocks[2]) continue;
      // Halo surface of one block (cells on its faces), the quantity the exchange moves.
      const double bx = double(global_[0]) / px, by = double(global_[1]) / py,
                   bz = double(global_[2]) / pz;
      const double surface = (px > 1 || periodic_[0] ? by * bz : 0.0) +
                             (py > 1 || periodic_[1] ? bx * bz : 0.0) +
                             (pz > 1 || periodic_[2] ? bx * by : 0.0);
      if (surface < best_surface) {
        best_surface = surface;
        blocks_ = {px, py, pz};
        found = true;
      }
    }
  }
  if (!found) {
    std::ostringstream msg;
    msg << "more ranks (" << nranks << ") than blocks: a " << global_[0] << "x" << global_[1] << "x"
        << global_[2] << "-cell box splits into at most " << max_blocks[0] << "x" << max_blocks[1]
        << "x" << max_blocks[2] << " blocks of at least " << min_block_cells
        << " cells per direction, and " << nranks << " does not factor into that";
    throw DecompositionError(msg.str());
  }
}

Index3 BoxDecomposition::block_coords(int rank) const {
  return {rank % blocks_[0], (rank / blocks_[0]) % blocks_[1], rank / (blocks_[0] * blocks_[1])};
}

int BoxDecomposition::rank_of(Index3 c) const {
  return c[0] + blocks_[0] * (c[1] + blocks_[1] * c[2]);
}

Box BoxDecomposition::box(int rank) const {
  const Index3 c = block_coords(rank);
  Box b;
  for (int d = 0; d < 3; ++d) {
    // Balanced split: the first (n mod p) blocks get one extra cell.
    const int n = global_[d], p = blocks_[d], base = n / p, extra = n % p;
    b.lo[d] = c[d] * base + std::min(c[d], extra);
    b.hi[d] = b.lo[d] + base + (c[d] < extra ? 1 : 0);
  }
  return b;
}

int BoxDecomposition::neighbor(int rank, int d, int side) const {
  Index3 c = block_coords(rank);
  c[d] += side == 0 ? -1 : 1;
  if (c[d] < 0 || c[d] >= blocks_[d]) {
    if (!periodic_[d]) return -1;
    c[d] = (c[d] + blocks_[d]) % blocks_[d];
  }
  return rank_of(c);
}

}  // namespace amphora::mesh
