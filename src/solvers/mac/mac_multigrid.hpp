#pragma once
// Geometric multigrid for the MAC pressure Poisson matrix, as a preconditioner for CG
// (MGPCG: McAdams, Sifakis & Teran 2010). Levels halve the grid while every dimension is even;
// red-black Gauss–Seidel smoothing (red then black before the coarse correction, black then red
// after, so the V-cycle is symmetric), trilinear prolongation and its transpose, coarse matrices
// by re-discretisation (kernels/mac/grid_transfer.hpp), and an exact sparse Cholesky solve on the
// coarsest grid. The preconditioner works in single precision (matrices and vectors): on these
// memory-bound sweeps that halves the time, and CG, in double, is unaffected at 1e-8.
#include <memory>
#include <string>
#include <vector>

#include "kernels/host_vector.hpp"
#include "kernels/mac/grid_transfer.hpp"
#include "solvers/conjugate_gradient.hpp"
#include "solvers/mac/coarse_cholesky.hpp"
#include "solvers/mac/stencil_csr.hpp"

namespace amphora::solvers::mac {

struct MacMultigridOptions {
  int smoothing_steps = 2;         ///< red-black sweeps before and after the coarse correction
  long max_coarse_cells = 4096;    ///< largest coarsest grid factorised directly
};

/// Empty if the multigrid can coarsen g down to at most max_coarse_cells; otherwise a message
/// naming the dimension at fault and the nearest sizes that work.
std::string multigrid_size_error(const mesh::MacGrid& g, long max_coarse_cells);

template <class ExecSpace>
class MacMultigrid {
 public:
  using MemSpace = typename ExecSpace::memory_space;
  using Stencil = kernels::mac::PoissonStencil<MemSpace>;
  using LevelStencil = kernels::mac::PoissonStencil<MemSpace, float>;
  using Vector = Kokkos::View<double*, MemSpace>;
  using LevelVector = Kokkos::View<float*, MemSpace>;

  /// Throws std::invalid_argument (multigrid_size_error) for grids it cannot coarsen.
  MacMultigrid(const ExecSpace& exec, const Stencil& A, const MacMultigridOptions& options = {});

  /// z = one V-cycle applied to r (the preconditioner of CG).
  void apply(const ExecSpace& exec, const Vector& r, const Vector& z) const;
  /// y = A x on the finest level (the operator of CG).
  struct FineOperator {
    Stencil A;
    void apply(const ExecSpace& exec, const Vector& x, const Vector& y) const {
      kernels::mac::apply(exec, A, x, y);
    }
  };
  FineOperator fine_operator() const { return FineOperator{fine_}; }
  /// Multigrid-preconditioned CG from the guess in x; b must vanish on non-fluid cells.
  SolverResult solve(const ExecSpace& exec, const Vector& b, const Vector& x, const SolverControl& control) const {
    return conjugate_gradient(exec, fine_operator(), b, x, control, *this);
  }

  int levels() const { return static_cast<int>(levels_.size()); }
  const LevelStencil& level(int l) const { return levels_[l]; }

 private:
  void vcycle(const ExecSpace& exec, int l) const;

