#pragma once
// Reading and writing the nodal values of one cell batch of a Q_k lattice (QkLattice): the
// gather/scatter half of every matrix-free kernel (operators, transfers, error norms).
#include "kernels/prefetch.hpp"
#include "kernels/sumfac/qk_lattice.hpp"
#include "kernels/sumfac/simd.hpp"
#include "kernels/sumfac/strided_lanes.hpp"

namespace amphora::kernels::sumfac {

template <int dim, int n_p, int W>
struct BatchDofAccess {
  using T = Simd<W>;
  static constexpr int n_dofs = dim == 2 ? n_p * n_p : n_p * n_p * n_p;
  QkLattice<dim> lattice;

  /// Lattice node of local node `n` of lane 0's cell, and the per-lane stride along x.
  KOKKOS_INLINE_FUNCTION void local_node(const int* cell, int n, int* node) const {
    node[0] = cell[0] * lattice.degree + n % n_p;
    node[1] = cell[1] * lattice.degree + (n / n_p) % n_p;
    if constexpr (dim == 3) node[2] = cell[2] * lattice.degree + n / (n_p * n_p);
  }

  /// Where a batch's nodes live: per lane and x-node an offset, per (y, z) row a base, and
  /// which of them are constrained. The fast batches (full, interior, no periodic wrap) need
  /// only `start`: lane l, node i of row r is at rows[r] + start + l k + i.
  static constexpr int n_rows = n_dofs / n_p;
  struct BatchIndex {
    bool fast;     ///< full batch, no periodic wrap: contiguous addressing
    bool x_lower;  ///< fast batch on a Dirichlet face x = lower: lane 0, node 0 constrained
    bool x_upper;  ///< ... x = upper: lane W-1, node k constrained
    int active;
    long start;
    long rows[n_rows];
    bool row_constrained[n_rows];
    int x[W][n_p];
    bool x_constrained[W][n_p];
  };

  KOKKOS_INLINE_FUNCTION void batch_index(int b, BatchIndex& ix) const {
    int cell[3];
    lattice.batch_cell(b, cell);
    row_index(cell, ix);
    lane_index(cell, ix);
  }
  /// The part of batch_index that depends on the row of cells only (rows, row_constrained):
  /// the same for every batch of the row, so a kernel running a row forms it once.
  KOKKOS_INLINE_FUNCTION void row_index(const int* cell, BatchIndex& ix) const {
    const int k = lattice.degree;
    const long sx = lattice.dofs[0], sxy = sx * lattice.dofs[1];
    for (int r = 0; r < n_rows; ++r) {
      const int ny = cell[1] * k + r % n_p;
      const int nz = dim == 3 ? cell[2] * k + r / n_p : 0;
      ix.rows[r] = sx * lattice.dof_1d(1, ny) + (dim == 3 ? sxy * lattice.dof_1d(2, nz) : 0);
      ix.row_constrained[r] =
          lattice.constrained_1d(1, ny) || (dim == 3 && lattice.constrained_1d(2, nz));
    }
  }
  /// The rest, for the batch whose lane 0 is cell `cell` (batch_cell), after row_index for its
  /// row.
  KOKKOS_INLINE_FUNCTION void lane_index(const int* cell, BatchIndex& ix) const {
    const int k = lattice.degree;
    ix.active = lattice.active_lanes_at(cell);
    ix.fast = ix.active == W && !lattice.wraps_at(cell);
    ix.x_lower = cell[0] == 0 && (lattice.dirichlet_faces & 1);
    ix.x_upper = cell[0] + W == lattice.cells[0] && (lattice.dirichlet_faces >> 1 & 1);
    ix.start = static_cast<long>(cell[0]) * k;
    if (ix.fast) return;
    for (int l = 0; l < W; ++l)
      for (int i = 0; i < n_p; ++i) {
        const int nx = (cell[0] + (l < ix.active ? l : ix.active - 1)) * k + i;
        ix.x[l][i] = lattice.dof_1d(0, nx);
        ix.x_constrained[l][i] = lattice.constrained_1d(0, nx);
      }
  }

