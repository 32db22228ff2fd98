#pragma once
// A structured box of cells split into one rectangular block per rank (the layout AMReX and
// hypre's Struct interface use), and the neighbour topology the halo exchange needs.
#include <array>
#include <stdexcept>
#include <string>

namespace amphora::mesh {

using Index3 = std::array<int, 3>;

/// Cell index range [lo, hi) per direction, in global cell indices.
struct Box {
  Index3 lo{0, 0, 0};
  Index3 hi{0, 0, 0};
  int extent(int d) const { return hi[d] - lo[d]; }
  long long cells() const { return 1LL * extent(0) * extent(1) * extent(2); }
};

class DecompositionError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class BoxDecomposition {
 public:
  /// Splits `global_cells` into `nranks` blocks of at least `min_block_cells` cells per split
  /// direction, choosing the factorisation with the least halo surface; directions with
  /// `splittable` false stay whole (e.g. the vertical of a water grid, whose columns must not
  /// be cut). Throws DecompositionError if no split exists (more ranks than blocks).
  BoxDecomposition(Index3 global_cells, std::array<bool, 3> periodic, int nranks,
                   int min_block_cells = 1, std::array<bool, 3> splittable = {true, true, true});

  const Index3& global_cells() const { return global_; }
  const Index3& blocks() const { return blocks_; }
  int num_blocks() const { return blocks_[0] * blocks_[1] * blocks_[2]; }
  bool periodic(int d) const { return periodic_[d]; }

  /// Block coordinates of a rank (ranks are numbered x fastest) and back.
  Index3 block_coords(int rank) const;
  int rank_of(Index3 coords) const;
  /// The cells owned by `rank`.
  Box box(int rank) const;
  /// Rank across face `side` (0 = low, 1 = high) in direction `d`, or -1 at a non-periodic
  /// boundary of the global box.
  int neighbor(int rank, int d, int side) const;

 private:
  Index3 global_;
  std::array<bool, 3> periodic_;
  Index3 blocks_{1, 1, 1};
};

}  // namespace amphora::mesh
