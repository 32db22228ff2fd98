#pragma once
// Continuous Q_k DoF numbering on a structured box of hexahedra (quadrilaterals in 2D): the
// nodes of all cells form a lattice of n_d k + 1 points per direction (n_d k with periodic
// direction d, whose last layer is the first), numbered lexicographically, x fastest. Cell
// batches are `width` consecutive cells along x, so a batch's lanes read nodes k apart and no
// index array is stored: the index traffic of an unstructured code (4 bytes per cell node) is
// gone. Plain data, copied into kernels by value.
#include "kernels/kokkos_compat.hpp"

namespace amphora::kernels::sumfac {

template <int dim>
struct QkLattice {
  int degree = 1;
  int cells[3] = {1, 1, 1};
  int nodes[3] = {2, 2, 2};  ///< node layers per direction, periodic wrap not applied
  int dofs[3] = {2, 2, 2};   ///< distinct DoFs per direction (nodes - 1 if periodic)
  bool periodic[3] = {false, false, false};
  int dirichlet_faces = 0;  ///< bit 2d: face x_d = lower; bit 2d+1: face x_d = upper
  int shared_faces = 0;     ///< as dirichlet_faces: faces shared with another rank's lattice
  int width = 1;            ///< cells per batch
  int batches_x = 1;        ///< batches per row of cells along x

  static QkLattice create(int degree, const int* cells, const bool* periodic, int dirichlet_faces,
                          int width) {
    QkLattice l;
    l.degree = degree;
    l.width = width;
    l.dirichlet_faces = dirichlet_faces;
    for (int d = 0; d < dim; ++d) {
      l.cells[d] = cells[d];
      l.periodic[d] = periodic[d];
      l.nodes[d] = cells[d] * degree + 1;
      l.dofs[d] = periodic[d] ? cells[d] * degree : l.nodes[d];
    }
    l.batches_x = (cells[0] + width - 1) / width;
    return l;
  }

  KOKKOS_INLINE_FUNCTION long n_dofs() const {
    long n = 1;
    for (int d = 0; d < dim; ++d) n *= dofs[d];
    return n;
  }
  KOKKOS_INLINE_FUNCTION long n_nodes() const {
    long n = 1;
    for (int d = 0; d < dim; ++d) n *= nodes[d];
    return n;
  }
  KOKKOS_INLINE_FUNCTION int n_batches() const {
    int n = batches_x;
    for (int d = 1; d < dim; ++d) n *= cells[d];
    return n;
  }
  /// Cells along the slab direction (the last one). Slabs run in blocks of consecutive
  /// slabs, and the blocks' parity colours the cell loop.
  KOKKOS_INLINE_FUNCTION int n_slabs() const { return cells[dim - 1]; }
  KOKKOS_INLINE_FUNCTION int batches_per_slab() const { return n_batches() / cells[dim - 1]; }

  /// Slabs per block: about 8 blocks, so that one thread runs consecutive slabs and finds the
  /// node layer they share still in cache (with one slab per block it was loaded twice). Fixed
  /// by the lattice, not by the thread count, so the order of the sums is fixed too.
  KOKKOS_INLINE_FUNCTION int slabs_per_block() const {
    const int n = cells[dim - 1];
    return n >= 16 ? n / 8 : 1;
  }
  KOKKOS_INLINE_FUNCTION int n_slab_blocks() const {
    const int r = slabs_per_block();
    return (cells[dim - 1] + r - 1) / r;
  }
  /// Colour of block B: parity, and 2 for the last block of an odd periodic count (it
  /// touches block 0).
  KOKKOS_INLINE_FUNCTION int block_colour(int B) const {
    const int nb = n_slab_blocks();
    return (periodic[dim - 1] && nb % 2 == 1 && nb > 1 && B == nb - 1) ? 2 : B % 2;
  }
  KOKKOS_INLINE_FUNCTION int slab_colour(int s) const {
    return block_colour(s / slabs_per_block());
  }
  /// Whether slab t runs before slab s: an earlier colour, or earlier in the same block.
  KOKKOS_INLINE_FUNCTION bool slab_runs_before(int t, int s) const {
    const int ct = slab_colour(t), cs = slab_colour(s), r = slabs_per_block();
    return ct < cs || (ct == cs && t / r == s / r && t < s);
  }
  /// Node layers (along the last direction) slab s writes first when slabs run by colour:
  /// [first, end). A layer shared with a slab that runs earlier is left to that slab.
  KOKKOS_INLINE_FUNCTION void slab_first_layers(int s, int& first, int& end) const {
    const int n = cells[dim - 1], k = degree;
    const bool per = periodic[dim - 1];
    const int lower = s > 0 ? s - 1 : (per ? n - 1 : -1);
    const int upper = s < n - 1 ? s + 1 : (per ? 0 : -1);
    first = (lower < 0 || lower == s || !slab_runs_before(lower, s)) ? s * k : s * k + 1;
    const bool upper_wraps = per && s == n - 1;
    end = (!upper_wraps && (upper < 0 || !slab_runs_before(upper, s))) ? (s + 1) * k + 1
                                                                       : (s + 1) * k;
  }

