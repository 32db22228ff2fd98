#include "solvers/mac/tall_cell_matrix.hpp"

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
  for (int k = 0; k < g.nz; ++k)
    for (int i = 0; i < g.nx; ++i) {
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
    }
  // horizontal faces between a column and its +x / +z neighbour, where either is this block's
  // (on a split grid the faces to the ghost ring too: their terms in this block's rows)
  const auto& nb = T.block().neighbours;
  for (int dir = 0; dir < 2; ++dir) {
    const int i_lo = dir == 0 && nb[0] >= 0 ? -1 : 0, k_lo = dir == 1 && nb[4] >= 0 ? -1 : 0;
    const int i_hi = dir == 0 ? (nb[1] >= 0 ? g.nx : g.nx - 1) : g.nx;  // lower column's range
    const int k_hi = dir == 1 ? (nb[5] >= 0 ? g.nz : g.nz - 1) : g.nz;
    const auto& cond = dir == 0 ? cx : cz;
    for (int k = k_lo; k < k_hi; ++k)
      for (int i = i_lo; i < i_hi; ++i) {
        const int in = i + (dir == 0), kn = k + (dir == 1);
        const mesh::TallCellColumn &col = T.column(i, k), &next = T.column(in, kn);
        const double dc = tall_step(col), dn = tall_step(next);
        double block[4][4] = {};
        bool any_block = false;
        for (int j = std::max(col.terrain, next.terrain); j < g.ny; ++j) {
          const double c = cond(g.index(i, j, k));
          if (c == 0.0) continue;
          if (j < col.band && j < next.band) {  // tall against tall: a 4x4 block
            const double t = (j - col.terrain) * dc, s = (j - next.terrain) * dn;
            const double v[4] = {1.0 - t, t, -(1.0 - s), -s};
            for (int a = 0; a < 4; ++a)
              for (int b = 0; b < 4; ++b) block[a][b] += c * v[a] * v[b];
            any_block = true;
          } else {
            add_face(i, j, k, in, j, kn, c);
          }
        }
        if (any_block) {
          const int bot = static_cast<int>(T.global_first_unknown(i, k));
          const int nbot = static_cast<int>(T.global_first_unknown(in, kn));
          const int ids[4] = {bot, bot + 1, nbot, nbot + 1};
          for (int a = 0; a < 4; ++a)
            for (int b = 0; b < 4; ++b) rows.add(ids[a], ids[b], block[a][b]);
        }
      }
  }
  return rows.to_csr();
}

}  // namespace amphora::solvers::mac
