#include "solvers/mac/tall_cell_level_transfer.hpp"

#include <algorithm>
#include <cstddef>
#include <utility>
#include <vector>

#include "kernels/mac/grid_transfer.hpp"
#include "kernels/mac/tall_cell_transfer.hpp"

namespace amphora::solvers::mac {

namespace {
/// The coarse cells (one or two) and weights of cell-centred linear interpolation at fine cell
/// f along one direction: 3/4 from the parent, 1/4 from the parent's neighbour on f's side;
/// beyond an edge of the grid the neighbour is the parent reflected, +1/4 at a wall, -1/4 at an
/// open face (grid_transfer.hpp).
int axis_weights(int f, int n_coarse, bool edge_lo, bool edge_hi, bool wall_lo, bool wall_hi,
                 int index[2], double weight[2]) {
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
}  // namespace

TallCellLevelTransfer tall_cell_level_transfer(
    const mesh::mac::TallCellGrid& fine, const mesh::mac::TallCellGrid& coarse,
    const kernels::mac::PoissonStencil<kernels::HostMemSpace>& coarse_A) {
  const kernels::mac::MacGrid &gf = fine.grid(), &gc = coarse.grid();
  const auto edge = coarse_A.edges();
  const auto wall = coarse_A.walls();
  // every fine unknown whose row of Q this block needs: its own (for Q; in their order, column
  // by column) and its ring's (for the coarse rows of Q^T), with the cell that carries it
  struct Carrier {
    long unknown;
    int i, j, k;
  };
  const auto ring = fine.ring_unknown_cells();
  csr_vector<Carrier> carriers(static_cast<std::size_t>(fine.unknowns()));  // each written below
  carriers.reserve(carriers.size() + ring.size());
  Kokkos::parallel_for("amphora::tall_mg::transfer_carriers",
                       Kokkos::RangePolicy<kernels::HostExecSpace>(0, gf.nz), [&](int k) {
                         for (int i = 0; i < gf.nx; ++i)
                           fine.for_each_unknown_in_column(
                               i, k, [&](int u, int ci, int cj, int ck) {
                                 carriers[u] = {fine.first_unknown() + u, ci, cj, ck};
                               });
                       });
  for (const auto& [u, cell] : ring) {
    Carrier c{u, 0, 0, 0};
    gf.ijk(cell, c.i, c.j, c.k);
    carriers.push_back(c);
  }
  const auto is_tall_top = [&](const Carrier& c) {
    const mesh::mac::TallCellColumn column = fine.column(c.i, c.k);
    return c.j < column.band && c.j == column.terrain + 1;
  };

  // The rows of Q for all of them, merged, built in chunks of carriers in parallel (each row
  // alone, so the result does not depend on the threads); then Q^T's rows of this block's
  // coarse unknowns.
  struct Rows {
    std::vector<long> ends;  // each row's end in cols/values
    std::vector<int> cols;
    std::vector<double> values;
  };
  // What each coarse cell of the block and its ring contributes to the interpolation, looked up
  // once per cell rather than once per fine row that reads it: its (one or two) coarse unknowns
  // and weights, none for air (zero pressure), solid = -1 for a solid cell (its weight is spread
  // over the others).
  struct CoarseCell {
    int n;
    int id[2];
    double w[2];
  };
  csr_vector<CoarseCell> coarse_cells(
      static_cast<std::size_t>(gc.padded_size()));  // each written below
  Kokkos::parallel_for("amphora::tall_mg::transfer_coarse_cells",
                       Kokkos::RangePolicy<kernels::HostExecSpace>(0, gc.nz + 2), [&](int kk) {
                         const int k = kk - 1;
                         for (int j = -1; j <= gc.ny; ++j)
                           for (int i = -1; i <= gc.nx; ++i) {
                             const int C = gc.index(i, j, k);
                             CoarseCell& cell = coarse_cells[C];
                             cell = CoarseCell{0, {0, 0}, {0.0, 0.0}};
                             if (coarse_A.solid(C))
                               cell.n = -1;
                             else if (coarse_A.inverse_diag(C) != 0.0 && j >= 0 && j < gc.ny)
                               cell.n = coarse.weights(i, j, k, cell.id, cell.w);
                           }
                       });
  const auto build = [&](std::size_t r_begin, std::size_t r_end, Rows& out) {
    // the terms of the row(s) under construction: coarse unknown and the weights of the fine
    // samples (a tall cell fits its two together), one term per coarse unknown
    struct Term {
      int id;
      double w[2];
    };
    std::vector<Term> terms(64);  // grown if a tall cell's rows need more
    std::size_t n_terms = 0;
    // about 8 coarse unknowns per row (trilinear), so no regrowth copies of the row arrays
    out.ends.reserve(r_end - r_begin);
    out.cols.reserve(10 * (r_end - r_begin));
    out.values.reserve(10 * (r_end - r_begin));
    // The coarse cells (one or two per axis) and weights interpolating at fine cell (i, j, k)
    struct Trilinear {
      int n[3], index[3][2];
      double weight[3][2];
    };
    auto trilinear = [&](int i, int j, int k) {
      Trilinear t;
      const int f[3] = {i, j, k}, nc[3] = {gc.nx, gc.ny, gc.nz};
      for (int d = 0; d < 3; ++d)
        t.n[d] = axis_weights(f[d], nc[d], edge[2 * d], edge[2 * d + 1], wall[2 * d],
                              wall[2 * d + 1], t.index[d], t.weight[d]);
      return t;
    };
    // += scale * (the coarse pressure interpolated with tri), for sample `side`
    auto interpolate_at = [&](const Trilinear& tri, int side, double scale) {
      // the (up to 16) weights first, then the share of the solid cells' weight
      int ids[16];
      double ws[16];
      int m = 0;
      double total = 0.0, solid = 0.0;
      for (int c = 0; c < tri.n[2]; ++c)
        for (int b = 0; b < tri.n[1]; ++b)
          for (int a = 0; a < tri.n[0]; ++a) {
            const double w = tri.weight[0][a] * tri.weight[1][b] * tri.weight[2][c];
            total += w;
            const CoarseCell& cell =
                coarse_cells[gc.index(tri.index[0][a], tri.index[1][b], tri.index[2][c])];
            if (cell.n < 0) {
              solid += w;
              continue;
            }
            for (int e = 0; e < cell.n; ++e) ids[m] = cell.id[e], ws[m++] = w * cell.w[e];
          }
      const double share = total - solid > 0.0 ? scale * total / (total - solid) : 0.0;
      for (int e = 0; e < m; ++e) {
        const double v = ws[e] * share;
        std::size_t t = 0;
        while (t < n_terms && terms[t].id != ids[e]) ++t;
        if (t == n_terms) {
          if (n_terms == terms.size()) terms.resize(2 * n_terms);
          terms[n_terms++] = {ids[e], {0.0, 0.0}};
        }
        terms[t].w[side] += v;
      }
    };
    auto interpolate = [&](int i, int j, int k, int side, double scale) {
      interpolate_at(trilinear(i, j, k), side, scale);
    };
    // the row of one uniform sample, or the rows G^-1 [sum_0; sum_1] of a tall cell's two
    auto emit = [&](const kernels::mac::TallCellGram* G) {
      const int samples = G ? 2 : 1;
      // insertion sort: a row has about 8 terms
      for (std::size_t a = 1; a < n_terms; ++a)
        for (std::size_t b = a; b > 0 && terms[b - 1].id > terms[b].id; --b)
          std::swap(terms[b - 1], terms[b]);
      for (int sample = 0; sample < samples; ++sample) {
        for (std::size_t e = 0; e < n_terms; ++e) {
          out.cols.push_back(terms[e].id);
          out.values.push_back(!G ? terms[e].w[0]
                                  : G->solve(terms[e].w[sample], terms[e].w[1 - sample]));
        }
        out.ends.push_back(static_cast<long>(out.cols.size()));
      }
      n_terms = 0;
    };
    // A uniform cell whose eight coarse cells are all uniform fluid cells (no edge, solid, air
    // or tall cell among them): the trilinear weights themselves, one entry each (what
    // interpolate and emit give, without the accumulation). Else false.
    auto plain_row = [&](const Trilinear& tri) {
      if (tri.n[0] < 2 || tri.n[1] < 2 || tri.n[2] < 2) return false;
      const CoarseCell* cell[8];
      for (int m = 0; m < 8; ++m) {
        cell[m] = &coarse_cells[gc.index(tri.index[0][m & 1], tri.index[1][(m >> 1) & 1],
                                         tri.index[2][m >> 2])];
        if (cell[m]->n != 1 || cell[m]->w[0] != 1.0) return false;
      }
      for (int m = 0; m < 8; ++m) {
        out.cols.push_back(cell[m]->id[0]);
        out.values.push_back(tri.weight[0][m & 1] * tri.weight[1][(m >> 1) & 1] *
                             tri.weight[2][m >> 2]);
      }
      out.ends.push_back(static_cast<long>(out.cols.size()));
      return true;
    };
    for (std::size_t r = r_begin; r < r_end; ++r) {
      const int i = carriers[r].i, j = carriers[r].j, k = carriers[r].k;
      const mesh::mac::TallCellColumn column = fine.column(i, k);
      if (j >= column.band) {  // a uniform cell
        const Trilinear tri = trilinear(i, j, k);
        if (plain_row(tri)) continue;
        interpolate_at(tri, 0, 1.0);
        emit(nullptr);
        continue;
      }
      // A tall cell (its two samples are carried by its lowest two cells, r and r + 1): the
      // least-squares fit G^-1 P^T of the interpolated coarse pressure over its rows, G = P^T P
      // in closed form as in kernels/mac/tall_cell_transfer.hpp.
      const int t = column.terrain, L = column.band - column.terrain;
      // Where both coarse rows of the interpolation lie inside the coarse tall cells of all the
      // columns it reads, the interpolated pressure is linear in the fine row (linear interpolation
      // of linear functions), so those rows enter through their two ends: the sums over them cost
      // scalar work only.
      int lo = t, hi = column.band - 1;
      {
        const Trilinear tr = trilinear(i, t, k);  // its coarse columns
        for (int c = 0; c < tr.n[2]; ++c)
          for (int a = 0; a < tr.n[0]; ++a) {
            const mesh::mac::TallCellColumn C = coarse.column(tr.index[0][a], tr.index[2][c]);
            if (!C.has_tall_cell()) hi = lo - 1;
            lo = std::max(lo, 2 * C.terrain + 1);
            hi = std::min(hi, 2 * C.band - 2);
          }
      }
      // the rows outside [lo, hi] one by one
      const auto row_by_row = [&](int jj) {
        const double s = double(jj - t) / double(L - 1);
        if (s < 1.0) interpolate(i, jj, k, 0, 1.0 - s);
        if (s > 0.0) interpolate(i, jj, k, 1, s);
      };
      const bool linear = lo <= hi;
      for (int jj = t; jj < (linear ? lo : column.band); ++jj) row_by_row(jj);
      if (linear) {
        // sum over x = jj - lo in [0, n) of the sample weights (1 - s, s), s = a + b x, times the
        // ends' weights (1 - lambda, lambda), lambda = c x: power sums of x, so a tall cell
        // costs the same whatever its height
        const double n = hi - lo + 1, a = double(lo - t) / double(L - 1), b = 1.0 / double(L - 1);
        const double c = hi > lo ? 1.0 / double(hi - lo) : 0.0;
        const double sx = 0.5 * n * (n - 1.0), sxx = sx * (2.0 * n - 1.0) / 3.0;
        const double s_sum = a * n + b * sx, l_sum = c * sx, sl_sum = a * c * sx + b * c * sxx;
        const double ends[2][2] = {
            {n - s_sum - l_sum + sl_sum, l_sum - sl_sum},  // [sample][lo or hi end]
            {s_sum - sl_sum, sl_sum}};
        for (int side = 0; side < 2; ++side) {
          interpolate(i, lo, k, side, ends[side][0]);
          if (hi > lo) interpolate(i, hi, k, side, ends[side][1]);
        }
        for (int jj = hi + 1; jj < column.band; ++jj) row_by_row(jj);
      }
      const kernels::mac::TallCellGram G(L);
      emit(&G);
      ++r;  // the top sample's row is done
    }
  };
  // chunk bounds never split a tall cell's two samples (the bottom's carrier, then the top's)
  const std::size_t n_carriers = carriers.size(),
                    chunks = std::min<std::size_t>(64, n_carriers + 1);
  std::vector<std::size_t> bound(chunks + 1, n_carriers);
  for (std::size_t c = 0; c < chunks; ++c) {
    std::size_t r = c * n_carriers / chunks;
    while (r > 0 && r < n_carriers && is_tall_top(carriers[r])) ++r;
    bound[c] = r;
  }
  std::vector<Rows> parts(chunks);
  Kokkos::parallel_for("amphora::tall_mg::transfer_rows",
                       Kokkos::RangePolicy<kernels::HostExecSpace>(0, chunks),
                       [&](std::size_t c) { build(bound[c], bound[c + 1], parts[c]); });
  // The parts one after the other (each copied in parallel to its place): Q's rows for all
  // carriers.
  std::vector<long> part_row(chunks + 1, 0), part_entry(chunks + 1, 0);
  for (std::size_t c = 0; c < chunks; ++c) {
    part_row[c + 1] = part_row[c] + static_cast<long>(parts[c].ends.size());
    part_entry[c + 1] = part_entry[c] + static_cast<long>(parts[c].cols.size());
  }
  csr_vector<long> row_ptr(part_row[chunks] + 1);
  csr_vector<int> cols(part_entry[chunks]);
  csr_vector<double> values(part_entry[chunks]);
  row_ptr[0] = 0;
  Kokkos::parallel_for(
      "amphora::tall_mg::transfer_merge", Kokkos::RangePolicy<kernels::HostExecSpace>(0, chunks),
      [&](std::size_t c) {
        const Rows& part = parts[c];
        for (std::size_t r = 0; r < part.ends.size(); ++r)
          row_ptr[part_row[c] + 1 + r] = part_entry[c] + part.ends[r];
        std::copy(part.cols.begin(), part.cols.end(), cols.begin() + part_entry[c]);
        std::copy(part.values.begin(), part.values.end(), values.begin() + part_entry[c]);
      });
  parts.clear();
  TallCellLevelTransfer t;
  // Q^T by counting, in groups of carriers: each group counts its entries per coarse row, a
  // row's groups follow one another in order, so each coarse row lists its fine columns in
  // carrier order (increasing fine unknowns within the block and within the ring) whatever the
  // threads.
  CsrMatrix& R = t.restriction;
  const long first = coarse.first_unknown();
  R.n = coarse.unknowns();
  const std::size_t groups = std::min<std::size_t>(
      chunks, 2 * static_cast<std::size_t>(kernels::HostExecSpace().concurrency()));
  std::vector<std::size_t> group_bound(groups + 1);
  for (std::size_t q = 0; q <= groups; ++q) group_bound[q] = bound[q * chunks / groups];
  std::vector<long> count(groups * R.n, 0);  // per group, per coarse row
  const auto own_row = [&](int U) { return U >= first && U < first + R.n ? U - first : -1L; };
  Kokkos::parallel_for("amphora::tall_mg::transpose_count",
                       Kokkos::RangePolicy<kernels::HostExecSpace>(0, groups), [&](std::size_t q) {
                         long* n = count.data() + q * R.n;
                         for (long e = row_ptr[group_bound[q]]; e < row_ptr[group_bound[q + 1]];
                              ++e) {
                           const long U = own_row(cols[e]);
                           if (U >= 0) ++n[U];
                         }
                       });
  // count becomes each group's first position in each coarse row
  R.row_ptr.assign(R.n + 1, 0);
  long at = 0;
  for (long U = 0; U < R.n; ++U) {
    R.row_ptr[U] = at;
    for (std::size_t q = 0; q < groups; ++q) {
      const long n = count[q * R.n + U];
      count[q * R.n + U] = at;
      at += n;
    }
  }
  R.row_ptr[R.n] = at;
  R.cols.resize(at);
  R.values.resize(at);
  Kokkos::parallel_for("amphora::tall_mg::transpose_fill",
                       Kokkos::RangePolicy<kernels::HostExecSpace>(0, groups), [&](std::size_t q) {
                         long* next = count.data() + q * R.n;
                         for (std::size_t r = group_bound[q]; r < group_bound[q + 1]; ++r)
                           for (long e = row_ptr[r]; e < row_ptr[r + 1]; ++e) {
                             const long U = own_row(cols[e]);
                             if (U < 0) continue;
                             R.cols[next[U]] = static_cast<int>(carriers[r].unknown);
                             R.values[next[U]++] = values[e];
                           }
                       });
  // Q: this block's rows, the first ones (the ring's follow them)
  CsrMatrix& Q = t.prolongation;
  Q.n = fine.unknowns();
  row_ptr.resize(Q.n + 1);
  cols.resize(row_ptr.back());
  values.resize(row_ptr.back());
  Q.row_ptr = std::move(row_ptr);
  Q.cols = std::move(cols);
  Q.values = std::move(values);
  return t;
}

}  // namespace amphora::solvers::mac
