#pragma once
// A box in space split into one rectangular subdomain per rank (a BoxDecomposition over a
// virtual grid of cells at least `min_width` wide), for particles: who owns a point, and who
// the face neighbours are. Ranks exchange packed particle records through it.
#include <array>
#include <vector>

#include "mesh/box_decomposition.hpp"
#include "base/communicator.hpp"

namespace amphora {

class SpatialDecomposition {
 public:
  /// Throws DecompositionError if the box cannot give every rank a subdomain at least
  /// min_width wide in each split direction.
  SpatialDecomposition(const std::array<double, 3>& lo, const std::array<double, 3>& hi,
                       double min_width, const Communicator& comm);

  const Communicator& comm() const { return comm_; }
  /// Subdomain of `rank` as [lo, hi) (the global box's upper faces are inclusive).
  std::array<double, 3> lo(int rank) const;
  std::array<double, 3> hi(int rank) const;
  /// Owner of a point (points outside the box go to the nearest subdomain).
  int owner(const double x[3]) const;
  int neighbor(int d, int side) const { return boxes_.neighbor(comm_.rank(), d, side); }

  /// Sends buffers[r] (records of `record_size` doubles) to rank r and returns everything
  /// received, in rank order. Collective.
  std::vector<double> exchange_all(const std::vector<std::vector<double>>& buffers) const;
  /// Sends `out` to the neighbour across face (d, side) and returns what the neighbour on the
  /// opposite face sent (empty where there is none). Collective over the pair.
  std::vector<double> exchange_face(int d, int side, const std::vector<double>& out) const;
  /// The same where both sides know the sizes (a repeated exchange): n_out doubles from `out`
  /// to the neighbour across (d, side), n_in into `in` from the opposite one. One message.
  void exchange_face(int d, int side, const double* out, int n_out, double* in, int n_in) const;

 private:
  Communicator comm_;
  std::array<double, 3> lo_, hi_;
  double h_[3];
  BoxDecomposition boxes_;
};

}  // namespace amphora
