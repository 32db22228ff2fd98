#include "solvers/mac/tall_cell_matrix.hpp"

#include <algorithm>

#include "solvers/mac/row_accumulator.hpp"

namespace amphora::solvers::mac {

CsrMatrix assemble_tall_cell_matrix(const mesh::TallCellGrid& T, const kernels::mac::PoissonStencil<HostMemSpace>& A) {
  const mesh::MacGrid& g = T.grid();
  const int sy = g.stride_y(), sz = g.stride_z();
  RowAccumulator<8> rows(T.unknowns(), T.first_unknown());
  // c (p_P - p_Q)^2 for lattice cells P and Q, whatever they map to
  auto add_face = [&](int iP, int jP, int kP, int iQ, int jQ, int kQ, double c) {
    int ids[4];
    double v[4];
    double w[2];
    int n = T.weights(iP, jP, kP, ids, w);
    for (int m = 0; m < n; ++m) v[m] = w[m];
    const int nQ = T.weights(iQ, jQ, kQ, ids + n, w);
    for (int m = 0; m < nQ; ++m) v[n + m] = -w[m];
    rows.add_outer(ids, v, n + nQ, c);
  };
  auto tall_step = [](const mesh::TallCellColumn& c) {
    return c.has_tall_cell() ? 1.0 / (c.band - 1 - c.terrain) : 0.0;
  };
  const auto& d = A.diag;
  const auto &cx = A.cx, &cy = A.cy, &cz = A.cz;
  // Rows of a column take terms from its own cells and vertical faces, from the x faces to the
  // columns of its x line and from the z faces to the neighbouring lines: lines run in parallel
  // (host threads), the z faces in two passes over lines of one parity, so no row is written by
  // two threads and each row sums its terms in an order fixed by the grid, not the threads.
  auto column_terms = [&](int i, int k) {
    const mesh::TallCellColumn& col = T.column(i, k);
    const double dt = tall_step(col);
    const int bot = static_cast<int>(T.global_first_unknown(i, k));
    // free-surface / open-face terms D p^2
    for (int j = col.terrain; j < g.ny; ++j) {
      const int c = g.index(i, j, k);
      if (d(c) == 0.0) continue;
      const double D = d(c) - (double(cx(c - 1)) + double(cx(c)) + double(cy(c - sy)) + double(cy(c)) +
                               double(cz(c - sz)) + double(cz(c)));
      if (D == 0.0) continue;
      int ids[2];
      double w[2];
      const int n = T.weights(i, j, k, ids, w);
      rows.add_outer(ids, w, n, D);
    }
    // vertical faces: inside the tall cell in one block, the rest one by one
    double inside = 0.0;
    for (int j = col.terrain; j + 1 < g.ny; ++j) {
      const double c = cy(g.index(i, j, k));
      if (c == 0.0) continue;
      if (j + 1 < col.band)
        inside += c;
      else
        add_face(i, j, k, i, j + 1, k, c);
    }
    if (inside != 0.0) {
      const int ids[2] = {bot, bot + 1};
      const double v[2] = {dt, -dt};
      rows.add_outer(ids, v, 2, inside);
    }
  };
  const auto& nb = T.block().neighbours;
  // the terms of the face between column (i, k) and its +x (dir 0) or +z (dir 1) neighbour
  auto face_terms = [&](int dir, int i, int k) {
    const auto& cond = dir == 0 ? cx : cz;
    const int in = i + (dir == 0), kn = k + (dir == 1);
    const mesh::TallCellColumn &col = T.column(i, k), &next = T.column(in, kn);
    const double dc = tall_step(col), dn = tall_step(next);
    // tall against tall: sum_j c_j v(j) v(j)^T with v = (1 - t, t, -(1 - s), -s) linear in
    // j, so from the moments sum c, sum c x, sum c x^2 (x = j - j0, small for accuracy)
    const int j0 = std::max(col.terrain, next.terrain), j_tall = std::min(col.band, next.band);
    double m0 = 0.0, m1 = 0.0, m2 = 0.0;
    for (int j = j0; j < g.ny; ++j) {
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
      for (int a = 0; a < 4; ++a)
        for (int b = a; b < 4; ++b) {  // one value for (a, b) and (b, a): exactly symmetric
          const double v = p[a] * p[b] * m0 + (p[a] * q[b] + q[a] * p[b]) * m1 + q[a] * q[b] * m2;
          rows.add(ids[a], ids[b], v);
          if (b != a) rows.add(ids[b], ids[a], v);
        }
    }
  };
  // x faces between a column and its +x neighbour, where either is this block's (on a split
  // grid the faces to the ghost ring too: their terms in this block's rows); likewise z faces
  const int i_lo = nb[0] >= 0 ? -1 : 0, i_hi = nb[1] >= 0 ? g.nx : g.nx - 1;  // lower column's range
  const int k_lo = nb[4] >= 0 ? -1 : 0, k_hi = nb[5] >= 0 ? g.nz : g.nz - 1;
  Kokkos::parallel_for("amphora::tall::assemble_lines", Kokkos::RangePolicy<HostExecSpace>(0, g.nz), [&](int k) {
    for (int i = 0; i < g.nx; ++i) column_terms(i, k);
    for (int i = i_lo; i < i_hi; ++i) face_terms(0, i, k);
  });
  for (int parity = 0; parity < 2; ++parity) {
    const int first = k_lo + ((parity - k_lo) % 2 + 2) % 2, lines = (k_hi - first + 1) / 2;
    Kokkos::parallel_for("amphora::tall::assemble_z_faces", Kokkos::RangePolicy<HostExecSpace>(0, std::max(lines, 0)),
                         [&](int m) {
                           for (int i = 0; i < g.nx; ++i) face_terms(1, i, first + 2 * m);
                         });
  }
  return rows.to_csr();
}

}  // namespace amphora::solvers::mac
