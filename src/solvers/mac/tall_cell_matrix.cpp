#include "solvers/mac/tall_cell_matrix.hpp"

#include <algorithm>
#include <atomic>
#include <stdexcept>
#include <utility>

#include "solvers/mac/row_accumulator.hpp"

namespace amphora::solvers::mac {

namespace {
/// (P^T A P)'s row of the uniform cell (i, j, k) with unknown u (global), gathered: A's row
/// (its diagonal d, -c towards each neighbour) times P, the neighbour's unknowns weighted as
/// T.weights gives them (a neighbour in a tall cell to its two samples). No two neighbours share
/// an unknown, so every entry is one product; a zero weight (the top sample's partner at a
/// tall cell's top row) adds no entry. Entries sorted by column; returns their number (<= 13,
/// as uniform_row_length counts them). The neighbours are visited in the order of the
/// numbering (columns x fastest, each column upwards: -z, -x, -y, the cell, +y, +x, +z), so on
/// one block the entries come sorted and the sort only checks them.
int uniform_row(const mesh::mac::TallCellGrid& T,
                const kernels::mac::PoissonStencil<kernels::HostMemSpace>& A, int i, int j, int k,
                int u, std::pair<int, double>* row) {
  const kernels::mac::MacGrid& g = T.grid();
  const int c = g.index(i, j, k), sy = g.stride_y(), sz = g.stride_z();
  int n = 0;
  const int di[7] = {0, -1, 0, 0, 0, 1, 0}, dj[7] = {0, 0, -1, 0, 1, 0, 0},
            dk[7] = {-1, 0, 0, 0, 0, 0, 1};
  const double cond[7] = {A.cz(c - sz), A.cx(c - 1), A.cy(c - sy), 0.0, A.cy(c), A.cx(c), A.cz(c)};
  for (int f = 0; f < 7; ++f) {
    if (f == 3) {  // the cell itself
      row[n++] = {u, A.diag(c)};
      continue;
    }
    if (cond[f] == 0.0) continue;
    int ids[2];
    double w[2];
    const int m = T.weights(i + di[f], j + dj[f], k + dk[f], ids, w);
    for (int e = 0; e < m; ++e)
      if (w[e] != 0.0) row[n++] = {ids[e], -(cond[f] * w[e])};
  }
  std::sort(row, row + n);
  return n;
}

/// The number of entries uniform_row gives, from the columns alone: the cell, and per neighbour
/// across a face with c != 0 (a fluid cell, so an unknown or a tall cell's row) one entry, or two
/// for a tall cell's inner row (at its bottom and top rows one sample's weight is zero).
int uniform_row_length(const mesh::mac::TallCellGrid& T,
                       const kernels::mac::PoissonStencil<kernels::HostMemSpace>& A, int i, int j,
                       int k) {
  const kernels::mac::MacGrid& g = T.grid();
  const int c = g.index(i, j, k), sy = g.stride_y(), sz = g.stride_z();
  const int di[6] = {0, -1, 0, 0, 1, 0}, dj[6] = {0, 0, -1, 1, 0, 0}, dk[6] = {-1, 0, 0, 0, 0, 1};
  const float cond[6] = {A.cz(c - sz), A.cx(c - 1), A.cy(c - sy), A.cy(c), A.cx(c), A.cz(c)};
  int n = 1;
  for (int f = 0; f < 6; ++f) {
    if (cond[f] == 0.0f) continue;
    const mesh::mac::TallCellColumn& col = T.column(i + di[f], k + dk[f]);
    const int jj = j + dj[f];
    const bool inner = jj > col.terrain && jj + 1 < col.band;  // tall, and neither end row
    n += inner ? 2 : 1;
  }
  return n;
}

/// The rows of the tall cells' samples, from the quadratic form p^T A p = sum_faces c (p_P -
/// p_Q)^2 + sum_cells D p^2 over the faces and cells that touch a tall cell (the uniform rows
/// are gathered apart). Accumulated per tall sample: slot[u] is u's accumulator row (-1 for a
/// uniform unknown).
class TallRows {
 public:
  TallRows(const mesh::mac::TallCellGrid& grid,
           const kernels::mac::PoissonStencil<kernels::HostMemSpace>& stencil)
      : T(grid),
        A(stencil),
        g(grid.grid()),
        sy(g.stride_y()),
        sz(g.stride_z()),
        n(grid.unknowns()),
        first(grid.first_unknown()),
        slot(n, -1),
        tall_rows(number_samples(grid, slot)),
        rows(tall_rows, 0),
        unit(stencil.unit_fluid_faces),
        marked(stencil.surface_free_rows.extent(0) == static_cast<std::size_t>(g.ny) * g.nz) {}

