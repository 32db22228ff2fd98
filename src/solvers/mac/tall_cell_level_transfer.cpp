#include "solvers/mac/tall_cell_level_transfer.hpp"

#include <string>

#include "kernels/mac/grid_transfer.hpp"
#include "kernels/mac/tall_cell_transfer.hpp"
#include "solvers/csr_rows.hpp"

namespace amphora::solvers::mac {

namespace detail {

/// The coarse cells (one or two) and weights of cell-centred linear interpolation at fine cell
/// f along one direction: 3/4 from the parent, 1/4 from the parent's neighbour on f's side;
/// beyond an edge of the grid the neighbour is the parent reflected, +1/4 at a wall, -1/4 at an
/// open face (grid_transfer.hpp).
KOKKOS_INLINE_FUNCTION int axis_weights(int f, int n_coarse, bool edge_lo, bool edge_hi,
                                        bool wall_lo, bool wall_hi, int index[2],
                                        double weight[2]) {
  const int parent = f >= 0 ? f / 2 : -((1 - f) / 2);  // floor(f / 2): ring cells lie at -1
  const int side = f - 2 * parent;
  index[0] = parent;
  const bool outside = side == 0 ? parent == 0 && edge_lo : parent == n_coarse - 1 && edge_hi;
  if (outside) {
    weight[0] =
        0.75 + kernels::mac::detail::reflected_weight<double>(side == 0 ? wall_lo : wall_hi);
    return 1;
  }
  weight[0] = 0.75;
  index[1] = side == 0 ? parent - 1 : parent + 1;
  weight[1] = 0.25;
  return 2;
}

/// The coarse cells (one or two per axis) and weights interpolating at a fine cell.
struct Trilinear {
  int n[3], index[3][2];
  double weight[3][2];
};

/// The terms of a uniform row: coarse column and weight, one per coarse column, in the order
/// met (at most 8 cells of at most 2 unknowns).
struct FewTerms {
  int id[16];
  double w[16];
  int n = 0;
  KOKKOS_INLINE_FUNCTION void add(int column, int, int, int, bool, int, double v) {
    int t = 0;
    while (t < n && id[t] != column) ++t;
    if (t == n) id[n] = column, w[n++] = 0.0;
    w[t] += v;
  }
};

/// The terms of a tall cell's rows: per coarse column q (of the up to four the interpolation
/// reads) its two tall samples, then its uniform cells from row first[q] up, at fixed places
/// from base[q] in the tall cell's part of a scratch (id -1: no term).
struct DenseTerms {
  int* id;
  double* w0;
  double* w1;
  int base[4], first[4];
  int size = 0;
  KOKKOS_INLINE_FUNCTION void add(int column, int q, int y, int e, bool tall, int side, double v) {
    const int at = base[q] + (tall ? e : 2 + y - first[q]);
    id[at] = column;
    (side == 0 ? w0[at] : w1[at]) += v;
  }
};

/// Q's rows: per row (a fine unknown of the block or of its ring) the interpolation of the
/// coarse unknowns at its carrier cell, a tall cell's fitted over its rows.
template <class MemSpace>
struct TransferRows {
  kernels::mac::TallCellMap<MemSpace> F, C;  ///< the fine and coarse grids
  kernels::mac::MacGrid gf, gc;
  Kokkos::Array<bool, 6> edge, wall;
  Kokkos::View<int*, MemSpace> carriers;  ///< the fine grid's own unknowns' cells
  int n_fine = 0, coarse_ghost_base = 0;
  /// per coarse padded cell: -1 solid, else the number (0..2) of its unknowns, and those
  Kokkos::View<int*, MemSpace> cell_n;
  Kokkos::View<int* [2], MemSpace> cell_id;
  Kokkos::View<double* [2], MemSpace> cell_w;
  /// per row, a tall cell's bottom sample's: the first place of its terms in the scratch
  Kokkos::View<int*, MemSpace> scratch_at;
  Kokkos::View<int*, MemSpace> scratch_id;
  Kokkos::View<double*, MemSpace> scratch_w0, scratch_w1;

