#include "solvers/mac/tall_cell_matrix.hpp"

#include "solvers/csr_rows.hpp"

#include <stdexcept>
#include <string>

namespace amphora::solvers::mac {

namespace detail {

/// The entries of one row under construction: the tall samples' columns (the row's own two and
/// its four neighbours' two each) accumulated in slots, in the order the terms come; a uniform
/// cell's column, which one term gives (no two terms of a row share one), handed on at once.
struct TallRowSlots {
  int id[10];
  double value[10];
  int n = 0;
  KOKKOS_INLINE_FUNCTION void add(int column, double v) {
    for (int e = 0; e < n; ++e)
      if (id[e] == column) {
        value[e] += v;
        return;
      }
    id[n] = column, value[n++] = v;  // at most 10 tall samples touch a tall row
  }
};

/// P^T A P's rows of a block's unknowns. A uniform row is gathered from A's row (uniform_row);
/// a tall sample's row from the terms of the quadratic form that touch its tall cell
/// (tall_row): its cells' free-surface terms, its inner faces in one block, its top face, and
/// the faces to its four neighbouring columns, in the order of the one-pass assembly this
/// replaced (own terms, -x, +x, then the z faces by the line's parity), so each entry sums its
/// terms in an order fixed by the grid.
template <class MemSpace>
struct TallCellRows {
  kernels::mac::TallCellMap<MemSpace> T;
  kernels::mac::PoissonStencil<MemSpace> A;
  Kokkos::View<int*, MemSpace> carrier;  ///< each unknown's lattice cell
  /// per column with a tall cell its free-surface terms' sums (surface_terms), -1 in the first
  /// where it has none
  Kokkos::View<double* [4], MemSpace> surface;
  int ghost_base = -1;  ///< local columns from here on for the ring, or global
  bool unit = false, marked = false;
  bool face[4] = {false, false, false, false};  ///< a neighbouring block at -x, +x, -z, +z

  KOKKOS_INLINE_FUNCTION const kernels::mac::MacGrid& g() const { return T.own.grid; }
  /// The column number of this block's unknown u.
  KOKKOS_INLINE_FUNCTION int own_id(int u) const {
    return ghost_base >= 0 ? u : static_cast<int>(T.first + u);
  }
  KOKKOS_INLINE_FUNCTION int weights(int i, int j, int k, int u[2], double w[2]) const {
    return T.weights(i, j, k, u, w, ghost_base);
  }
  /// The column of column (i, k)'s bottom sample (it has a tall cell).
  KOKKOS_INLINE_FUNCTION int bottom_id(int i, int k) const {
    int t, b, f;
    T.column(i, k, t, b, f);
    int u[2] = {0, 0};
    double w[2];
    weights(i, t, k, u, w);
    return u[0];
  }
  KOKKOS_INLINE_FUNCTION static double tall_step(int t, int b) {
    return b > t ? 1.0 / (b - 1 - t) : 0.0;
  }
  KOKKOS_INLINE_FUNCTION bool surface_free(int j, int k) const {
    return marked && A.surface_free_rows(A.surface_free_row(j, k)) != 0;
  }

  /// emit(column, value) for each entry of row u, unsorted; returns their number.
  template <class Emit>
  KOKKOS_INLINE_FUNCTION int row(int u, const Emit& emit) const {
    int i, j, k;
    g().ijk(carrier(u), i, j, k);
    int t, b, f;
    T.column(i, k, t, b, f);
    if (j >= b) return uniform_row(i, j, k, own_id(u), emit);
    return tall_row(i, k, own_id(u), emit);
  }

  /// A's row (its diagonal d, -c towards each neighbour) times P: a neighbour's unknowns
  /// weighted as T.weights gives them; a zero weight adds no entry.
  template <class Emit>
  KOKKOS_INLINE_FUNCTION int uniform_row(int i, int j, int k, int self, const Emit& emit) const {
    const int c = g().index(i, j, k), sy = g().stride_y(), sz = g().stride_z();
    const int di[7] = {0, -1, 0, 0, 0, 1, 0}, dj[7] = {0, 0, -1, 0, 1, 0, 0},
              dk[7] = {-1, 0, 0, 0, 0, 0, 1};
    const double cond[7] = {A.cz(c - sz), A.cx(c - 1), A.cy(c - sy), 0.0,
                            A.cy(c),      A.cx(c),     A.cz(c)};
    int n = 0;
    for (int f = 0; f < 7; ++f) {
      if (f == 3) {
        emit(self, A.diag(c)), ++n;
        continue;
      }
      if (cond[f] == 0.0) continue;
      int ids[2];
      double w[2];
      const int m = weights(i + di[f], j + dj[f], k + dk[f], ids, w);
      for (int e = 0; e < m; ++e)
        if (w[e] != 0.0) emit(ids[e], -(cond[f] * w[e])), ++n;
    }
    return n;
  }

