#pragma once
// Multigrid for the tall-cell pressure matrix A_t = P^T A P, as a CG preconditioner: a
// hierarchy of tall-cell grids over lattices with cells twice as wide, each coarse tall cell
// ending where the finer ones under it end (mesh::mac::TallCellGrid's coarser-level constructor; in
// the spirit of the restricted tall-cell grids of Chentanez & Müller 2011), each level's matrix
// assembled as P_l^T A_l P_l from the rediscretised lattice matrix A_l. Between
// tall-cell levels the prolongation Q interpolates the coarse tall-cell pressure at the fine
// unknowns (trilinear between cells, linear in height inside tall cells) and the restriction
// is Q^T, both assembled (tall_cell_level_transfer.hpp), so a V-cycle costs work in proportion
// to the unknowns, not to the lattices under them. Chebyshev–Jacobi smoothing on each level
// (parallel, symmetric; the interval from Gershgorin's bound), exact sparse Cholesky on the
// coarsest.
//
// On a split grid (T.block()) every level keeps the blocks, halved, as the uniform multigrid
// does: each level's rows of A_t and of the transfers with the ghost ring's columns
// (BlockCsrMatrix), inner products summed over the ranks, and the coarsest system gathered and
// factorised on every rank.
#include <memory>
#include <vector>

#include "solvers/chebyshev.hpp"
#include "solvers/device_csr.hpp"
#include "solvers/mac/block_csr_matrix.hpp"
#include "solvers/mac/coarse_cholesky.hpp"
#include "solvers/mac/mac_multigrid.hpp"

namespace amphora::solvers::mac {

struct TallCellMultigridOptions {
  /// Chebyshev degree on the finest level and on the coarser ones: a cheaper smoother on the
  /// finest level, where a step costs most, is worth a few more iterations (the measured
  /// choice is in docs/water.md).
  int fine_chebyshev_degree = 2;
  int chebyshev_degree = 3;
  double smoothing_range = 8.0;
  long max_coarse_cells =
      4096;  ///< coarsest lattice size (the tall-cell system on it is factorised)
};

/// The coarse levels' lattice stencils, kept by a caller between multigrids built over a finest
/// stencil that changes from some row up only (the water module's, rebuilt from under the
/// lowest band): each level's is then coarsened again only from the first row its finer one can
/// have changed in (kernels::mac::first_coarse_row_changed). For one grid and block.
template <class MemSpace>
struct KeptCoarseStencils {
  std::vector<kernels::mac::PoissonStencil<MemSpace>> levels;  ///< empty at first
  /// The finest stencil's rows below this are what they were at the last multigrid built with
  /// these (0: none known, every row coarsened); set by the caller before each.
  int unchanged_below = 0;
};

template <class ExecSpace>
class TallCellMultigrid {
 public:
  using MemSpace = typename ExecSpace::memory_space;
  using Vector = Kokkos::View<double*, MemSpace>;
  using Stencil = kernels::mac::PoissonStencil<MemSpace>;
  using Csr = BlockCsrMatrix<MemSpace>;

  /// For A_t = P^T A P of the tall-cell grid T over the uniform stencil A (on a split grid: this
  /// block's rows, and A's ghost conductances exchanged), each level's assembled on the device.
  /// Collective over T.block()'s ranks. With `kept`, the coarse lattice stencils are taken from
  /// and left in it.
  TallCellMultigrid(const ExecSpace& exec, const mesh::mac::TallCellGrid& T, const Stencil& A,
                    const TallCellMultigridOptions& options = {},
                    KeptCoarseStencils<MemSpace>* kept = nullptr);
  TallCellMultigrid(const TallCellMultigrid&) = delete;  // the smoothers point at the matrices
  TallCellMultigrid& operator=(const TallCellMultigrid&) = delete;

  const Csr& matrix() const { return levels_[0]->A_t; }
  int levels() const { return static_cast<int>(levels_.size()); }

  /// z = one V-cycle applied to r.
  void apply(const ExecSpace& exec, const Vector& r, const Vector& z) const {
    vcycle(exec, 0, r, z);
  }

  /// Multigrid-preconditioned CG on A_t y = b from the guess in y.
  SolverResult solve(const ExecSpace& exec, const Vector& b, const Vector& y,
                     const SolverControl& control) const {
    return conjugate_gradient(exec, matrix(), b, y, control, *this,
                              BlockInnerProduct{halo_.block().comm});
  }

 private:
  struct Level {
    Csr A_t;
    Csr prolongation, restriction;  // from and to the next coarser level (none on the coarsest)
    std::unique_ptr<ChebyshevSmoother<ExecSpace, Csr, Vector, BlockInnerProduct>> smoother;
    Vector b, x, r;
  };
  void vcycle(const ExecSpace& exec, int l, const Vector& b, const Vector& x) const;

  mesh::mac::LatticeGhostExchange halo_;
  std::vector<std::unique_ptr<Level>> levels_;
  std::unique_ptr<CoarseCholesky> coarse_;
  // the coarsest system gathered: this block's rows start at coarse_first_ of coarse_host_
  long coarse_first_ = 0;
  std::vector<int> coarse_counts_, coarse_displacements_;
  mutable std::vector<double> coarse_host_, coarse_local_;
};

extern template class TallCellMultigrid<kernels::DefaultExecSpace>;
#if defined(KOKKOS_ENABLE_SERIAL) && defined(KOKKOS_ENABLE_OPENMP)
extern template class TallCellMultigrid<Kokkos::Serial>;
#endif

}  // namespace amphora::solvers::mac
