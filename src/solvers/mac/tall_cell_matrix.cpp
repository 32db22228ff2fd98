#include "solvers/mac/tall_cell_matrix.hpp"

#include <algorithm>
#include <utility>
#include <vector>

namespace amphora::solvers::mac {

namespace {

/// Rows of a symmetric matrix under assembly: up to K entries per row inline in flat arrays
/// (a uniform cell has 7), the rest of a longer row (a tall cell's samples facing many uniform
/// neighbour cells) in a per-row overflow list; entries found by linear search. No allocation
/// per row: assembly runs every sub-step.
class RowAccumulator {
 public:
  /// Rows first .. first + n - 1 of the global matrix (the others are dropped).
  RowAccumulator(long n, long first) : first_(first), count_(n, 0), cols_(n * K), values_(n * K), overflow_(n) {}
  void add(long global_row, int c, double v) {
    const long r = global_row - first_;
    if (r < 0 || r >= static_cast<long>(count_.size())) return;  // another block's row
    int* cols = cols_.data() + static_cast<long>(r) * K;
    double* values = values_.data() + static_cast<long>(r) * K;
    const int m = count_[r];
    for (int e = 0; e < m; ++e)
      if (cols[e] == c) {
        values[e] += v;
        return;
      }
    if (m < K) {
      cols[m] = c;
      values[m] = v;
      count_[r] = m + 1;
      return;
    }
    for (auto& e : overflow_[r])
      if (e.first == c) {
        e.second += v;
        return;
      }
    overflow_[r].emplace_back(c, v);
  }
  /// += scale v v^T for the n entries (ids, v).
  void add_outer(const int* ids, const double* v, int n, double scale) {
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < n; ++b) add(ids[a], ids[b], scale * v[a] * v[b]);
  }
  CsrMatrix to_csr() const {
    const long n = static_cast<long>(count_.size());
    CsrMatrix M;
    M.n = n;
    M.row_ptr.resize(n + 1);
    M.row_ptr[0] = 0;
    for (long r = 0; r < n; ++r) M.row_ptr[r + 1] = M.row_ptr[r] + count_[r] + static_cast<long>(overflow_[r].size());
    M.cols.resize(M.row_ptr[n]);
    M.values.resize(M.row_ptr[n]);
    std::vector<std::pair<int, double>> row;
    for (long r = 0; r < n; ++r) {
      row.clear();
      for (int e = 0; e < count_[r]; ++e) row.emplace_back(cols_[r * K + e], values_[r * K + e]);
      row.insert(row.end(), overflow_[r].begin(), overflow_[r].end());
      std::sort(row.begin(), row.end());
      long at = M.row_ptr[r];
      for (const auto& [c, v] : row) {
        M.cols[at] = c;
        M.values[at++] = v;
      }
    }
    return M;
  }

 private:
  static constexpr int K = 8;
  long first_ = 0;
  std::vector<int> count_;
  std::vector<int> cols_;
  std::vector<double> values_;
  std::vector<std::vector<std::pair<int, double>>> overflow_;
};

}  // namespace

CsrMatrix assemble_tall_cell_matrix(const mesh::TallCellGrid& T, const kernels::mac::PoissonStencil<HostMemSpace>& A) {
  const mesh::MacGrid& g = T.grid();
  const int sy = g.stride_y(), sz = g.stride_z();
  RowAccumulator rows(T.unknowns(), T.first_unknown());
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