  Kokkos::View<int* [3], MemSpace> row_cell;  ///< each row's carrier cell (i, j, k)

  KOKKOS_INLINE_FUNCTION int carrier(int r) const {
    return r < n_fine ? carriers(r) : F.ring.slot_cell(r - n_fine);
  }
  KOKKOS_INLINE_FUNCTION void at(int r, int& i, int& j, int& k) const {
    i = row_cell(r, 0), j = row_cell(r, 1), k = row_cell(r, 2);
  }
  KOKKOS_INLINE_FUNCTION Trilinear trilinear(int i, int j, int k) const {
    Trilinear t;
    const int f[3] = {i, j, k}, nc[3] = {gc.nx, gc.ny, gc.nz};
    for (int d = 0; d < 3; ++d)
      t.n[d] = axis_weights(f[d], nc[d], edge[2 * d], edge[2 * d + 1], wall[2 * d], wall[2 * d + 1],
                            t.index[d], t.weight[d]);
    return t;
  }
  /// += scale * (the coarse pressure interpolated with tri), for sample `side`: the (up to 16)
  /// weights, then the share of the solid cells' weight spread over them.
  template <class Terms>
  KOKKOS_INLINE_FUNCTION void interpolate_at(const Trilinear& tri, int side, double scale,
                                             Terms& terms) const {
    int ids[16], qs[16], ys[16], es[16];
    double ws[16];
    bool talls[16];
    int m = 0;
    double total = 0.0, solid = 0.0;
    for (int c = 0; c < tri.n[2]; ++c)
      for (int b = 0; b < tri.n[1]; ++b)
        for (int a = 0; a < tri.n[0]; ++a) {
          const double w = tri.weight[0][a] * tri.weight[1][b] * tri.weight[2][c];
          total += w;
          const int cell = gc.index(tri.index[0][a], tri.index[1][b], tri.index[2][c]);
          const int n = cell_n(cell);
          if (n < 0) {
            solid += w;
            continue;
          }
          for (int e = 0; e < n; ++e) {
            ids[m] = cell_id(cell, e), ws[m] = w * cell_w(cell, e);
            qs[m] = a + 2 * c, ys[m] = tri.index[1][b], es[m] = e, talls[m++] = n == 2;
          }
        }
    const double share = total - solid > 0.0 ? scale * total / (total - solid) : 0.0;
    for (int e = 0; e < m; ++e)
      terms.add(ids[e], qs[e], ys[e], es[e], talls[e], side, ws[e] * share);
  }

  /// A uniform cell whose eight coarse cells are all uniform fluid cells (no edge, solid, air or
  /// tall cell among them): the trilinear weights themselves, one entry each. emit(column,
  /// value); false (nothing emitted) otherwise.
  template <class Emit>
  KOKKOS_INLINE_FUNCTION bool plain_row(const Trilinear& tri, const Emit& emit) const {
    if (tri.n[0] < 2 || tri.n[1] < 2 || tri.n[2] < 2) return false;
    int cell[8];
    for (int m = 0; m < 8; ++m) {
      cell[m] = gc.index(tri.index[0][m & 1], tri.index[1][(m >> 1) & 1], tri.index[2][m >> 2]);
      if (cell_n(cell[m]) != 1 || cell_w(cell[m], 0) != 1.0) return false;
    }
    for (int m = 0; m < 8; ++m)
      emit(cell_id(cell[m], 0),
           tri.weight[0][m & 1] * tri.weight[1][(m >> 1) & 1] * tri.weight[2][m >> 2]);
    return true;
  }