  /// c (p_P - p_Q)^2's terms in row `self`: the tall samples' into slots, a uniform cell's
  /// emitted (zero weights left out).
  template <class Emit>
  KOKKOS_INLINE_FUNCTION int add_face(int self, int iP, int jP, int kP, int iQ, int jQ, int kQ,
                                      double c, TallRowSlots& slots, const Emit& emit) const {
    int ids[4], cell_ids[2];
    double v[4], w[2];
    bool tall[4];
    int m = 0;
    const int nP = weights(iP, jP, kP, cell_ids, w);
    for (int e = 0; e < nP; ++e)
      if (w[e] != 0.0) ids[m] = cell_ids[e], v[m] = w[e], tall[m++] = nP == 2;
    const int nQ = weights(iQ, jQ, kQ, cell_ids, w);
    for (int e = 0; e < nQ; ++e)
      if (w[e] != 0.0) ids[m] = cell_ids[e], v[m] = -w[e], tall[m++] = nQ == 2;
    int emitted = 0;
    for (int a = 0; a < m; ++a) {
      if (ids[a] != self) continue;
      for (int b = 0; b < m; ++b) {
        const double value = c * v[a] * v[b];
        if (tall[b])
          slots.add(ids[b], value);
        else
          emit(ids[b], value), ++emitted;
      }
    }
    return emitted;
  }

  /// The face between columns (iL, kL) and (iL, kL) + e_dir (dir 0: x, 1: z), over the rows
  /// where either side is in a tall cell, in row `self` (of one of the two columns' samples).
  template <class Emit>
  KOKKOS_INLINE_FUNCTION int face_terms(int self, int dir, int iL, int kL, TallRowSlots& slots,
                                        const Emit& emit) const {
    const int iU = iL + (dir == 0), kU = kL + (dir == 1);
    int tL, bL, fL, tU, bU, fU;
    T.column(iL, kL, tL, bL, fL);
    T.column(iU, kU, tU, bU, fU);
    if (bL <= tL && bU <= tU) return 0;
    const double dc = tall_step(tL, bL), dn = tall_step(tU, bU);
    const int j0 = tL > tU ? tL : tU, j_tall = bL < bU ? bL : bU, j_end = bL > bU ? bL : bU;
    double m0 = 0.0, m1 = 0.0, m2 = 0.0;
    int j_from = j0, emitted = 0;
    if (unit && j_tall > j0) {  // c = 1 on [j0, j_tall), fluid on both sides
      const long long len = j_tall - j0;
      m0 = double(len), m1 = double(len * (len - 1) / 2);
      m2 = double((len - 1) * len * (2 * len - 1) / 6);
      j_from = j_tall;
    }
    for (int j = j_from; j < j_end; ++j) {
      const int cell = g().index(iL, j, kL);
      const double c = dir == 0 ? A.cx(cell) : A.cz(cell);
      if (c == 0.0) continue;
      if (j < j_tall) {
        const double x = j - j0;
        m0 += c, m1 += c * x, m2 += c * x * x;
      } else {
        emitted += add_face(self, iL, j, kL, iU, j, kU, c, slots, emit);
      }
    }
    if (m0 == 0.0) return emitted;
    // v(j0 + x) = p + q x
    const double t0 = (j0 - tL) * dc, s0 = (j0 - tU) * dn;
    const double p[4] = {1.0 - t0, t0, -(1.0 - s0), -s0}, q[4] = {-dc, dc, dn, -dn};
    const int bot = bottom_id(iL, kL), nbot = bottom_id(iU, kU);
    const int ids[4] = {bot, bot + 1, nbot, nbot + 1};
    for (int a = 0; a < 4; ++a) {
      if (ids[a] != self) continue;
      for (int b = 0; b < 4; ++b) {  // (a, b) and (b, a) the same expression: exactly symmetric
        const int lo = a < b ? a : b, hi = a < b ? b : a;
        slots.add(ids[b],
                  p[lo] * p[hi] * m0 + (p[lo] * q[hi] + q[lo] * p[hi]) * m1 + q[lo] * q[hi] * m2);
      }
    }
    return emitted;
  }

