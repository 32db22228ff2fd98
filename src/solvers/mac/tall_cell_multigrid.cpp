#include "solvers/mac/tall_cell_multigrid.hpp"

#include "solvers/mac/tall_cell_matrix.hpp"

namespace amphora::solvers::mac {

template <class ExecSpace>
TallCellMultigrid<ExecSpace>::TallCellMultigrid(const ExecSpace& exec, const mesh::TallCellGrid& T,
                                                const CsrMatrix& A_t, const Stencil& A,
                                                const TallCellMultigridOptions& options) {
  const ChebyshevOptions smoothing{options.chebyshev_degree, options.smoothing_range, 12};
  CsrMatrix level_matrix = A_t;
  mesh::TallCellGrid level_grid = T;
  Stencil level_A = A;
  for (int l = 0;; ++l) {
    auto L = std::make_unique<Level>();
    L->layout = mesh::make_layout<MemSpace>(level_grid);
    L->A = level_A;
    L->A_t = Csr(level_matrix);
    const int n = L->A_t.n;
    L->b = Vector("amphora::tall_mg::b", n);
    L->x = Vector("amphora::tall_mg::x", n);
    L->r = Vector("amphora::tall_mg::r", n);
    L->lattice = Vector("amphora::tall_mg::lattice", level_A.grid.padded_size());
    const mesh::MacGrid g = level_A.grid;
    const bool coarsest = g.nx % 2 || g.ny % 2 || g.nz % 2 || g.cells() <= options.max_coarse_cells;
    if (coarsest) {
      coarse_ = std::make_unique<CoarseCholesky>(level_matrix);
      coarse_host_.resize(n);
      levels_.push_back(std::move(L));
      break;
    }
    L->smoother = std::make_unique<ChebyshevSmoother<ExecSpace, Csr, Vector>>(exec, L->A_t, L->A_t.inverse_diagonal,
                                                                              smoothing);
    levels_.push_back(std::move(L));
    // the next level: the same optical depth in metres on the coarser lattice
    level_A = kernels::mac::coarsen_stencil(exec, level_A);
    const int depth = (T.optical_depth() + (2 << l) - 1) >> (l + 1);
    const auto host_A = kernels::mac::copy_stencil<HostMemSpace>(level_A);
    level_grid = mesh::TallCellGrid(host_A, std::max(depth, 1));
    level_matrix = assemble_tall_cell_matrix(level_grid, host_A);
  }
}

template <class ExecSpace>
void TallCellMultigrid<ExecSpace>::vcycle(const ExecSpace& exec, int l, const Vector& b, const Vector& x) const {
  const Level& L = *levels_[l];
  if (l + 1 == levels()) {
    Kokkos::View<double*, HostMemSpace, Kokkos::MemoryTraits<Kokkos::Unmanaged>> host(coarse_host_.data(),
                                                                                     coarse_host_.size());
    Kokkos::deep_copy(exec, host, b);
    exec.fence();
    coarse_->solve(coarse_host_.data(), coarse_host_.data());
    Kokkos::deep_copy(exec, x, host);
    return;
  }
  const Level& C = *levels_[l + 1];
  L.smoother->smooth(exec, b, x, true);
  // restriction: r -> G^-1 r -> lattice -> coarse lattice -> coarse tall unknowns
  kernels::mac::residual_csr(exec, L.A_t, b, x, L.r);
  kernels::mac::tall_cell_gram_solve(exec, L.layout, L.r);
  kernels::mac::tall_cell_prolongate(exec, L.layout, L.r, L.lattice);
  kernels::mac::restrict_residual(exec, L.A, C.A, L.lattice, C.lattice);
  kernels::mac::tall_cell_restrict(exec, C.layout, C.lattice, C.b);
  vcycle(exec, l + 1, C.b, C.x);
  // prolongation: coarse tall -> coarse lattice -> lattice -> fit -> add
  kernels::mac::tall_cell_prolongate(exec, C.layout, C.x, C.lattice);
  blas1::fill(exec, L.lattice, 0.0);
  kernels::mac::prolongate_correction(exec, C.A, L.A, C.lattice, L.lattice);
  kernels::mac::tall_cell_restrict(exec, L.layout, L.lattice, L.r);
  kernels::mac::tall_cell_gram_solve(exec, L.layout, L.r);
  blas1::axpy(exec, 1.0, L.r, x);
  L.smoother->smooth(exec, b, x, false);
}

template class TallCellMultigrid<DefaultExecSpace>;
#if defined(KOKKOS_ENABLE_SERIAL) && defined(KOKKOS_ENABLE_OPENMP)
template class TallCellMultigrid<Kokkos::Serial>;
#endif

}  // namespace amphora::solvers::mac
