#pragma once
// A box in space split into one rectangular subdomain per rank (a BoxDecomposition over a
// virtual grid of cells at least `min_width` wide), for particles: who owns a point, and who
// the face neighbours are. Ranks exchange packed particle records through it. Periodic
// directions wrap: the neighbours across the box's faces are the ranks at the opposite faces
// (this rank itself where one block spans the direction), and records crossing them are
// images, shifted by the box's length (image_shift).
#include <array>
#include <vector>

#include "base/communicator.hpp"
#include "kernels/spaces.hpp"
#include "mesh/box_decomposition.hpp"

namespace amphora::mesh::particles {

/// SpatialDecomposition::owner as a device-copyable map (the same arithmetic, so the same
/// owner on host and device).
/// Periodic wrapping of points into the box [lo, hi) along its periodic directions (device
/// copyable).
struct PeriodicWrap {
  double lo[3] = {0, 0, 0}, length[3] = {0, 0, 0};
  bool periodic[3] = {false, false, false};
  KOKKOS_INLINE_FUNCTION bool any() const { return periodic[0] || periodic[1] || periodic[2]; }
  /// x(d) moved by whole lengths into [lo, lo + length) where d is periodic.
  KOKKOS_INLINE_FUNCTION double operator()(double x, int d) const {
    if (!periodic[d]) return x;
    const double s = kernels::math::floor((x - lo[d]) / length[d]);
    return s == 0.0 ? x : x - s * length[d];
  }
};

/// The grid a SpatialDecomposition's subdomains are whole blocks of, where a caller sets it (a
/// coupling whose mesh is split so: the flow's cells and slabs along z).
struct DecompositionLayout {
  std::array<int, 3> cells{0, 0, 0};  ///< cells per direction (0: as wide as min_width allows)
  std::array<bool, 3> split{true, true, true};  ///< directions the ranks may be split along
};

struct OwnerMap {
  double lo[3], h[3];
  int cells[3], blocks[3];
  KOKKOS_INLINE_FUNCTION int operator()(double x0, double x1, double x2) const {
    const double x[3] = {x0, x1, x2};
    int c[3];
    for (int d = 0; d < 3; ++d) {
      const int n = cells[d];
      int cell = static_cast<int>(kernels::math::floor((x[d] - lo[d]) / h[d]));
      cell = cell < 0 ? 0 : (cell >= n ? n - 1 : cell);
      const int p = blocks[d], base = n / p, extra = n % p;
      const int long_cells = extra * (base + 1);
      c[d] = cell < long_cells ? cell / (base + 1) : extra + (cell - long_cells) / base;
    }
    return c[0] + blocks[0] * (c[1] + blocks[1] * c[2]);
  }
};

class SpatialDecomposition {
 public:
  /// Throws DecompositionError if the box cannot give every rank a subdomain at least
  /// min_width wide in each split direction (of whole cells of `layout` where it sets them).
  SpatialDecomposition(const std::array<double, 3>& lo, const std::array<double, 3>& hi,
                       double min_width, const Communicator& comm,
                       const std::array<bool, 3>& periodic = {false, false, false},
                       const DecompositionLayout& layout = {});

  const Communicator& comm() const { return comm_; }
  /// Subdomain of `rank` as [lo, hi) (the global box's upper faces are inclusive).
  std::array<double, 3> lo(int rank) const;
  std::array<double, 3> hi(int rank) const;
  /// Owner of a point (points outside the box go to the nearest subdomain).
  int owner(const double x[3]) const;
  int neighbor(int d, int side) const { return boxes_.neighbor(comm_.rank(), d, side); }
  bool periodic(int d) const { return boxes_.periodic(d); }
  /// The shift of the positions that arrive on the exchange across face (d, side): they come
  /// from the neighbour across the opposite face, so +length(d) where side 0 receives across the
  /// box's upper face, -length(d) where side 1 receives across its lower one, else 0.
  double image_shift(int d, int side) const;
  PeriodicWrap wrap() const;
  /// owner() for kernels.
  OwnerMap owner_map() const {
    OwnerMap m;
    for (int d = 0; d < 3; ++d) {
      m.lo[d] = lo_[d], m.h[d] = h_[d];
      m.cells[d] = boxes_.global_cells()[d], m.blocks[d] = boxes_.blocks()[d];
    }
    return m;
  }

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

}  // namespace amphora::mesh::particles