  /// The free-surface terms D p^2 (D = d - sum c: nonzero only where a row meets air beside it)
  /// of column (i, k)'s tall cell, in its two samples' rows: surface(col, 2 a + e) = sum_j D_j
  /// w_a(j) w_e(j) over its rows upwards, or -1 in surface(col, 0) where no row has a term.
  KOKKOS_INLINE_FUNCTION void surface_terms(int i, int k) const {
    const kernels::mac::MacGrid& G = g();
    const int sy = G.stride_y(), sz = G.stride_z(), col = i + G.nx * k;
    int t, b, f;
    T.column(i, k, t, b, f);
    double sum[4] = {0.0, 0.0, 0.0, 0.0};
    bool any = false;
    for (int j = t; j < b; ++j) {
      if (surface_free(j, k)) continue;
      const int c = G.index(i, j, k);
      if (A.diag(c) == 0.0) continue;
      const double D = A.diag(c) - (double(A.cx(c - 1)) + double(A.cx(c)) + double(A.cy(c - sy)) +
                                    double(A.cy(c)) + double(A.cz(c - sz)) + double(A.cz(c)));
      if (D == 0.0) continue;
      const double s = double(j - t) / double(b - 1 - t), w[2] = {1.0 - s, s};
      for (int a = 0; a < 2; ++a)
        for (int e = 0; e < 2; ++e) {
          const double v = D * w[a] * w[e];
          sum[2 * a + e] = any ? sum[2 * a + e] + v : v;
        }
      any = true;
    }
    for (int e = 0; e < 4; ++e) surface(col, e) = sum[e];
    if (!any) surface(col, 0) = -1.0;
  }

