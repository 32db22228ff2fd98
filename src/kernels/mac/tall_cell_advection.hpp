#pragma once
// The tall-cell parts of a water step (Irving, Guendelman, Losasso & Fedkiw 2006, sec. 4-5):
// - velocity in a tall cell is linear in height through its two samples; when the grid is
//   rebuilt (the band follows the surface), the lattice velocity in the new tall cells is
//   replaced by its least-squares linear fit per sample column, which keeps the column's
//   momentum sum_j u_j h^3 exactly (constants lie in the span of the fit) and reproduces linear
//   profiles;
// - in tall cells the velocity is advected by first-order upwind in flux form (a control volume
//   per face sample, face velocities averaged onto its faces): the fluxes telescope, so momentum
//   moves between samples without being created, and the scheme is stable for a Courant sum
//   dt (|u| + |v| + |w|) / h <= 1 there, which tall_cell_speed() lets the caller keep; the
//   step is followed by the linear fit, which needs only each sample column's sum and first
//   moment: for fields linear in height these come in closed form from the fluxes' end values,
//   so a tall cell's flux work does not grow with its height, its rows are only written
//   (tall_range_upwind_fit);
//   semi-Lagrangian tracing stays in the uniform cells, where the surface is;
// - the level set is neither advected nor reinitialised inside tall cells: they lie at least
//   the optical depth below the surface, where only its sign is used.
// The fields stay expanded on the lattice; these kernels choose the scheme per sample.
#include "kernels/mac/level_set.hpp"
#include "kernels/mac/semi_lagrangian.hpp"
#include "kernels/mac/tall_cell_columns.hpp"