  /// Every tall row's terms. Rows of a column take terms from its own cells and vertical
  /// faces, from the x faces to the columns of its x line and from the z faces to the
  /// neighbouring lines: lines run in parallel (host threads), the z faces in two passes over
  /// lines of one parity, so no row is written by two threads and each row sums its terms in
  /// an order fixed by the grid, not the threads.
  CsrMatrix assemble();
  const std::vector<int>& slots() const { return slot; }

 private:
  static long number_samples(const mesh::mac::TallCellGrid& grid, std::vector<int>& slots) {
    long count = 0;
    for (const mesh::mac::TallCellColumn& col : grid.columns())
      if (col.has_tall_cell())
        for (int s = 0; s < 2; ++s) slots[col.first_unknown + s] = static_cast<int>(count++);
    return count;
  }
  int tall_slot(int global) const {
    const long u = global - first;
    return u >= 0 && u < n ? slot[u] : -1;
  }
  /// += scale v v^T in the tall rows among ids
  void add_outer(const int* ids, const double* v, int m, double scale) {
    for (int a = 0; a < m; ++a) {
      const int s = tall_slot(ids[a]);
      if (s < 0) continue;
      for (int b = 0; b < m; ++b) rows.add(s, ids[b], scale * v[a] * v[b]);
    }
  }
  /// c (p_P - p_Q)^2 for lattice cells P and Q, whatever they map to (zero weights left out)
  void add_face(int iP, int jP, int kP, int iQ, int jQ, int kQ, double c) {
    int ids[4], cell_ids[2];
    double v[4], w[2];
    int m = 0;
    const int nP = T.weights(iP, jP, kP, cell_ids, w);
    for (int e = 0; e < nP; ++e)
      if (w[e] != 0.0) ids[m] = cell_ids[e], v[m++] = w[e];
    const int nQ = T.weights(iQ, jQ, kQ, cell_ids, w);
    for (int e = 0; e < nQ; ++e)
      if (w[e] != 0.0) ids[m] = cell_ids[e], v[m++] = -w[e];
    add_outer(ids, v, m, c);
  }
  static double tall_step(const mesh::mac::TallCellColumn& c) {
    return c.has_tall_cell() ? 1.0 / (c.band - 1 - c.terrain) : 0.0;
  }
  /// What the stencil knows of its values lets most rows of a tall cell go unread (their sums
  /// are the same): rows known free of free-surface terms, and faces between fluid cells with
  /// c = 1 exactly (`unit`), whose sums over rows are sums of small integers, exact in closed
  /// form.
  bool surface_free(int j, int k) const {
    return marked && A.surface_free_rows(A.surface_free_row(j, k)) != 0;
  }
  /// A column's tall cell: the free-surface terms D p^2 of its rows (D = d - sum c: nonzero
  /// only where a row meets air beside it), its inner vertical faces in one block, its top face.
  void column_terms(int i, int k) {
    const auto& d = A.diag;
    const auto &cx = A.cx, &cy = A.cy, &cz = A.cz;
    const mesh::mac::TallCellColumn& col = T.column(i, k);
    if (!col.has_tall_cell()) return;
    const int bot = static_cast<int>(T.global_first_unknown(i, k));
    for (int j = col.terrain; j < col.band; ++j) {
      if (surface_free(j, k)) continue;
      const int c = g.index(i, j, k);
      if (d(c) == 0.0) continue;
      const double D = d(c) - (double(cx(c - 1)) + double(cx(c)) + double(cy(c - sy)) +
                               double(cy(c)) + double(cz(c - sz)) + double(cz(c)));
      if (D == 0.0) continue;
      int ids[2];
      double w[2];
      const int m = T.weights(i, j, k, ids, w);
      add_outer(ids, w, m, D);
    }
    // the faces between its rows: all between fluid cells
    double inside = unit ? double(col.band - 1 - col.terrain) : 0.0;
    if (!unit)
      for (int j = col.terrain; j + 1 < col.band; ++j) inside += cy(g.index(i, j, k));
    if (inside != 0.0) {
      const double dt = tall_step(col);
      const int ids[2] = {bot, bot + 1};
      const double v[2] = {dt, -dt};
      add_outer(ids, v, 2, inside);
    }
    const double top = cy(g.index(i, col.band - 1, k));
    if (top != 0.0 && col.band < g.ny) add_face(i, col.band - 1, k, i, col.band, k, top);
  }
  /// The face between column (i, k) and its +x (dir 0) or +z (dir 1) neighbour, over the rows
  /// where either side is in a tall cell (above them both are uniform: gathered rows).
  void face_terms(int dir, int i, int k) {
    const auto &cx = A.cx, &cz = A.cz;
    const auto& cond = dir == 0 ? cx : cz;
    const int in = i + (dir == 0), kn = k + (dir == 1);
    const mesh::mac::TallCellColumn &col = T.column(i, k), &next = T.column(in, kn);
    if (!col.has_tall_cell() && !next.has_tall_cell()) return;
    const double dc = tall_step(col), dn = tall_step(next);
    // tall against tall: sum_j c_j v(j) v(j)^T with v = (1 - t, t, -(1 - s), -s) linear in
    // j, so from the moments sum c, sum c x, sum c x^2 (x = j - j0, small for accuracy)
    const int j0 = std::max(col.terrain, next.terrain), j_tall = std::min(col.band, next.band);
    const int j_end = std::max(col.band, next.band);
    double m0 = 0.0, m1 = 0.0, m2 = 0.0;
    int j_from = j0;
    if (unit && j_tall > j0) {  // c = 1 on [j0, j_tall), fluid on both sides
      const long long len = j_tall - j0;
      m0 = double(len), m1 = double(len * (len - 1) / 2);
      m2 = double((len - 1) * len * (2 * len - 1) / 6);
      j_from = j_tall;
    }
    for (int j = j_from; j < j_end; ++j) {
      const double c = cond(g.index(i, j, k));
      if (c == 0.0) continue;
      if (j < j_tall) {
        const double x = j - j0;
        m0 += c, m1 += c * x, m2 += c * x * x;
      } else {
        add_face(i, j, k, in, j, kn, c);
      }
    }
    if (m0 != 0.0) {
      // v(j0 + x) = p + q x
      const double t0 = (j0 - col.terrain) * dc, s0 = (j0 - next.terrain) * dn;
      const double p[4] = {1.0 - t0, t0, -(1.0 - s0), -s0}, q[4] = {-dc, dc, dn, -dn};
      const int bot = static_cast<int>(T.global_first_unknown(i, k));
      const int nbot = static_cast<int>(T.global_first_unknown(in, kn));
      const int ids[4] = {bot, bot + 1, nbot, nbot + 1};
      for (int a = 0; a < 4; ++a) {
        const int s = tall_slot(ids[a]);
        if (s < 0) continue;
        for (int b = 0; b < 4; ++b) {  // (a, b) and (b, a) the same expression: exactly symmetric
          const int lo = std::min(a, b), hi = std::max(a, b);
          rows.add(s, ids[b],
                   p[lo] * p[hi] * m0 + (p[lo] * q[hi] + q[lo] * p[hi]) * m1 + q[lo] * q[hi] * m2);
        }
      }
    }
  }