  /// Row `self`, a sample of column (i, k)'s tall cell.
  template <class Emit>
  KOKKOS_INLINE_FUNCTION int tall_row(int i, int k, int self, const Emit& emit) const {
    const kernels::mac::MacGrid& G = g();
    int t, b, f;
    T.column(i, k, t, b, f);
    TallRowSlots slots;
    int emitted = 0;
    // the free-surface terms, summed per column by surface_terms
    const int bot = bottom_id(i, k), col = i + G.nx * k;
    if (surface(col, 0) >= 0.0) {
      const int a = self - bot;
      slots.add(bot, surface(col, 2 * a));
      slots.add(bot + 1, surface(col, 2 * a + 1));
    }
    // the faces between its rows (all between fluid cells) in one block
    double inside = unit ? double(b - 1 - t) : 0.0;
    if (!unit)
      for (int j = t; j + 1 < b; ++j) inside += A.cy(G.index(i, j, k));
    if (inside != 0.0) {
      const double dt = tall_step(t, b);
      const double v[2] = {dt, -dt};
      const int a = self - bot;
      for (int e = 0; e < 2; ++e) slots.add(bot + e, inside * v[a] * v[e]);
    }
    const double top = A.cy(G.index(i, b - 1, k));
    if (top != 0.0 && b < G.ny) emitted += add_face(self, i, b - 1, k, i, b, k, top, slots, emit);
    // the faces to the neighbouring columns
    if (i > 0 || face[0]) emitted += face_terms(self, 0, i - 1, k, slots, emit);
    if (i + 1 < G.nx || face[1]) emitted += face_terms(self, 0, i, k, slots, emit);
    const bool lower_first = k % 2 != 0;  // the z faces' passes: even lines first
    for (int pass = 0; pass < 2; ++pass) {
      if (pass == (lower_first ? 0 : 1)) {
        if (k > 0 || face[2]) emitted += face_terms(self, 1, i, k - 1, slots, emit);
      } else {
        if (k + 1 < G.nz || face[3]) emitted += face_terms(self, 1, i, k, slots, emit);
      }
    }
    for (int e = 0; e < slots.n; ++e) emit(slots.id[e], slots.value[e]);
    return emitted + slots.n;
  }
};

/// The rows for assemble_csr_rows, each to be sorted by column.
template <class MemSpace>
struct SortedRows {
  TallCellRows<MemSpace> R;
  template <class Emit>
  KOKKOS_INLINE_FUNCTION bool operator()(int u, const Emit& emit) const {
    R.row(u, emit);
    return true;
  }
};

}  // namespace detail

template <class ExecSpace>
Kokkos::View<int*, typename ExecSpace::memory_space> tall_cell_carriers(
    const ExecSpace& exec, const mesh::mac::TallCellGrid& T) {
  using Mem = typename ExecSpace::memory_space;
  const kernels::mac::TallCellLayout<Mem> L = T.layout<Mem>();
  const kernels::mac::MacGrid g = L.grid;
  Kokkos::View<int*, Mem> carrier(
      Kokkos::view_alloc(Kokkos::WithoutInitializing, std::string("amphora::tall::carriers")),
      T.unknowns());
  Kokkos::parallel_for(
      "amphora::tall::carriers", kernels::RangePolicy<ExecSpace>(exec, 0, g.nx * g.nz),
      KOKKOS_LAMBDA(int col) {
        const int i = col % g.nx, k = col / g.nx;
        const int t = L.terrain(col), b = L.band(col);
        int u = L.first_unknown(col);
        if (b > t) {
          carrier(u++) = g.index(i, t, k);
          carrier(u++) = g.index(i, t + 1, k);
        }
        for (int j = b; j < g.ny; ++j) {
          const int c = g.index(i, j, k);
          if (L.cell_unknown(c) >= 0) carrier(u++) = c;
        }
      });
  return carrier;
}

template <class ExecSpace>
DeviceCsrMatrix<typename ExecSpace::memory_space> assemble_tall_cell_matrix(
    const ExecSpace& exec, const mesh::mac::TallCellGrid& T,
    const kernels::mac::PoissonStencil<typename ExecSpace::memory_space>& A, bool local_columns,
    Kokkos::View<int*, typename ExecSpace::memory_space> carriers, bool device_schedule) {
  using Mem = typename ExecSpace::memory_space;
  const int n = static_cast<int>(T.unknowns());
  detail::TallCellRows<Mem> R;
  R.T = T.map<Mem>();
  R.A = A;
  R.carrier = carriers.data() != nullptr ? carriers : tall_cell_carriers(exec, T);
  R.ghost_base = local_columns ? n : -1;
  R.unit = A.unit_fluid_faces;
  R.marked = A.surface_free_rows.extent(0) == static_cast<std::size_t>(A.grid.ny) * A.grid.nz;
  const auto& nb = T.block().neighbours;
  R.face[0] = nb[0] >= 0, R.face[1] = nb[1] >= 0, R.face[2] = nb[4] >= 0, R.face[3] = nb[5] >= 0;
  const kernels::mac::MacGrid g = A.grid;
  R.surface = Kokkos::View<double* [4], Mem>(
      Kokkos::view_alloc(Kokkos::WithoutInitializing, std::string("amphora::tall::surface_terms")),
      g.nx * g.nz);
  const auto band = R.T.own.band, terrain = R.T.own.terrain;
  Kokkos::parallel_for(
      "amphora::tall::surface_terms", kernels::RangePolicy<ExecSpace>(exec, 0, g.nx * g.nz),
      KOKKOS_LAMBDA(int col) {
        if (band(col) > terrain(col)) R.surface_terms(col % g.nx, col / g.nx);
      });
  DeviceCsrMatrix<Mem> M = assemble_csr_rows(exec, n, detail::SortedRows<Mem>{R},
                                             std::string("amphora::tall::matrix"), device_schedule);
  M.inverse_diagonal =
      Kokkos::View<double*, Mem>(Kokkos::view_alloc(Kokkos::WithoutInitializing,
                                                    std::string("amphora::tall::inverse_diagonal")),
                                 n);
  const auto row_ptr = M.row_ptr;
  const auto cols = M.cols;
  const auto values = M.values;
  const auto inverse_diagonal = M.inverse_diagonal;
  Kokkos::parallel_for(
      "amphora::tall::inverse_diagonal", kernels::RangePolicy<ExecSpace>(exec, 0, n),
      KOKKOS_LAMBDA(int u) {
        const int self = R.own_id(u);
        double d = 0.0;
        for (int e = row_ptr(u); e < row_ptr(u + 1); ++e)
          if (cols(e) == self) d = values(e);
        inverse_diagonal(u) = d != 0.0 ? 1.0 / d : 0.0;
      });
  return M;
}

CsrMatrix assemble_tall_cell_matrix(const mesh::mac::TallCellGrid& T,
                                    const kernels::mac::PoissonStencil<kernels::HostMemSpace>& A) {
  return to_csr_matrix(assemble_tall_cell_matrix(kernels::HostExecSpace(), T, A, false));
}

#define AMPHORA_TALL_CELL_MATRIX(E)                                                                \
  template Kokkos::View<int*, E::memory_space> tall_cell_carriers(const E&,                        \
                                                                  const mesh::mac::TallCellGrid&); \
  template DeviceCsrMatrix<E::memory_space> assemble_tall_cell_matrix(                             \
      const E&, const mesh::mac::TallCellGrid&,                                                    \
      const kernels::mac::PoissonStencil<E::memory_space>&, bool,                                  \
      Kokkos::View<int*, E::memory_space>, bool);
AMPHORA_FOR_EACH_EXEC_SPACE(AMPHORA_TALL_CELL_MATRIX)
#undef AMPHORA_TALL_CELL_MATRIX

}  // namespace amphora::solvers::mac