namespace amphora::kernels::mac {

/// The face velocity component e at padded index c.
template <class U, class V, class W>
KOKKOS_INLINE_FUNCTION double component(int e, const U& u, const V& v, const W& w, int c) {
  return e == 0 ? double(u(c)) : e == 1 ? double(v(c)) : double(w(c));
}

/// Face sample c of component d after dt of first-order upwind advection in flux form:
/// q - dt/h sum_e (F_e+ - F_e-), F = U q_upwind with U the velocity normal to the control
/// volume's face (component e averaged over the two samples that share it).
template <class Q, class U, class V, class W>
KOKKOS_INLINE_FUNCTION double conservative_upwind_sample(const kernels::mac::MacGrid& g, int d,
                                                         int c, const Q& q, const U& u, const V& v,
                                                         const W& w, double dt) {
  const int stride[3] = {1, g.stride_y(), g.stride_z()};
  const int sd = stride[d];
  double net = 0.0;
  for (int e = 0; e < 3; ++e) {
    const int se = stride[e];
    // along d the control volume's faces are cell centres; across it, cell edges
    const double up =
        e == d ? 0.5 * (component(e, u, v, w, c) + component(e, u, v, w, c + sd))
               : 0.5 * (component(e, u, v, w, c + se) + component(e, u, v, w, c + se - sd));
    const double down = e == d ? 0.5 * (component(e, u, v, w, c - sd) + component(e, u, v, w, c))
                               : 0.5 * (component(e, u, v, w, c) + component(e, u, v, w, c - sd));
    net += up * (up > 0.0 ? q(c) : q(c + se)) - down * (down > 0.0 ? q(c - se) : q(c));
  }
  return q(c) - dt / g.h * net;
}

namespace detail {
/// sum_{x = x0}^{x1 - 1} (a0 + a1 x)(b0 + b1 x)(w0 + w1 x), by the power sums of x^0..x^3.
KOKKOS_INLINE_FUNCTION double cubic_sum(double a0, double a1, double b0, double b1, double w0,
                                        double w1, int x0, int x1) {
  if (x1 <= x0) return 0.0;
  const auto powers = [](double n, double S[4]) {  // sum_{x=0}^{n-1} x^k
    const double t = 0.5 * n * (n - 1.0);
    S[0] = n, S[1] = t, S[2] = t * (2.0 * n - 1.0) / 3.0, S[3] = t * t;
  };
  double S1[4], S0[4];
  powers(x1, S1);
  powers(x0, S0);
  const double p0 = a0 * b0, p1 = a0 * b1 + a1 * b0, p2 = a1 * b1;
  const double c[4] = {p0 * w0, p0 * w1 + p1 * w0, p1 * w1 + p2 * w0, p2 * w1};
  double sum = 0.0;
  for (int m = 0; m < 4; ++m) sum += c[m] * (S1[m] - S0[m]);
  return sum;
}

/// The rows [lo, hi) where the samples of component e in sample column (i, k) are linear in
/// height (its tall rows; none for a column outside the block and its ghost ring).
template <class MemSpace>
KOKKOS_INLINE_FUNCTION void linear_rows(const kernels::mac::TallCellColumns<MemSpace>& T, int e,
                                        int i, int k, int& lo, int& hi) {
  const kernels::mac::MacGrid& g = T.grid;
  const bool inside = i >= (e == 0 ? 0 : -1) && i <= g.nx && k >= (e == 2 ? 0 : -1) && k <= g.nz;
  lo = hi = 0;
  if (inside) T.tall_rows(e, i, k, lo, hi);
}
}  // namespace detail

/// The sums over rows [lo, hi) of one upwind flux F(j) = U(j) q_upwind(j) of the conservative
/// scheme, and of (j - mid) F(j): U = (a + b) / 2 from two samples of component e, q_upwind =
/// q at l where U > 0, at r elsewhere (lattice indices at row 0; row j adds j stride_y). Where
/// all four samples are linear in height (rows [lin_lo, lin_hi)) the sums come in closed form
/// from each sample's two end values, split where U changes sign; elsewhere row by row.
template <class Q, class U, class V, class W>
KOKKOS_INLINE_FUNCTION void upwind_flux_sums(const kernels::mac::MacGrid& g, int e, int a, int b,
                                             int l, int r, int lo, int hi, int lin_lo, int lin_hi,
                                             double mid, const Q& q, const U& u, const V& v,
                                             const W& w, double& sum, double& moment) {
  const int sy = g.stride_y();
  int s0 = math::max(lo, lin_lo), s1 = math::min(hi, lin_hi);
  if (s1 - s0 < 2) s0 = s1 = hi;  // no closed form for fewer than two rows: all row by row
  const auto add_row = [&](int j) {
    const double Uj = 0.5 * (component(e, u, v, w, a + j * sy) + component(e, u, v, w, b + j * sy));
    const double F = Uj * (Uj > 0.0 ? double(q(l + j * sy)) : double(q(r + j * sy)));
    sum += F, moment += (j - mid) * F;
  };
  for (int j = lo; j < s0; ++j) add_row(j);
  for (int j = s1; j < hi; ++j) add_row(j);
  if (s1 == s0) return;
  // x = j - s0 in [0, n): each sample f0 + f1 x from its values at both ends
  const int n = s1 - s0, top = (n - 1) * sy;
  const auto line = [&](double at0, double at1, double& f0, double& f1) {
    f0 = at0, f1 = (at1 - at0) / (n - 1);
  };
  double U0, U1, L0, L1, R0, R1;
  line(0.5 * (component(e, u, v, w, a + s0 * sy) + component(e, u, v, w, b + s0 * sy)),
       0.5 * (component(e, u, v, w, a + s0 * sy + top) + component(e, u, v, w, b + s0 * sy + top)),
       U0, U1);
  line(q(l + s0 * sy), q(l + s0 * sy + top), L0, L1);
  line(q(r + s0 * sy), q(r + s0 * sy + top), R0, R1);
  // the rows [x_pos, x_end) where U > 0 (a prefix or a suffix of [0, n))
  int x_pos = 0, x_end = 0;
  if (U1 == 0.0) {
    if (U0 > 0.0) x_end = n;
  } else {
    const double root = math::min(math::max(-U0 / U1, -1.0), double(n));
    if (U1 > 0.0)
      x_pos = math::min(static_cast<int>(math::floor(root)) + 1, n), x_end = n;
    else
      x_end = math::max(static_cast<int>(math::ceil(root)), 0);
  }
  const double t0 = s0 - mid;                                                // j - mid = t0 + x
  const int neg_lo = x_pos > 0 ? 0 : x_end, neg_hi = x_pos > 0 ? x_pos : n;  // the other rows
  sum += detail::cubic_sum(U0, U1, L0, L1, 1.0, 0.0, x_pos, x_end) +
         detail::cubic_sum(U0, U1, R0, R1, 1.0, 0.0, neg_lo, neg_hi);
  moment += detail::cubic_sum(U0, U1, L0, L1, t0, 1.0, x_pos, x_end) +
            detail::cubic_sum(U0, U1, R0, R1, t0, 1.0, neg_lo, neg_hi);
}

/// The shortest tall range of a sample column that tall_range_upwind_fit updates as a whole
/// (shorter ones are linear already; fit_linear_in_tall_cells leaves them too).
constexpr int min_tall_sample_rows = 3;

/// Face samples [lo, hi) of component d in sample column (i, k) of a tall cell: the conservative
/// upwind step of every row (conservative_upwind_sample) followed by the momentum-keeping
/// linear fit (fit_linear_in_tall_cells), done at once: the new samples are mean + slope (j -
/// mid), mid = (lo + hi - 1) / 2. The fit needs only the column's sum and first moment; the
/// fluxes of fields linear in height have them in closed form, so the work is per tall cell,
/// not per lattice row inside it. The fields must be linear in height in the tall cells of T
/// (fit_linear_in_tall_cells; the pressure projection keeps them so).
template <class MemSpace, class Q, class U, class V, class W>
KOKKOS_INLINE_FUNCTION void tall_range_upwind_fit(const kernels::mac::TallCellColumns<MemSpace>& T,
                                                  int d, int i, int k, int lo, int hi, const Q& q,
                                                  const U& u, const V& v, const W& w, double dt,
                                                  double& mean, double& slope) {
  const kernels::mac::MacGrid& g = T.grid;
  const int sy = g.stride_y(), c0 = g.index(i, 0, k);
  const int stride[3] = {1, sy, g.stride_z()};
  const double mid = 0.5 * (lo + hi - 1);
  double sum = 0.0, moment = 0.0;  // of the net outflow over the rows
  for (int e = 0; e < 3; ++e)
    for (int side = 0; side < 2; ++side) {
      // the control volume's face at +e (side 0) or -e (side 1): offsets (di, dj, dk) of the two
      // velocity samples averaged onto it (a, b) and of q upwind of it (l, r), as in
      // conservative_upwind_sample
      int off[4][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
      if (side == 0 && e == d) {
        off[1][d] = 1, off[3][d] = 1;
      } else if (side == 0) {
        off[0][e] = 1, off[1][e] = 1, off[1][d] = -1, off[3][e] = 1;
      } else if (e == d) {
        off[0][d] = -1, off[2][d] = -1;
      } else {
        off[1][d] = -1, off[2][e] = -1;
      }
      int idx[4], lin_lo = lo, lin_hi = hi;
      for (int m = 0; m < 4; ++m) {
        idx[m] = c0 + off[m][0] * stride[0] + off[m][1] * stride[1] + off[m][2] * stride[2];
        int a, b;
        detail::linear_rows(T, m < 2 ? e : d, i + off[m][0], k + off[m][2], a, b);
        lin_lo = math::max(lin_lo, a - off[m][1]), lin_hi = math::min(lin_hi, b - off[m][1]);
      }
      double S = 0.0, M = 0.0;
      upwind_flux_sums(g, e, idx[0], idx[1], idx[2], idx[3], lo, hi, lin_lo, lin_hi, mid, q, u, v,
                       w, S, M);
      sum += side == 0 ? S : -S, moment += side == 0 ? M : -M;
    }
  // q itself is linear here: its sum and first moment from its end values
  const double n = hi - lo, tt = n * (n * n - 1.0) / 12.0;
  const double q_lo = q(c0 + lo * sy), q_hi = q(c0 + (hi - 1) * sy);
  mean = 0.5 * (q_lo + q_hi) - dt / g.h * sum / n;
  slope = (q_hi - q_lo) / (n - 1.0) - dt / g.h * moment / tt;
}

/// q_new = q advected over dt: semi-Lagrangian in uniform cells, conservative upwind for face
/// samples in tall cells (a tall range of at least min_tall_sample_rows as a whole, with the
/// fit: tall_range_upwind_fit), unchanged for cell samples in tall cells. Face samples whose
/// cells both have phi >= reach are only copied: for reach at least the distance the surface can
/// move in dt plus the cells the next classification looks at, such a face lies in the air
/// after the step, where the caller discards the velocity (it is extrapolated afresh). q_new
/// must not alias q.
///
/// Two passes: one work item per sample column finds its tall rows and, for a tall range taken
/// as a whole, its line (closed form, so the work is per column); then one work item per x-row
/// of samples writes their values along x: the line, the semi-Lagrangian trace, the upwind step
/// or a copy. Done down each column in the first pass instead, the samples gave a GPU half as
/// many work items and strode through memory on the host (a 128^3 semi-Lagrangian face
/// component 75-79 ms that way, 60-61 ms this way; an MDRange over the samples was slower still
/// on the host).
///
/// q, u, v, w, phi and T live on T.grid; q_new on `out`, whose sample (i, j, k) is T.grid's
/// (i + out_offset[0], j, k + out_offset[2]) (a block inside its widened grid: the traces near
/// the block's faces read the neighbours' cells). Cell samples (s == centre) in rows below
/// first_row are not written: pass kernels::mac::lowest_band(), below which they all lie in tall
/// cells or under the terrain, with q_new holding q there already.
template <class ExecSpace, class MemSpace, class Q, class QN, class U, class V, class W, class P>
void advect(const ExecSpace& exec, const kernels::mac::TallCellColumns<MemSpace>& T, Staggering s,
            const Q& q, const QN& q_new, const U& u, const V& v, const W& w, double dt,
            const P& phi, double reach, const kernels::mac::MacGrid& out, const int out_offset[3],
            int first_row = 0) {
  const kernels::mac::MacGrid g = T.grid, go = out;
  const int d = static_cast<int>(s), oi = out_offset[0], ok = out_offset[2];
  const int ex = go.nx + (d == 0), ey = go.ny + (d == 1), ez = go.nz + (d == 2);
  const int j0 = d < 0 ? math::clamp(first_row, 0, ey) : 0, rows_written = ey - j0;
  const int below = d == 0 ? 1 : d == 1 ? g.stride_y() : d == 2 ? g.stride_z() : 0;
  // per sample column: its tall rows [lo, hi), the rows [wlo, whi) written from the line (or
  // copied, for cell samples), and the line
  Kokkos::View<int* [4], MemSpace> rows(
      Kokkos::view_alloc(Kokkos::WithoutInitializing, "amphora::mac::tall_rows"), ex * ez);
  Kokkos::View<double* [2], MemSpace> line(
      Kokkos::view_alloc(Kokkos::WithoutInitializing, "amphora::mac::tall_line"), ex * ez);
  Kokkos::parallel_for(
      "amphora::mac::advect::tall_lines", RangePolicy<ExecSpace>(exec, 0, ex * ez),
      KOKKOS_LAMBDA(int m) {
        const int I = m % ex + oi, K = m / ex + ok;
        int lo, hi;
        T.tall_rows(d, I, K, lo, hi);
        // cell samples keep their tall rows; face samples take a long enough range as a whole
        const bool whole = d < 0 || hi - lo >= min_tall_sample_rows;
        rows(m, 0) = lo, rows(m, 1) = hi, rows(m, 2) = whole ? lo : 0, rows(m, 3) = whole ? hi : 0;
        if (d >= 0 && whole && hi > lo)
          tall_range_upwind_fit(T, d, I, K, lo, hi, q, u, v, w, dt, line(m, 0), line(m, 1));
      });
  Kokkos::parallel_for(
      "amphora::mac::advect::samples", RangePolicy<ExecSpace>(exec, 0, rows_written * ez),
      KOKKOS_LAMBDA(int row) {
        const int j = j0 + row % rows_written, k = row / rows_written, K = k + ok;
        for (int i = 0; i < ex; ++i) {
          const int m = i + ex * k, I = i + oi;
          const int lo = rows(m, 0), hi = rows(m, 1), wlo = rows(m, 2), whi = rows(m, 3);
          const int c = g.index(I, j, K), o = go.index(i, j, k);
          if (j >= wlo && j < whi)
            q_new(o) = d < 0 ? double(q(c)) : line(m, 0) + line(m, 1) * (j - 0.5 * (wlo + whi - 1));
          else if (d >= 0 && math::min(phi(c), phi(c - below)) >= reach)
            q_new(o) = q(c);
          else if (j < lo || j >= hi)
            q_new(o) = semi_lagrangian_sample(g, s, I, j, K, q, u, v, w, dt);
          else
            q_new(o) = conservative_upwind_sample(g, d, c, q, u, v, w, dt);
        }
      });
}

/// The same on T.grid itself.
template <class ExecSpace, class MemSpace, class Q, class QN, class U, class V, class W, class P>
void advect(const ExecSpace& exec, const kernels::mac::TallCellColumns<MemSpace>& T, Staggering s,
            const Q& q, const QN& q_new, const U& u, const V& v, const W& w, double dt,
            const P& phi, double reach) {
  const int none[3] = {0, 0, 0};
  advect(exec, T, s, q, q_new, u, v, w, dt, phi, reach, T.grid, none);
}

/// One pseudo-time step of reinitialisation in the uniform cells (tall cells keep phi). Rows
/// below first_row are not written (as in advect: pass kernels::mac::lowest_band(), phi_new holding
/// phi there already).
template <class ExecSpace, class MemSpace, class P0, class P, class PN>
void reinitialise_step(const ExecSpace& exec, const kernels::mac::TallCellColumns<MemSpace>& T,
                       const P0& phi0, const P& phi, const PN& phi_new,
                       const kernels::mac::MacEdges& edges = kernels::mac::box_edges(),
                       int first_row = 0) {
  const kernels::mac::MacGrid g = T.grid;
  Kokkos::parallel_for(
      "amphora::mac::reinitialise_step_tall_cells",
      Kokkos::MDRangePolicy<ExecSpace, Kokkos::Rank<3>>(
          exec, {0, math::clamp(first_row, 0, g.ny), 0}, {g.nz, g.ny, g.nx}),
      KOKKOS_LAMBDA(int k, int j, int i) {
        const int c = g.index(i, j, k);
        phi_new(c) = T.in_tall_cell(-1, i, j, k)
                         ? double(phi(c))
                         : reinitialised_value(g, edges, phi0, phi, i, j, k);
      });
}

/// Replaces the samples of face component d inside tall cells by their least-squares linear
/// fit in height, per sample column (sum and first moment kept). With `fitted` (columns on whose
/// tall cells f is linear already, as the tall-cell advection leaves it), a sample column whose
/// tall rows are the same under T and `fitted` is left alone: refitting a line changes it only
/// at round-off. Most columns keep their rows from one sub-step to the next.
template <class ExecSpace, class MemSpace, class F>
void fit_linear_in_tall_cells(const ExecSpace& exec,
                              const kernels::mac::TallCellColumns<MemSpace>& T, int d, const F& f,
                              const kernels::mac::TallCellColumns<MemSpace>& fitted = {}) {
  const kernels::mac::MacGrid g = T.grid;
  const int ex = g.nx + (d == 0), ez = g.nz + (d == 2), sy = g.stride_y();
  const bool skip_fitted = fitted.terrain.extent(0) > 0;
  Kokkos::parallel_for(
      "amphora::mac::fit_linear_in_tall_cells", RangePolicy<ExecSpace>(exec, 0, ex * ez),
      KOKKOS_LAMBDA(int m) {
        const int i = m % ex, k = m / ex;
        int lo, hi;
        T.tall_rows(d, i, k, lo, hi);
        if (hi - lo < min_tall_sample_rows) return;  // one or two samples are linear already
        if (skip_fitted) {
          int flo, fhi;
          fitted.tall_rows(d, i, k, flo, fhi);
          if (flo == lo && fhi == hi) return;
        }
        // centred heights t = j - mid keep the normal equations diagonal
        const double mid = 0.5 * (lo + hi - 1);
        const int c0 = g.index(i, lo, k);
        double sum = 0.0, moment = 0.0, tt = 0.0;
        for (int j = lo; j < hi; ++j) {
          const double t = j - mid, value = f(c0 + (j - lo) * sy);
          sum += value;
          moment += t * value;
          tt += t * t;
        }
        const double mean = sum / (hi - lo), slope = moment / tt;
        for (int j = lo; j < hi; ++j) f(c0 + (j - lo) * sy) = mean + slope * (j - mid);
      });
}

/// The largest |u| + |v| + |w| (each the larger of a cell's two faces) over the tall cells of
/// the block: the upwind step there is stable for dt <= h / tall_cell_speed (on a split grid the
/// caller takes the largest over the blocks). The faces must be linear in height in their tall
/// rows (fit_linear_in_tall_cells; advection and projection keep them so): where all six of a
/// cell's are, the sum is convex in height (a sum of maxima of |linear|), so only the ends of
/// those rows are read, whatever the tall cell's height.
template <class ExecSpace, class MemSpace, class U, class V, class W>
double tall_cell_speed(const ExecSpace& exec, const kernels::mac::TallCellColumns<MemSpace>& T,
                       const U& u, const V& v, const W& w) {
  const kernels::mac::MacGrid g = T.grid;
  const int sy = g.stride_y(), sz = g.stride_z();
  double speed = 0.0;
  Kokkos::parallel_reduce(
      "amphora::mac::tall_cell_speed", RangePolicy<ExecSpace>(exec, 0, g.nx * g.nz),
      KOKKOS_LAMBDA(int m, double& acc) {
        const int i = m % g.nx, k = m / g.nx, col = T.column(i, k);
        const int t = T.terrain(col), b = T.band(col);
        if (b <= t) return;
        // rows [lo, hi) where all six faces are linear: u at i and i + 1, v at j and j + 1, w at
        // k and k + 1
        int lo = t + 1, hi = b - 1;
        const auto within = [&](int d, int fi, int fk) {
          int a, z;
          T.tall_rows(d, fi, fk, a, z);
          lo = math::max(lo, a), hi = math::min(hi, z);
        };
        within(0, i, k), within(0, i + 1, k), within(2, i, k), within(2, i, k + 1);
        if (hi - lo < 3) lo = hi = b;  // nothing to skip
        for (int j = t; j < b; ++j) {
          if (j == lo + 1) j = hi - 1;  // inside: below the larger of the ends
          const int c = g.index(i, j, k);
          const double s = math::max(math::abs(u(c)), math::abs(u(c + 1))) +
                           math::max(math::abs(v(c)), math::abs(v(c + sy))) +
                           math::max(math::abs(w(c)), math::abs(w(c + sz)));
          acc = math::max(acc, s);
        }
      },
      Kokkos::Max<double>(speed));
  return math::max(speed, 0.0);  // no tall cell: the reducer's identity is the lowest double
}

/// The largest |f| over the samples of face component d in T's tall rows below row `below`. f
/// must be linear in height there (as for tall_cell_speed), so only the ends of each sample
/// column's rows are read: the caller measures the lattice from `below` up.
template <class ExecSpace, class MemSpace, class F>
double tall_rows_max_abs(const ExecSpace& exec, const kernels::mac::TallCellColumns<MemSpace>& T,
                         int d, const F& f, int below) {
  const kernels::mac::MacGrid g = T.grid;
  const int ex = g.nx + (d == 0), ez = g.nz + (d == 2);
  double largest = 0.0;
  Kokkos::parallel_reduce(
      "amphora::mac::tall_rows_max_abs", RangePolicy<ExecSpace>(exec, 0, ex * ez),
      KOKKOS_LAMBDA(int m, double& acc) {
        const int i = m % ex, k = m / ex;
        int lo, hi;
        T.tall_rows(d, i, k, lo, hi);
        hi = math::min(hi, below);
        if (hi <= lo) return;
        const double bottom = f(g.index(i, lo, k)), top = f(g.index(i, hi - 1, k));
        acc = math::max(acc, math::max(math::abs(bottom), math::abs(top)));
      },
      Kokkos::Max<double>(largest));
  return math::max(largest, 0.0);  // no tall rows below `below`: zero, not the reducer's identity
}

}  // namespace amphora::kernels::mac