  MacMultigridOptions options_;
  Stencil fine_;
  std::vector<LevelStencil> levels_;
  std::vector<LevelVector> x_, b_, r_;  // per level
  CompactNumbering coarse_numbering_;
  std::unique_ptr<CoarseCholesky> coarse_;
  Kokkos::View<int*, MemSpace> coarse_cells_;
  mutable Kokkos::View<double*, MemSpace> coarse_compact_;
  mutable std::vector<double> coarse_host_;
};

template <class ExecSpace>
MacMultigrid<ExecSpace>::MacMultigrid(const ExecSpace& exec, const Stencil& A, const MacMultigridOptions& options)
    : options_(options) {
  const std::string error = multigrid_size_error(A.grid, options.max_coarse_cells);
  if (!error.empty()) throw std::invalid_argument(error);
  fine_ = A;
  // Down to a grid of at most 64 cells, or as far as the dimensions stay even (coarsened in
  // double, then stored in single precision).
  Stencil level = A;
  levels_.push_back(kernels::mac::convert_stencil<float>(exec, level));
  for (mesh::MacGrid g = A.grid; g.nx % 2 == 0 && g.ny % 2 == 0 && g.nz % 2 == 0 && g.cells() > 64;
       g = g.coarsened()) {
    level = kernels::mac::coarsen_stencil(exec, level);
    levels_.push_back(kernels::mac::convert_stencil<float>(exec, level));
  }
  for (const LevelStencil& S : levels_) {
    const long n = S.grid.padded_size();
    x_.emplace_back("amphora::mac_mg::x", n);  // zero, ghost entries stay zero
    b_.emplace_back("amphora::mac_mg::b", n);
    r_.emplace_back("amphora::mac_mg::r", n);
  }
  exec.fence();
  coarse_ = std::make_unique<CoarseCholesky>(stencil_to_csr(level, coarse_numbering_));
  coarse_cells_ = to_view<MemSpace>(coarse_numbering_.cell, "amphora::mac_mg::coarse_cells");
  coarse_compact_ = Vector("amphora::mac_mg::coarse_compact", coarse_numbering_.size());
  coarse_host_.resize(coarse_numbering_.size());
}

template <class ExecSpace>
void MacMultigrid<ExecSpace>::apply(const ExecSpace& exec, const Vector& r, const Vector& z) const {
  const LevelVector b = b_[0], x = x_[0];
  Kokkos::parallel_for(
      "amphora::mac_mg::to_single", RangePolicy<ExecSpace>(exec, 0, static_cast<int>(r.extent(0))),
      KOKKOS_LAMBDA(int c) { b(c) = static_cast<float>(r(c)); });
  vcycle(exec, 0);
  Kokkos::parallel_for(
      "amphora::mac_mg::to_double", RangePolicy<ExecSpace>(exec, 0, static_cast<int>(z.extent(0))),
      KOKKOS_LAMBDA(int c) { z(c) = x(c); });
}

template <class ExecSpace>
void MacMultigrid<ExecSpace>::vcycle(const ExecSpace& exec, int l) const {
  const LevelStencil& A = levels_[l];
  const LevelVector b = b_[l], x = x_[l];
  if (l + 1 == levels()) {
    // Exact solve: gather the fluid cells, factorised solve on the host, scatter back.
    const auto cells = coarse_cells_;
    const auto compact = coarse_compact_;
    const int n = static_cast<int>(cells.extent(0));
    Kokkos::parallel_for(
        "amphora::mac_mg::coarse_gather", RangePolicy<ExecSpace>(exec, 0, n),
        KOKKOS_LAMBDA(int u) { compact(u) = b(cells(u)); });
    Kokkos::View<double*, HostMemSpace, Kokkos::MemoryTraits<Kokkos::Unmanaged>> host(coarse_host_.data(), n);
    Kokkos::deep_copy(exec, host, compact);
    exec.fence();
    coarse_->solve(coarse_host_.data(), coarse_host_.data());
    Kokkos::deep_copy(exec, compact, host);
    blas1::fill(exec, x, 0.0f);
    Kokkos::parallel_for(
        "amphora::mac_mg::coarse_scatter", RangePolicy<ExecSpace>(exec, 0, n),
        KOKKOS_LAMBDA(int u) { x(cells(u)) = compact(u); });
    return;
  }
  const int nu = options_.smoothing_steps << l;
  blas1::fill(exec, x, 0.0f);
  for (int s = 0; s < nu; ++s) {
    kernels::mac::red_black_gauss_seidel(exec, A, b, x, 0);
    kernels::mac::red_black_gauss_seidel(exec, A, b, x, 1);
  }
  kernels::mac::residual(exec, A, b, x, r_[l]);
  kernels::mac::restrict_residual(exec, A, levels_[l + 1], r_[l], b_[l + 1]);
  vcycle(exec, l + 1);
  kernels::mac::prolongate_correction(exec, levels_[l + 1], A, x_[l + 1], x);
  for (int s = 0; s < nu; ++s) {
    kernels::mac::red_black_gauss_seidel(exec, A, b, x, 1);
    kernels::mac::red_black_gauss_seidel(exec, A, b, x, 0);
  }
}

extern template class MacMultigrid<DefaultExecSpace>;
#if defined(KOKKOS_ENABLE_SERIAL) && defined(KOKKOS_ENABLE_OPENMP)
extern template class MacMultigrid<Kokkos::Serial>;
#endif

}  // namespace amphora::solvers::mac