  /// u = src at the batch's nodes (DoF lattice); constrained DoFs read as zero (unless
  /// `constrained` is false: a component without Dirichlet conditions, as a pressure).
  KOKKOS_INLINE_FUNCTION void gather(const double* src, const BatchIndex& ix, T* u,
                                     bool constrained = true) const {
    const int k = lattice.degree;
    if (ix.fast) {
      for (int r = 0; r < n_rows; ++r) {
        if (constrained && ix.row_constrained[r]) {
          for (int i = 0; i < n_p; ++i) u[r * n_p + i] = T(0.0);
          continue;
        }
        const double* p = src + ix.rows[r] + ix.start;
        // each row's lines asked into L1 four rows ahead of their loads (from degree 5 they
        // were prefetched to L2 a batch ahead): the indirect rows defeat the hardware
        // prefetcher
        if constexpr (n_p >= 3) {
          constexpr int ahead = 4;
          if (r + ahead < n_rows) prefetch_row<into_l1>(src + ix.rows[r + ahead] + ix.start, false);
        }
        // compile-time stride up to degree 3; above, the loop below measured faster
        // (perf samples of the gather/scatter against apply_local, LaplaceDealii, 1 thread)
        if (n_p <= 4 && k == n_p - 1) {
          read_strided_row<n_p - 1, W>(p, u + r * n_p);
        } else {
          for (int i = 0; i < n_p; ++i) {
            T& v = u[r * n_p + i];
            for (int l = 0; l < W; ++l) v[l] = p[l * k + i];
          }
        }
        if (constrained && ix.x_lower) u[r * n_p][0] = 0.0;
        if (constrained && ix.x_upper) u[r * n_p + n_p - 1][W - 1] = 0.0;
      }
      return;
    }
    for (int r = 0; r < n_rows; ++r) {
      const double* p = src + ix.rows[r];
      for (int i = 0; i < n_p; ++i) {
        T& v = u[r * n_p + i];
        for (int l = 0; l < W; ++l)
          v[l] = constrained && (ix.row_constrained[r] || ix.x_constrained[l][i]) ? 0.0
                                                                                  : p[ix.x[l][i]];
      }
    }
  }

  /// dst += u at the batch's nodes, inactive lanes skipped. Constrained DoFs may receive
  /// contributions (fast batches on an x face): callers overwrite them afterwards. With
  /// `constrained` false, every node receives its part.
  template <bool atomic>
  KOKKOS_INLINE_FUNCTION void scatter_add(double* dst, const BatchIndex& ix, const T* u,
                                          bool constrained = true) const {
    const int k = lattice.degree;
    if (ix.fast) {
      for (int r = 0; r < n_rows; ++r) {
        if (constrained && ix.row_constrained[r]) continue;
        double* p = dst + ix.rows[r] + ix.start;
        if constexpr (!atomic && n_p > 1) {
          if (k == n_p - 1) {
            add_strided_row<n_p - 1, W>(p, u + r * n_p);
            continue;
          }
        }
        for (int i = 0; i < n_p; ++i)
          for (int l = 0; l < W; ++l) add<atomic>(p + l * k + i, u[r * n_p + i][l]);
      }
      return;
    }
    for (int r = 0; r < n_rows; ++r) {
      if (constrained && ix.row_constrained[r]) continue;
      double* p = dst + ix.rows[r];
      for (int i = 0; i < n_p; ++i)
        for (int l = 0; l < ix.active; ++l)
          if (!constrained || !ix.x_constrained[l][i])
            add<atomic>(p + ix.x[l][i], u[r * n_p + i][l]);
    }
  }

  /// Whether kernels prefetch a batch's rows: from n_p = 6 (degree 5), where it measured
  /// faster (LaplaceDealii/5 and 6, 1 and 2 threads). At degrees 2-4 a prefetch of the next
  /// batch measured slower (the hardware prefetcher follows those fewer rows by itself).
  static constexpr bool prefetch_rows = n_rows > 32;

