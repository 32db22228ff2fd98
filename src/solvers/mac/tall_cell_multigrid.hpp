#pragma once
// Multigrid for the tall-cell pressure matrix A_t = P^T A P, as a CG preconditioner: a
// hierarchy of tall-cell grids over lattices with cells twice as wide, the same optical depth
// in metres (in the spirit of the restricted tall-cell grids of Chentanez & Müller 2011), each
// level's matrix assembled as P_l^T A_l P_l from the rediscretised lattice matrix A_l. Between
// tall-cell levels l and l+1
//   Q = G_l^-1 P_l^T P_u P_{l+1},  G_l = P_l^T P_l   (coarse tall -> coarse lattice -> fine
//                                  lattice by trilinear P_u -> least-squares fit on level l),
//   restriction Q^T = P_{l+1}^T P_u^T P_l G_l^-1,
// so Q^T A_t,l Q ~ A_t,l+1 on functions the coarse level represents. Chebyshev–Jacobi smoothing
// on each level (parallel, symmetric), exact sparse Cholesky on the coarsest. The transfers pass
// over the lattices; all smoothing is on the tall-cell unknowns.
//
// On a grid split over ranks (T.block()) every level keeps the blocks, halved, as the uniform
// multigrid does: each level's rows of A_t with the ghost ring's columns (BlockCsrMatrix), the
// lattices' ghost layers exchanged before the restriction and the prolongation read across the
// block faces, inner products summed over the ranks, and the coarsest system gathered and
// factorised on every rank.
#include <memory>
#include <vector>

#include "kernels/mac/tall_cell_transfer.hpp"
#include "solvers/chebyshev.hpp"
#include "solvers/device_csr.hpp"
#include "solvers/mac/block_csr_matrix.hpp"
#include "solvers/mac/coarse_cholesky.hpp"
#include "solvers/mac/mac_multigrid.hpp"

namespace amphora::solvers::mac {

struct TallCellMultigridOptions {
  int chebyshev_degree = 3;
  double smoothing_range = 8.0;
  long max_coarse_cells = 4096;  ///< coarsest lattice size (the tall-cell system on it is factorised)
};

template <class ExecSpace>
class TallCellMultigrid {
 public:
  using MemSpace = typename ExecSpace::memory_space;
  using Vector = Kokkos::View<double*, MemSpace>;
  using Stencil = kernels::mac::PoissonStencil<MemSpace>;
  using Csr = BlockCsrMatrix<MemSpace>;

  /// T and A_t = P^T A P of the uniform stencil A (on a split grid: this block's rows, and A's
  /// ghost conductances exchanged). Collective over T.block()'s ranks.
  TallCellMultigrid(const ExecSpace& exec, const mesh::TallCellGrid& T, const CsrMatrix& A_t, const Stencil& A,
                    const TallCellMultigridOptions& options = {});
  TallCellMultigrid(const TallCellMultigrid&) = delete;  // the smoothers point at the matrices
  TallCellMultigrid& operator=(const TallCellMultigrid&) = delete;

  const Csr& matrix() const { return levels_[0]->A_t; }
  int levels() const { return static_cast<int>(levels_.size()); }

  /// z = one V-cycle applied to r.
  void apply(const ExecSpace& exec, const Vector& r, const Vector& z) const { vcycle(exec, 0, r, z); }

  /// Multigrid-preconditioned CG on A_t y = b from the guess in y.
  SolverResult solve(const ExecSpace& exec, const Vector& b, const Vector& y, const SolverControl& control) const {
    return conjugate_gradient(exec, matrix(), b, y, control, *this, BlockInnerProduct{halo_.block().comm});
  }

 private:
  struct Level {
    mesh::TallCellLayout<MemSpace> layout;
    Stencil A;  // the lattice matrix
    Csr A_t;
    std::unique_ptr<ChebyshevSmoother<ExecSpace, Csr, Vector, BlockInnerProduct>> smoother;
    Vector b, x, r, lattice;
  };
  void vcycle(const ExecSpace& exec, int l, const Vector& b, const Vector& x) const;
  /// The ghost layer of a level's lattice field (nothing on one block).
  void sync(const ExecSpace& exec, const Level& L, const Vector& v) const { halo_.exchange(exec, L.A.grid, v); }

  mesh::LatticeGhostExchange halo_;
  std::vector<std::unique_ptr<Level>> levels_;
  std::unique_ptr<CoarseCholesky> coarse_;
  // the coarsest system gathered: this block's rows start at coarse_first_ of coarse_host_
  long coarse_first_ = 0;
  std::vector<int> coarse_counts_, coarse_displacements_;
  mutable std::vector<double> coarse_host_, coarse_local_;
};

extern template class TallCellMultigrid<DefaultExecSpace>;
#if defined(KOKKOS_ENABLE_SERIAL) && defined(KOKKOS_ENABLE_OPENMP)
extern template class TallCellMultigrid<Kokkos::Serial>;
#endif

}  // namespace amphora::solvers::mac