  /// Row r of Q (a fine unknown of the block, or of its ring from r = n_fine on): emit(column,
  /// value) for each entry, a uniform row's sorted by column (a plain row's in the order of its
  /// eight cells), a tall row's (`tall`) not; returns their number.
  template <class Emit>
  KOKKOS_INLINE_FUNCTION int row(int r, const Emit& emit, bool& tall) const {
    int i, j, k;
    at(r, i, j, k);
    int t, b, f;
    F.column(i, k, t, b, f);
    tall = j < b;
    if (!tall) {  // a uniform cell
      const Trilinear tri = trilinear(i, j, k);
      int n = 0;
      if (plain_row(tri, [&](int c, double v) { emit(c, v), ++n; })) return n;
      FewTerms terms;
      interpolate_at(tri, 0, 1.0, terms);
      for (int a = 1; a < terms.n; ++a)  // by column
        for (int e = a; e > 0 && terms.id[e - 1] > terms.id[e]; --e) {
          const int c = terms.id[e];
          const double v = terms.w[e];
          terms.id[e] = terms.id[e - 1], terms.w[e] = terms.w[e - 1];
          terms.id[e - 1] = c, terms.w[e - 1] = v;
        }
      for (int e = 0; e < terms.n; ++e) emit(terms.id[e], terms.w[e]);
      return terms.n;
    }
    // a tall cell's bottom (j = t) or top (j = t + 1) sample: the terms tall_cell_terms left
    // in the bottom row's part of the scratch
    const int sample = j - t, from = scratch_at(r - sample), to = scratch_at(r - sample + 1);
    const kernels::mac::TallCellGram G(b - t);
    int n = 0;
    for (int e = from; e < to; ++e) {
      if (scratch_id(e) < 0) continue;
      const double a = sample == 0 ? scratch_w0(e) : scratch_w1(e),
                   c = sample == 0 ? scratch_w1(e) : scratch_w0(e);
      emit(scratch_id(e), G.solve(a, c)), ++n;
    }
    return n;
  }

  /// The terms of the tall cell whose bottom sample is row r, in its part of the scratch.
  KOKKOS_INLINE_FUNCTION void tall_cell_terms(int r) const {
    int i, j, k, t, b, f;
    at(r, i, j, k);
    F.column(i, k, t, b, f);
    DenseTerms terms;
    terms.size = dense_size(i, k, t, b, terms.base, terms.first);
    const int at = scratch_at(r);
    terms.id = scratch_id.data() + at;
    terms.w0 = scratch_w0.data() + at;
    terms.w1 = scratch_w1.data() + at;
    for (int e = 0; e < terms.size; ++e) terms.id[e] = -1, terms.w0[e] = 0.0, terms.w1[e] = 0.0;
    tall_terms(i, k, t, b, terms);
  }