  /// Asks for the cache lines of a fast batch's rows, moved along them by `shift` entries (the
  /// next batch of the row: W k), to be brought into L2 (for writing with `write`). A hint:
  /// does nothing on devices (prefetch_line).
  KOKKOS_INLINE_FUNCTION void prefetch(const double* base, const BatchIndex& ix, bool write,
                                       long shift = 0) const {
    if (!ix.fast) return;
    for (int r = 0; r < n_rows; ++r)
      prefetch_row<into_l2>(base + ix.rows[r] + ix.start + shift, write);
  }
  /// The lines of one fast row of a batch (its W cells' nodes, W k + 1 entries) from p.
  template <int target>
  KOKKOS_FORCEINLINE_FUNCTION void prefetch_row(const double* p, bool write) const {
    const int len = W * lattice.degree + 1;
    for (int m = 0; m < len; m += 8) prefetch_line<target>(p + m, write);  // one per 64-byte line
  }

  template <bool atomic>
  KOKKOS_INLINE_FUNCTION static void add(double* p, double v) {
    if constexpr (atomic)
      Kokkos::atomic_add(p, v);
    else
      *p += v;
  }

  /// f(n, l, node) for every local node n and lane l of batch b, with the lattice node of that
  /// lane's cell (lanes past the last cell of a partial batch repeat it). The general path,
  /// for setup and fields: no fast addressing.
  template <class F>
  KOKKOS_INLINE_FUNCTION void for_each_lane_node(int b, const F& f) const {
    int cell[3];
    lattice.batch_cell(b, cell);
    const int active = lattice.active_lanes(b);
    for (int n = 0; n < n_dofs; ++n) {
      int node[3];
      local_node(cell, n, node);
      const int x0 = node[0];
      for (int l = 0; l < W; ++l) {
        node[0] = x0 + (l < active ? l : active - 1) * lattice.degree;
        f(n, l, node);
      }
    }
  }

  /// x = a blocked field on the unwrapped node lattice (coordinates), lanes clamped.
  KOKKOS_INLINE_FUNCTION void gather_nodes(const double* src, int b, T* x) const {
    for_each_lane_node(
        b, [&](int n, int l, const int* node) { x[n][l] = src[lattice.node_index(node)]; });
  }

  /// u = src at the batch's nodes, constrained DoFs included (fields, not unknowns).
  KOKKOS_INLINE_FUNCTION void gather_unconstrained(const double* src, int b, T* u) const {
    for_each_lane_node(
        b, [&](int n, int l, const int* node) { u[n][l] = src[lattice.dof_index(node)]; });
  }

  /// Inverse multiplicities of the batch's nodes (cells sharing each node), lanes clamped: the
  /// product of one factor per direction (QkLattice::multiplicity_1d), so n_p (W + dim - 1)
  /// factors instead of n_dofs W multiplicities (transfers take it every application).
  KOKKOS_INLINE_FUNCTION void inverse_multiplicity(int b, T* w) const {
    int cell[3] = {0, 0, 0};
    lattice.batch_cell(b, cell);
    const int active = lattice.active_lanes(b), k = lattice.degree;
    T wx[n_p];
    double wy[n_p], wz[n_p];
    const auto inv = [&](int d, int node) {
      return lattice.multiplicity_1d(d, node) == 2 ? 0.5 : 1.0;
    };
    for (int i = 0; i < n_p; ++i) {
      for (int l = 0; l < W; ++l)
        wx[i][l] = inv(0, (cell[0] + (l < active ? l : active - 1)) * k + i);
      wy[i] = inv(1, cell[1] * k + i);
      wz[i] = dim == 3 ? inv(dim - 1, cell[dim - 1] * k + i) : 1.0;
    }
    int n = 0;
    for (int iz = 0; iz < (dim == 3 ? n_p : 1); ++iz)
      for (int iy = 0; iy < n_p; ++iy) {
        const T s(wy[iy] * wz[iz]);
        for (int ix = 0; ix < n_p; ++ix, ++n) w[n] = wx[ix] * s;
      }
  }
};

}  // namespace amphora::kernels::sumfac
