#include "solvers/mac/tall_cell_multigrid.hpp"

#include <mpi.h>

#include <optional>
#include <utility>
#include <vector>

#include "solvers/mac/tall_cell_level_transfer.hpp"
#include "solvers/mac/tall_cell_matrix.hpp"

namespace amphora::solvers::mac {

namespace {
bool on_every_rank(MPI_Comm comm, bool local) {
  int in = local ? 1 : 0, out = 0;
  MPI_Allreduce(&in, &out, 1, MPI_INT, MPI_MIN, comm);
  return out == 1;
}

/// Every block's rows (global columns) in one matrix, on every rank: rank order is the global
/// numbering of the unknowns.
CsrMatrix gather_rows(MPI_Comm comm, const CsrMatrix& M, std::vector<int>& counts,
                      std::vector<int>& displacements) {
  int ranks = 1;
  MPI_Comm_size(comm, &ranks);
  const int n = static_cast<int>(M.n), nnz = static_cast<int>(M.nnz());
  counts.assign(ranks, 0);
  std::vector<int> nnz_counts(ranks, 0), nnz_displacements(ranks, 0);
  MPI_Allgather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, comm);
  MPI_Allgather(&nnz, 1, MPI_INT, nnz_counts.data(), 1, MPI_INT, comm);
  displacements.assign(ranks, 0);
  for (int r = 1; r < ranks; ++r) {
    displacements[r] = displacements[r - 1] + counts[r - 1];
    nnz_displacements[r] = nnz_displacements[r - 1] + nnz_counts[r - 1];
  }
  CsrMatrix W;
  W.n = displacements[ranks - 1] + counts[ranks - 1];
  const long total_nnz = nnz_displacements[ranks - 1] + nnz_counts[ranks - 1];
  std::vector<int> lengths(W.n), mine(n);
  for (int i = 0; i < n; ++i) mine[i] = static_cast<int>(M.row_ptr[i + 1] - M.row_ptr[i]);
  MPI_Allgatherv(mine.data(), n, MPI_INT, lengths.data(), counts.data(), displacements.data(),
                 MPI_INT, comm);
  W.cols.resize(total_nnz);
  W.values.resize(total_nnz);
  MPI_Allgatherv(M.cols.data(), nnz, MPI_INT, W.cols.data(), nnz_counts.data(),
                 nnz_displacements.data(), MPI_INT, comm);
  MPI_Allgatherv(M.values.data(), nnz, MPI_DOUBLE, W.values.data(), nnz_counts.data(),
                 nnz_displacements.data(), MPI_DOUBLE, comm);
  W.row_ptr.assign(W.n + 1, 0);
  for (long i = 0; i < W.n; ++i) W.row_ptr[i + 1] = W.row_ptr[i] + lengths[i];
  return W;
}
}  // namespace