  /// Rows of batches in a slab: the rows of cells along direction 1 in 3D, the slab itself in
  /// 2D. One thread runs a slab's rows in order.
  KOKKOS_INLINE_FUNCTION int rows_per_slab() const { return dim == 3 ? cells[1] : 1; }
  /// Node layers along direction 1 that row r of a slab (3D) writes first when rows run in
  /// order: [first, end). The layer shared with row r - 1 is left to it, and so is layer 0 for
  /// the last row of a periodic direction.
  KOKKOS_INLINE_FUNCTION void row_first_layers(int r, int& first, int& end) const {
    const int k = degree;
    first = r == 0 ? 0 : r * k + 1;
    end = (periodic[1] && r == cells[1] - 1) ? (r + 1) * k : (r + 1) * k + 1;
  }

  /// Whether the DoFs a row of batches writes last (slab_last_layers, row_last_layers) form
  /// ranges of lines: not so across a periodic wrap of direction 1 or of the slab direction,
  /// whose last layer is the first.
  KOKKOS_INLINE_FUNCTION bool last_touch_ranges() const {
    return !periodic[dim - 1] && (dim == 2 || !periodic[1]);
  }
  /// Node layers along the last direction that slab s writes last when slabs run by colour:
  /// [first, end). A layer shared with a slab that runs later is left to that slab. Only where
  /// last_touch_ranges().
  KOKKOS_INLINE_FUNCTION void slab_last_layers(int s, int& first, int& end) const {
    const int n = cells[dim - 1], k = degree;
    first = (s == 0 || slab_runs_before(s - 1, s)) ? s * k : s * k + 1;
    end = (s == n - 1 || slab_runs_before(s + 1, s)) ? (s + 1) * k + 1 : (s + 1) * k;
  }
  /// Node layers along direction 1 that row r of a slab (3D) writes last when rows run in
  /// order: [first, end). Only where last_touch_ranges().
  KOKKOS_INLINE_FUNCTION void row_last_layers(int r, int& first, int& end) const {
    const int k = degree;
    first = r * k;
    end = r == cells[1] - 1 ? (r + 1) * k + 1 : (r + 1) * k;
  }

  /// Cell coordinates of lane 0 of batch b: (bx * width, cy, cz).
  KOKKOS_INLINE_FUNCTION void batch_cell(int b, int* c) const {
    c[0] = (b % batches_x) * width;
    const int rest = b / batches_x;
    if constexpr (dim == 2) {
      c[1] = rest;
    } else {
      c[1] = rest % cells[1];
      c[2] = rest / cells[1];
    }
  }
  /// Lanes of the batch that hold real cells (the last batch of a row may be partial).
  KOKKOS_INLINE_FUNCTION int active_lanes(int b) const {
    const int c[3] = {(b % batches_x) * width, 0, 0};
    return active_lanes_at(c);
  }
  /// The same for the batch whose lane 0 is cell c (batch_cell).
  KOKKOS_INLINE_FUNCTION int active_lanes_at(const int* c) const {
    return cells[0] - c[0] < width ? cells[0] - c[0] : width;
  }

  KOKKOS_INLINE_FUNCTION int dof_1d(int d, int node) const {
    return node == dofs[d] ? 0 : node;  // only a periodic direction reaches node == dofs
  }
  KOKKOS_INLINE_FUNCTION bool constrained_1d(int d, int node) const {
    return (node == 0 && (dirichlet_faces >> (2 * d) & 1)) ||
           (node == nodes[d] - 1 && (dirichlet_faces >> (2 * d + 1) & 1));
  }
  /// Global DoF of lattice node (i, j, k), periodic wrap applied.
  KOKKOS_INLINE_FUNCTION long dof_index(const int* node) const {
    long idx = dof_1d(dim - 1, node[dim - 1]);
    for (int d = dim - 2; d >= 0; --d) idx = idx * dofs[d] + dof_1d(d, node[d]);
    return idx;
  }
  /// Index of lattice node in the unwrapped node lattice (coordinates live there).
  KOKKOS_INLINE_FUNCTION long node_index(const int* node) const {
    long idx = node[dim - 1];
    for (int d = dim - 2; d >= 0; --d) idx = idx * nodes[d] + node[d];
    return idx;
  }
  KOKKOS_INLINE_FUNCTION bool constrained(const int* node) const {
    for (int d = 0; d < dim; ++d)
      if (constrained_1d(d, node[d])) return true;
    return false;
  }
  /// Direction d's factor of the number of cells sharing a node whose coordinate d is i (the
  /// number is the product over d; periodic wrap and cells of other ranks across shared faces
  /// counted): 2 on a vertex layer inside or across a periodic or shared face, else 1.
  KOKKOS_INLINE_FUNCTION int multiplicity_1d(int d, int i) const {
    const bool vertex_layer = i % degree == 0;
    const bool boundary =
        !periodic[d] && ((i == 0 && !(shared_faces >> (2 * d) & 1)) ||
                         (i == nodes[d] - 1 && !(shared_faces >> (2 * d + 1) & 1)));
    return (vertex_layer && !boundary) ? 2 : 1;
  }
  /// True if a node of the batch lies on the wrapped last layer of a periodic direction.
  KOKKOS_INLINE_FUNCTION bool wraps(int b) const {
    int c[3];
    batch_cell(b, c);
    return wraps_at(c);
  }
  /// The same for the batch whose lane 0 is cell c (batch_cell).
  KOKKOS_INLINE_FUNCTION bool wraps_at(const int* c) const {
    const int last0 = c[0] + active_lanes_at(c) - 1;
    for (int d = 0; d < dim; ++d)
      if (periodic[d] && (d == 0 ? last0 : c[d]) == cells[d] - 1) return true;
    return false;
  }
};

}  // namespace amphora::kernels::sumfac