  const mesh::mac::TallCellGrid& T;
  const kernels::mac::PoissonStencil<kernels::HostMemSpace>& A;
  const kernels::mac::MacGrid& g;
  const int sy, sz;
  const long n, first;
  std::vector<int> slot;
  const long tall_rows;
  RowAccumulator<16> rows;
  const bool unit, marked;
};

CsrMatrix TallRows::assemble() {
  // x faces between a column and its +x neighbour, where either is this block's (on a split
  // grid the faces to the ghost ring too: their terms in this block's rows); likewise z faces.
  const auto& nb = T.block().neighbours;
  const int i_lo = nb[0] >= 0 ? -1 : 0,
            i_hi = nb[1] >= 0 ? g.nx : g.nx - 1;  // lower column's range
  const int k_lo = nb[4] >= 0 ? -1 : 0, k_hi = nb[5] >= 0 ? g.nz : g.nz - 1;
  if (tall_rows > 0) {
    Kokkos::parallel_for("amphora::tall::assemble_lines",
                         Kokkos::RangePolicy<kernels::HostExecSpace>(0, g.nz), [&](int k) {
                           for (int i = 0; i < g.nx; ++i) column_terms(i, k);
                           for (int i = i_lo; i < i_hi; ++i) face_terms(0, i, k);
                         });
    for (int parity = 0; parity < 2; ++parity) {
      const int first_line = k_lo + ((parity - k_lo) % 2 + 2) % 2,
                lines = (k_hi - first_line + 1) / 2;
      Kokkos::parallel_for("amphora::tall::assemble_z_faces",
                           Kokkos::RangePolicy<kernels::HostExecSpace>(0, std::max(lines, 0)),
                           [&](int m) {
                             for (int i = 0; i < g.nx; ++i) face_terms(1, i, first_line + 2 * m);
                           });
    }
  }
  return rows.to_csr();
}

/// The matrix from the tall rows and the uniform rows gathered (uniform_row): every row's
/// length first (a uniform row's counted, a tall row's from `tall`), then the rows in place
/// (cheaper than a scratch of 13 entries per unknown filled in the first pass, whose fresh
/// pages cost more than the second walk).
CsrMatrix merge_rows(const mesh::mac::TallCellGrid& T,
                     const kernels::mac::PoissonStencil<kernels::HostMemSpace>& A,
                     const std::vector<int>& slot, const CsrMatrix& tall) {
  const kernels::mac::MacGrid& g = T.grid();
  const long n = T.unknowns(), first = T.first_unknown();
  CsrMatrix M;
  M.n = n;
  M.row_ptr.assign(n + 1, 0);
  const auto for_each_row = [&](const char* name, bool entries, const auto& f) {
    Kokkos::parallel_for(
        name, Kokkos::RangePolicy<kernels::HostExecSpace>(0, g.nx * g.nz), [&](int col) {
          std::pair<int, double> row[13];
          T.for_each_unknown_in_column(col % g.nx, col / g.nx, [&](int u, int i, int j, int k) {
            if (slot[u] < 0) {
              f(u,
                entries ? uniform_row(T, A, i, j, k, static_cast<int>(first + u), row)
                        : uniform_row_length(T, A, i, j, k),
                nullptr, nullptr, row);
              return;
            }
            const long from = tall.row_ptr[slot[u]], length = tall.row_ptr[slot[u] + 1] - from;
            f(u, length, tall.cols.data() + from, tall.values.data() + from, nullptr);
          });
        });
  };
  for_each_row("amphora::tall::row_lengths", false,
               [&](int u, long length, const int*, const double*, const std::pair<int, double>*) {
                 M.row_ptr[u + 1] = length;
               });
  for (long u = 0; u < n; ++u) M.row_ptr[u + 1] += M.row_ptr[u];
  M.cols.resize(M.row_ptr[n]);
  M.values.resize(M.row_ptr[n]);
  std::atomic<bool> lengths_agree{true};
  for_each_row(
      "amphora::tall::rows", true,
      [&](int u, long length, const int* cols, const double* values,
          const std::pair<int, double>* row) {
        const long at = M.row_ptr[u];
        if (at + length != M.row_ptr[u + 1]) {  // never: the lengths pass counts what this writes
          lengths_agree = false;
          return;
        }
        for (long e = 0; e < length; ++e) {
          M.cols[at + e] = row ? row[e].first : cols[e];
          M.values[at + e] = row ? row[e].second : values[e];
        }
      });
  if (!lengths_agree)
    throw std::logic_error(
        "assemble_tall_cell_matrix: a row's entries differ from its counted length");
  return M;
}

}  // namespace

CsrMatrix assemble_tall_cell_matrix(const mesh::mac::TallCellGrid& T,
                                    const kernels::mac::PoissonStencil<kernels::HostMemSpace>& A) {
  TallRows tall(T, A);
  const CsrMatrix rows = tall.assemble();
  return merge_rows(T, A, tall.slots(), rows);
}

}  // namespace amphora::solvers::mac