template <class ExecSpace>
TallCellMultigrid<ExecSpace>::TallCellMultigrid(const ExecSpace& exec,
                                                const mesh::mac::TallCellGrid& T, const Stencil& A,
                                                const TallCellMultigridOptions& options,
                                                KeptCoarseStencils<MemSpace>* kept)
    : halo_(T.block()) {
  const mesh::mac::MacBlock& block = T.block();
  const MPI_Comm comm = block.comm;
  const BlockInnerProduct inner{comm};
  // the level's grid (T itself on the finest) and stencil
  const mesh::mac::TallCellGrid* level_grid = &T;
  std::optional<mesh::mac::TallCellGrid> coarse_level_grid;
  Stencil level_A = A;
  complete_block_stencil(exec, halo_, static_cast<const Stencil*>(nullptr), level_A);
  mesh::mac::MacBlock level_block = block;
  int unchanged_below = kept ? kept->unchanged_below : 0;  // on this level's lattice
  Kokkos::View<int*, MemSpace> carriers;  // the lattice cell of each of the level's unknowns
  for (int l = 0;; ++l) {
    auto L = std::make_unique<Level>();
    // the level's matrix, assembled on the device with local columns
    Kokkos::Profiling::pushRegion("amphora::tall_mg::level_matrix");
    if (l == 0) carriers = tall_cell_carriers(exec, *level_grid);
    L->A_t = Csr(assemble_tall_cell_matrix(exec, *level_grid, level_A, true, carriers), *level_grid,
                 carriers);
    Kokkos::Profiling::popRegion();
    const int n = L->A_t.n;
    L->b = Vector("amphora::tall_mg::b", n);
    L->x = Vector("amphora::tall_mg::x", n);
    L->r = Vector("amphora::tall_mg::r", n);
    // every rank decides together (a block's first cell must stay on the coarse grid)
    const kernels::mac::MacGrid g = level_A.grid;
    long cells = g.cells();
    MPI_Allreduce(MPI_IN_PLACE, &cells, 1, MPI_LONG, MPI_SUM, comm);
    const bool halvable = g.nx % 2 == 0 && g.ny % 2 == 0 && g.nz % 2 == 0 &&
                          level_block.global_lower[0] % 2 == 0 &&
                          level_block.global_lower[2] % 2 == 0;
    if (!on_every_rank(comm, halvable) || cells <= options.max_coarse_cells) {
      // the host's copy of the rows, with global columns; every block's on a split grid
      const CsrMatrix rows = block.split() ? to_csr_matrix(assemble_tall_cell_matrix(
                                                 exec, *level_grid, level_A, false, carriers))
                                           : to_csr_matrix(L->A_t.local);
      const CsrMatrix whole =
          block.split() ? gather_rows(comm, rows, coarse_counts_, coarse_displacements_) : rows;
      Kokkos::Profiling::pushRegion("amphora::tall_mg::coarse_cholesky");
      coarse_ = std::make_unique<CoarseCholesky>(whole);
      Kokkos::Profiling::popRegion();
      coarse_first_ = level_grid->first_unknown();
      coarse_host_.resize(whole.n);
      coarse_local_.resize(n);
      levels_.push_back(std::move(L));
      break;
    }
    // The smoothed interval ends at Gershgorin's bound of lambda_max(D^-1 A) over all blocks'
    // rows: 3.01-3.06 on the levels of the deep splash, where 12 Lanczos steps estimated 2.91-2.95
    // (so 1.2 lambda = 3.5 was the end before), at no operator applications.
    ChebyshevOptions smoothing;
    smoothing.degree = l == 0 ? options.fine_chebyshev_degree : options.chebyshev_degree;
    smoothing.smoothing_range = options.smoothing_range;
    smoothing.lambda_max_bound = jacobi_gershgorin_bound(exec, L->A_t.local);
    MPI_Allreduce(MPI_IN_PLACE, &smoothing.lambda_max_bound, 1, MPI_DOUBLE, MPI_MAX, comm);
    Kokkos::Profiling::pushRegion("amphora::tall_mg::smoother");
    L->smoother = std::make_unique<ChebyshevSmoother<ExecSpace, Csr, Vector, BlockInnerProduct>>(
        exec, L->A_t, L->A_t.inverse_diagonal, smoothing, inner);
    Kokkos::Profiling::popRegion();
    // the next level: the coarser lattice, its tall cells following this level's
    Kokkos::Profiling::pushRegion("amphora::tall_mg::coarse_grid");
    // the coarser lattice's stencil: a kept one coarsened again from the rows that can differ
    const bool keeps = kept && static_cast<std::size_t>(l) < kept->levels.size();
    Stencil coarse = keeps ? kept->levels[l] : Stencil(level_A.grid.coarsened());
    unchanged_below =
        keeps ? kernels::mac::first_coarse_row_changed(unchanged_below, level_A.phi.extent(0) > 0)
              : 0;
    kernels::mac::coarsen_stencil(exec, level_A, coarse, unchanged_below);
    complete_block_stencil(exec, halo_, &level_A, coarse);
    if (keeps)
      kept->levels[l] = coarse;
    else if (kept)
      kept->levels.push_back(coarse);
    level_A = coarse;
    for (int d : {0, 2}) level_block.global_lower[d] /= 2;
    mesh::mac::TallCellGrid coarse_grid(exec, level_A, *level_grid, level_block);
    const auto coarse_carriers = tall_cell_carriers(exec, coarse_grid);
    Kokkos::Profiling::popRegion();
    Kokkos::Profiling::pushRegion("amphora::tall_mg::transfer");
    auto transfer = tall_cell_level_transfer(exec, *level_grid, coarse_grid, level_A, carriers);
    L->prolongation = Csr(std::move(transfer.prolongation), coarse_grid, coarse_carriers);
    L->restriction = Csr(std::move(transfer.restriction), *level_grid, carriers);
    Kokkos::Profiling::popRegion();
    levels_.push_back(std::move(L));
    carriers = coarse_carriers;
    coarse_level_grid.emplace(std::move(coarse_grid));  // the finer one is done with
    level_grid = &*coarse_level_grid;
  }
}

template <class ExecSpace>
void TallCellMultigrid<ExecSpace>::vcycle(const ExecSpace& exec, int l, const Vector& b,
                                          const Vector& x) const {
  const Level& L = *levels_[l];
  if (l + 1 == levels()) {
    const int n = static_cast<int>(coarse_local_.size());
    Kokkos::View<double*, kernels::HostMemSpace, Kokkos::MemoryTraits<Kokkos::Unmanaged>> local(
        coarse_local_.data(), n);
    Kokkos::deep_copy(exec, local, b);
    exec.fence();
    if (halo_.block().split())
      MPI_Allgatherv(coarse_local_.data(), n, MPI_DOUBLE, coarse_host_.data(),
                     coarse_counts_.data(), coarse_displacements_.data(), MPI_DOUBLE,
                     halo_.block().comm);
    else
      coarse_host_ = coarse_local_;
    coarse_->solve(coarse_host_.data(), coarse_host_.data());
    for (int i = 0; i < n; ++i) coarse_local_[i] = coarse_host_[coarse_first_ + i];
    Kokkos::deep_copy(exec, x, local);
    return;
  }
  const Level& C = *levels_[l + 1];
  L.smoother->smooth(exec, b, x, true);
  L.A_t.residual(exec, b, x, L.r);
  L.restriction.apply(exec, L.r, C.b);
  vcycle(exec, l + 1, C.b, C.x);
  L.prolongation.apply(exec, C.x, L.r);
  kernels::blas1::axpy(exec, 1.0, L.r, x);
  L.smoother->smooth(exec, b, x, false);
}

template class TallCellMultigrid<kernels::DefaultExecSpace>;
#if defined(KOKKOS_ENABLE_SERIAL) && defined(KOKKOS_ENABLE_OPENMP)
template class TallCellMultigrid<Kokkos::Serial>;
#endif

}  // namespace amphora::solvers::mac