  /// The coarse rows the interpolation over rows [t, b) reads, and per coarse column q the
  /// first of its uniform ones (above its tall cell); returns the number of places.
  KOKKOS_INLINE_FUNCTION int dense_size(int i, int k, int t, int b, int base[4],
                                        int first[4]) const {
    const Trilinear tr = trilinear(i, t, k);
    const int y_lo = t / 2 - 1 > 0 ? t / 2 - 1 : 0;
    const int y_hi = (b - 1) / 2 + 1 < gc.ny - 1 ? (b - 1) / 2 + 1 : gc.ny - 1;
    int size = 0;
    for (int q = 0; q < 4; ++q) base[q] = 0, first[q] = 0;
    for (int c = 0; c < tr.n[2]; ++c)
      for (int a = 0; a < tr.n[0]; ++a) {
        const int q = a + 2 * c;
        int tc, bc, fc;
        C.column(tr.index[0][a], tr.index[2][c], tc, bc, fc);
        first[q] = bc > y_lo ? bc : y_lo;
        base[q] = size;
        size += 2 + (y_hi >= first[q] ? y_hi - first[q] + 1 : 0);
      }
    return size;
  }
  /// A tall cell's terms: the least-squares fit G^-1 P^T of the interpolated coarse pressure
  /// over its rows [t, b), G = P^T P in closed form (kernels/mac/tall_cell_transfer.hpp).
  KOKKOS_INLINE_FUNCTION void tall_terms(int i, int k, int t, int b, DenseTerms& terms) const {
    const int L = b - t;
    // Where both coarse rows of the interpolation lie inside the coarse tall cells of all the
    // columns it reads, the interpolated pressure is linear in the fine row (linear
    // interpolation of linear functions), so those rows enter through their two ends.
    int lo = t, hi = b - 1;
    const Trilinear tr = trilinear(i, t, k);  // its coarse columns
    for (int c = 0; c < tr.n[2]; ++c)
      for (int a = 0; a < tr.n[0]; ++a) {
        int tc, bc, fc;
        C.column(tr.index[0][a], tr.index[2][c], tc, bc, fc);
        if (bc <= tc) hi = lo - 1;
        lo = lo > 2 * tc + 1 ? lo : 2 * tc + 1;
        hi = hi < 2 * bc - 2 ? hi : 2 * bc - 2;
      }
    const auto row_by_row = [&](int jj) {
      const double s = double(jj - t) / double(L - 1);
      if (s < 1.0) interpolate_at(trilinear(i, jj, k), 0, 1.0 - s, terms);
      if (s > 0.0) interpolate_at(trilinear(i, jj, k), 1, s, terms);
    };
    const bool linear = lo <= hi;
    for (int jj = t; jj < (linear ? lo : b); ++jj) row_by_row(jj);
    if (!linear) return;
    // sum over x = jj - lo in [0, n) of the sample weights (1 - s, s), s = a + b x, times the
    // ends' weights (1 - lambda, lambda), lambda = c x: power sums of x
    const double n = hi - lo + 1, a = double(lo - t) / double(L - 1), bb = 1.0 / double(L - 1);
    const double c = hi > lo ? 1.0 / double(hi - lo) : 0.0;
    const double sx = 0.5 * n * (n - 1.0), sxx = sx * (2.0 * n - 1.0) / 3.0;
    const double s_sum = a * n + bb * sx, l_sum = c * sx, sl_sum = a * c * sx + bb * c * sxx;
    const double ends[2][2] = {{n - s_sum - l_sum + sl_sum, l_sum - sl_sum},
                               {s_sum - sl_sum, sl_sum}};
    for (int side = 0; side < 2; ++side) {
      interpolate_at(trilinear(i, lo, k), side, ends[side][0], terms);
      if (hi > lo) interpolate_at(trilinear(i, hi, k), side, ends[side][1], terms);
    }
    for (int jj = hi + 1; jj < b; ++jj) row_by_row(jj);
  }
};

/// R = the columns < n of the matrix (row_ptr, cols, values) transposed, each row's entries in
/// increasing column: on a device by atomic counts and places, then each row sorted.
template <class ExecSpace, class Mem>
void transpose_with_atomics(const ExecSpace& exec, const Kokkos::View<int*, Mem>& row_ptr,
                            const Kokkos::View<int*, Mem>& cols,
                            const Kokkos::View<double*, Mem>& values, int n,
                            const Kokkos::View<int*, Mem>& r_ptr, Kokkos::View<int*, Mem>& r_cols,
                            Kokkos::View<double*, Mem>& r_values) {
  using Policy = kernels::RangePolicy<ExecSpace>;
  const int rows = static_cast<int>(row_ptr.extent(0)) - 1;
  Kokkos::parallel_for(
      "amphora::tall_mg::transpose_count", Policy(exec, 0, rows), KOKKOS_LAMBDA(int r) {
        for (int e = row_ptr(r); e < row_ptr(r + 1); ++e)
          if (cols(e) < n) Kokkos::atomic_increment(&r_ptr(cols(e) + 1));
      });
  const std::string label = "amphora::tall_mg::transpose";
  solvers::detail::allocate_entries(r_cols, r_values,
                                    solvers::detail::scan_row_lengths(exec, r_ptr, label), label);
  const Kokkos::View<int*, Mem> next(
      Kokkos::view_alloc(Kokkos::WithoutInitializing, std::string("amphora::tall_mg::r_next")), n);
  const auto rc = r_cols;
  const auto rv = r_values;
  Kokkos::parallel_for(
      "amphora::tall_mg::transpose_next", Policy(exec, 0, n),
      KOKKOS_LAMBDA(int c) { next(c) = r_ptr(c); });
  Kokkos::parallel_for(
      "amphora::tall_mg::transpose_fill", Policy(exec, 0, rows), KOKKOS_LAMBDA(int r) {
        for (int e = row_ptr(r); e < row_ptr(r + 1); ++e) {
          if (cols(e) >= n) continue;
          const int at = Kokkos::atomic_fetch_add(&next(cols(e)), 1);
          rc(at) = r, rv(at) = values(e);
        }
      });
  Kokkos::parallel_for(
      "amphora::tall_mg::transpose_sort", Policy(exec, 0, n),
      KOKKOS_LAMBDA(int c) { solvers::detail::sort_csr_row(rc, rv, r_ptr(c), r_ptr(c + 1)); });
}

/// The same on host threads: each of a few groups of consecutive rows counts and places its
/// entries per column alone, the groups' places one after the other, so every row comes out in
/// increasing column without atomics or a sort.
template <class ExecSpace, class Mem>
void transpose_in_groups(const ExecSpace& exec, const Kokkos::View<int*, Mem>& row_ptr,
                         const Kokkos::View<int*, Mem>& cols,
                         const Kokkos::View<double*, Mem>& values, int n,
                         const Kokkos::View<int*, Mem>& r_ptr, Kokkos::View<int*, Mem>& r_cols,
                         Kokkos::View<double*, Mem>& r_values) {
  using Policy = kernels::RangePolicy<ExecSpace>;
  const int rows = static_cast<int>(row_ptr.extent(0)) - 1;
  const int groups = rows < 2 * exec.concurrency() ? (rows > 0 ? rows : 1) : 2 * exec.concurrency();
  Kokkos::View<int**, Kokkos::LayoutRight, Mem> place("amphora::tall_mg::transpose_places", groups,
                                                      n);
  const auto first_row = [=](int q) { return int(long(q) * rows / groups); };
  Kokkos::parallel_for("amphora::tall_mg::transpose_count", Policy(exec, 0, groups), [=](int q) {
    for (int e = row_ptr(first_row(q)); e < row_ptr(first_row(q + 1)); ++e)
      if (cols(e) < n) ++place(q, cols(e));
  });
  int entries = 0;
  Kokkos::parallel_scan(
      "amphora::tall_mg::transpose_scan", Policy(exec, 0, n + 1),
      [=](int c, int& partial, bool final) {
        if (final) r_ptr(c) = partial;
        if (c == n) return;
        for (int q = 0; q < groups; ++q) {
          const int m = place(q, c);
          if (final) place(q, c) = partial;
          partial += m;
        }
      },
      entries);
  solvers::detail::allocate_entries(r_cols, r_values, entries, "amphora::tall_mg::transpose");
  const auto rc = r_cols;
  const auto rv = r_values;
  Kokkos::parallel_for("amphora::tall_mg::transpose_fill", Policy(exec, 0, groups), [=](int q) {
    for (int r = first_row(q); r < first_row(q + 1); ++r)
      for (int e = row_ptr(r); e < row_ptr(r + 1); ++e) {
        if (cols(e) >= n) continue;
        const int at = place(q, cols(e))++;
        rc(at) = r, rv(at) = values(e);
      }
  });
}

/// The rows of Q for assemble_csr_rows: a tall cell's to be sorted by column.
template <class MemSpace>
struct QRows {
  TransferRows<MemSpace> R;
  template <class Emit>
  KOKKOS_INLINE_FUNCTION bool operator()(int r, const Emit& emit) const {
    bool tall;
    R.row(r, emit, tall);
    return tall;
  }
};

}  // namespace detail

template <class ExecSpace>
TallCellLevelTransfer<typename ExecSpace::memory_space> tall_cell_level_transfer(
    const ExecSpace& exec, const mesh::mac::TallCellGrid& fine,
    const mesh::mac::TallCellGrid& coarse,
    const kernels::mac::PoissonStencil<typename ExecSpace::memory_space>& coarse_A,
    const Kokkos::View<int*, typename ExecSpace::memory_space>& fine_carriers,
    bool device_schedule) {
  using Mem = typename ExecSpace::memory_space;
  using Policy = kernels::RangePolicy<ExecSpace>;
  const auto alloc_int = [](const char* label, long n) {
    return Kokkos::View<int*, Mem>(
        Kokkos::view_alloc(Kokkos::WithoutInitializing, std::string(label)), n);
  };
  detail::TransferRows<Mem> R;
  R.F = fine.map<Mem>();
  R.C = coarse.map<Mem>();
  R.gf = fine.grid(), R.gc = coarse.grid();
  R.edge = coarse_A.edges(), R.wall = coarse_A.walls();
  R.carriers = fine_carriers;
  R.n_fine = static_cast<int>(fine.unknowns());
  R.coarse_ghost_base = static_cast<int>(coarse.unknowns());
  const kernels::mac::MacGrid gc = R.gc;
  // what each coarse cell of the block and its ring gives the interpolation, once per cell
  R.cell_n = alloc_int("amphora::tall_mg::cell_n", gc.padded_size());
  R.cell_id = Kokkos::View<int* [2], Mem>(
      Kokkos::view_alloc(Kokkos::WithoutInitializing, std::string("amphora::tall_mg::cell_id")),
      gc.padded_size());
  R.cell_w = Kokkos::View<double* [2], Mem>(
      Kokkos::view_alloc(Kokkos::WithoutInitializing, std::string("amphora::tall_mg::cell_w")),
      gc.padded_size());
  {
    const auto n = R.cell_n;
    const auto id = R.cell_id;
    const auto w = R.cell_w;
    const auto Cm = R.C;
    const auto solid = coarse_A.solid;
    const auto inverse_diag = coarse_A.inverse_diag;
    const int base = R.coarse_ghost_base;
    Kokkos::parallel_for(
        "amphora::tall_mg::transfer_coarse_cells", Policy(exec, 0, int(gc.padded_size())),
        KOKKOS_LAMBDA(int cell) {
          int i, j, k;
          gc.ijk(cell, i, j, k);
          int ids[2] = {0, 0};
          double ws[2] = {0.0, 0.0};
          int m = 0;
          if (solid(cell))
            m = -1;
          else if (inverse_diag(cell) != 0.0 && j >= 0 && j < gc.ny)
            m = Cm.weights(i, j, k, ids, ws, base);
          n(cell) = m;
          for (int e = 0; e < 2; ++e) id(cell, e) = ids[e], w(cell, e) = ws[e];
        });
  }
  // Q's rows for this block's fine unknowns and its ring's (local fine columns)
  const int rows = R.n_fine + R.F.ring.slots;
  R.row_cell = Kokkos::View<int* [3], Mem>(
      Kokkos::view_alloc(Kokkos::WithoutInitializing, std::string("amphora::tall_mg::row_cells")),
      rows);
  {
    const auto row_cell = R.row_cell;
    Kokkos::parallel_for(
        "amphora::tall_mg::transfer_row_cells", Policy(exec, 0, rows), KOKKOS_LAMBDA(int r) {
          int i, j, k;
          R.gf.ijk(R.carrier(r), i, j, k);
          row_cell(r, 0) = i, row_cell(r, 1) = j, row_cell(r, 2) = k;
        });
  }
  // each tall cell's terms, once, in a scratch: its part at its bottom sample's row
  R.scratch_at = Kokkos::View<int*, Mem>("amphora::tall_mg::scratch_at", rows + 1);
  {
    const auto at = R.scratch_at;
    Kokkos::parallel_for(
        "amphora::tall_mg::transfer_scratch_sizes", Policy(exec, 0, rows), KOKKOS_LAMBDA(int r) {
          int i, j, k, t, b, f, base[4], first[4];
          R.at(r, i, j, k);
          R.F.column(i, k, t, b, f);
          at(r + 1) = j == t && t < b ? R.dense_size(i, k, t, b, base, first) : 0;
        });
  }
  const int scratch =
      solvers::detail::scan_row_lengths(exec, R.scratch_at, "amphora::tall_mg::transfer_scratch");
  R.scratch_id = alloc_int("amphora::tall_mg::scratch_id", scratch);
  R.scratch_w0 = Kokkos::View<double*, Mem>(
      Kokkos::view_alloc(Kokkos::WithoutInitializing, std::string("amphora::tall_mg::scratch_w0")),
      scratch);
  R.scratch_w1 = Kokkos::View<double*, Mem>(
      Kokkos::view_alloc(Kokkos::WithoutInitializing, std::string("amphora::tall_mg::scratch_w1")),
      scratch);
  Kokkos::parallel_for(
      "amphora::tall_mg::transfer_tall_terms", Policy(exec, 0, rows), KOKKOS_LAMBDA(int r) {
        if (R.scratch_at(r + 1) > R.scratch_at(r)) R.tall_cell_terms(r);
      });
  // the rows, a tall cell's sorted by column
  const DeviceCsrMatrix<Mem> Q_all = assemble_csr_rows(
      exec, rows, detail::QRows<Mem>{R}, std::string("amphora::tall_mg::q"), device_schedule);
  const auto row_ptr = Q_all.row_ptr;
  const auto cols = Q_all.cols;
  const auto values = Q_all.values;
  TallCellLevelTransfer<Mem> T;
  T.prolongation.n = R.n_fine;
  T.prolongation.row_ptr = Kokkos::subview(row_ptr, Kokkos::make_pair(0, R.n_fine + 1));
  T.prolongation.cols = cols;
  T.prolongation.values = values;
  // Q^T: this block's coarse rows, from every row of Q (the ring's too), each row's entries
  // sorted by fine column
  const int n_coarse = R.coarse_ghost_base;
  Kokkos::View<int*, Mem> r_ptr("amphora::tall_mg::r_row_ptr", n_coarse + 1);
  Kokkos::View<int*, Mem> r_cols;
  Kokkos::View<double*, Mem> r_values;
  // as assemble_csr_rows: host threads group unless told the device's schedule
  bool atomics = true;
  if constexpr (kernels::runs_on_host_v<ExecSpace>) {
    atomics = device_schedule;
    if (!atomics)
      detail::transpose_in_groups(exec, row_ptr, cols, values, n_coarse, r_ptr, r_cols, r_values);
  }
  if (atomics)
    detail::transpose_with_atomics(exec, row_ptr, cols, values, n_coarse, r_ptr, r_cols, r_values);
  T.restriction.n = n_coarse;
  T.restriction.row_ptr = r_ptr;
  T.restriction.cols = r_cols;
  T.restriction.values = r_values;
  return T;
}

#define AMPHORA_TALL_CELL_TRANSFER(E)                                           \
  template TallCellLevelTransfer<E::memory_space> tall_cell_level_transfer(     \
      const E&, const mesh::mac::TallCellGrid&, const mesh::mac::TallCellGrid&, \
      const kernels::mac::PoissonStencil<E::memory_space>&,                     \
      const Kokkos::View<int*, E::memory_space>&, bool);
AMPHORA_FOR_EACH_EXEC_SPACE(AMPHORA_TALL_CELL_TRANSFER)
#undef AMPHORA_TALL_CELL_TRANSFER

}  // namespace amphora::solvers::mac
