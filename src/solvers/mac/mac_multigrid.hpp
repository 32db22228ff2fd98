#pragma once
// Geometric multigrid for the MAC pressure Poisson matrix, as a preconditioner for CG
// (MGPCG: McAdams, Sifakis & Teran 2010). Levels halve the grid while every dimension is even;
// red-black Gauss–Seidel smoothing (red then black before the coarse correction, black then red
// after, so the V-cycle is symmetric), trilinear prolongation and its transpose, coarse matrices
// by re-discretisation (kernels/mac/grid_transfer.hpp), and an exact sparse Cholesky solve on the
// coarsest grid. The preconditioner works in single precision (matrices and vectors): on these
// memory-bound sweeps that halves the time, and CG, in double, is unaffected at 1e-8.
//
// On a grid split horizontally over ranks (mesh::mac::MacBlock) every level keeps the blocks
// (halved), ghost layers are exchanged before each half-sweep, residual and transfer, the red-black
// colour follows the global cell index, the coarsest grid is gathered on every rank and solved
// there, and CG's inner products are summed over the ranks: the V-cycle is the single-block one, so
// the iterations do not depend on the rank count.
#include <memory>
#include <string>
#include <vector>

#include "kernels/host_vector.hpp"
#include "kernels/mac/grid_transfer.hpp"
#include "mesh/mac/lattice_halo.hpp"
#include "solvers/conjugate_gradient.hpp"
#include "solvers/mac/coarse_cholesky.hpp"
#include "solvers/mac/stencil_csr.hpp"

namespace amphora::solvers::mac {

struct MacMultigridOptions {
  int smoothing_steps = 2;       ///< red-black sweeps before and after the coarse correction
  long max_coarse_cells = 4096;  ///< largest coarsest grid factorised directly
  /// Levels of at most this many cells are smoothed by one team in one launch per smoothing
  /// (red_black_gauss_seidel_team: on a device, 2 launches a level a V-cycle where the sweeps
  /// take 4 smoothing_steps 2^l); 0: never. Unsplit grids only. Opt-in until a GPU measures it.
  long team_smoothing_cells = 0;
  int team_size = 0;  ///< of that team; 0: the largest the execution space allows (<= 1024)
};

/// Empty if the multigrid can coarsen g down to at most max_coarse_cells; otherwise a message
/// naming the dimension at fault and the nearest sizes that work.
std::string multigrid_size_error(const kernels::mac::MacGrid& g, long max_coarse_cells);

/// Completes a level of a split grid's stencil hierarchy: on a coarse level (`fine` given: the
/// level it was coarsened from) the ghost cells' + faces and the diagonal at the block faces,
/// then on every level the ghost diagonal, solid flags and solid shares; `any_solid` becomes the
/// same on every rank. Collective over the block's ranks; on one block only `any_solid` is set.
template <class ExecSpace, class MemSpace>
void complete_block_stencil(const ExecSpace& exec, const mesh::mac::LatticeGhostExchange& halo,
                            const kernels::mac::PoissonStencil<MemSpace>* fine,
                            kernels::mac::PoissonStencil<MemSpace>& level);

/// CG's inner products over the blocks of a split grid: local sums (ghost entries of one factor
/// are zero in every product CG forms) added over the ranks.
struct BlockInnerProduct {
  MPI_Comm comm = MPI_COMM_SELF;
  static constexpr bool fuses_cg_update = true;
  template <class ExecSpace, class X, class Y>
  double operator()(const ExecSpace& exec, const X& x, const Y& y) const {
    return sum(kernels::blas1::dot(exec, x, y));
  }
  template <class ExecSpace, class View>
  double fused_update(const ExecSpace& exec, double alpha, const View& p, const View& q,
                      const View& x, const View& r) const {
    return sum(kernels::blas1::cg_update(exec, alpha, p, q, x, r));
  }
  double sum(double local) const {
    double global = local;
    MPI_Allreduce(&local, &global, 1, MPI_DOUBLE, MPI_SUM, comm);
    return global;
  }
};

template <class ExecSpace>
class MacMultigrid {
 public:
  using MemSpace = typename ExecSpace::memory_space;
  using Stencil = kernels::mac::PoissonStencil<MemSpace>;
  using LevelStencil = kernels::mac::PoissonStencil<MemSpace, float>;
  using Vector = Kokkos::View<double*, MemSpace>;
  using LevelVector = Kokkos::View<float*, MemSpace>;

  /// Throws std::invalid_argument (multigrid_size_error) for grids it cannot coarsen. A is this
  /// block's matrix, its ghost conductances exchanged (see build_poisson_stencil).
  MacMultigrid(const ExecSpace& exec, const Stencil& A, const MacMultigridOptions& options = {},
               const mesh::mac::MacBlock& block = {});

  /// z = one V-cycle applied to r (the preconditioner of CG).
  void apply(const ExecSpace& exec, const Vector& r, const Vector& z) const;
  /// y = A x on the finest level (the operator of CG): x's ghosts exchanged first, y zero on
  /// every ghost cell.
  struct FineOperator {
    Stencil A;
    mesh::mac::LatticeGhostExchange halo;
    void apply(const ExecSpace& exec, const Vector& x, const Vector& y) const {
      halo.exchange(exec, A.grid, x);
      kernels::mac::apply(exec, A, x, y);
      if (halo.block().split()) kernels::mac::zero_ghost_cells(exec, A.grid, y);
    }
  };
  FineOperator fine_operator() const { return FineOperator{fine_, halo_}; }
  /// Multigrid-preconditioned CG from the guess in x; b must vanish on non-fluid and ghost cells.
  SolverResult solve(const ExecSpace& exec, const Vector& b, const Vector& x,
                     const SolverControl& control) const {
    return conjugate_gradient(exec, fine_operator(), b, x, control, *this,
                              BlockInnerProduct{halo_.block().comm});
  }

  int levels() const { return static_cast<int>(levels_.size()); }
  /// Bytes one V-cycle moves through memory, by a streaming model in which every array a kernel
  /// reads or writes crosses memory once per kernel (single precision): per level the fill, 4 nu
  /// red-black half-sweeps and the residual (x, b, a diagonal and three conductances read, one
  /// vector written: 28 B per cell each), restriction and prolongation; the conversions of r to
  /// and of z from single precision (24 B per fine cell). The coarsest grid's solve, a gather
  /// to the host of at most max_coarse_cells values, is left out.
  double bytes_per_application() const;
  /// The V-cycle's bytes plus CG's own on the fine grid in double precision (solve()): the
  /// direction p = z + beta p (24 B per cell), q = A p (x, y, diagonal in double and three float
  /// conductances: 36), p.q (16), the fused x and r update with r.r (48) and r.z (16).
  double bytes_per_cg_iteration() const {
    return bytes_per_application() + 140.0 * static_cast<double>(fine_.grid.padded_size());
  }
  const LevelStencil& level(int l) const { return levels_[l]; }

 public:  // (CUDA: extended lambdas may not live in private member functions)
  void vcycle(const ExecSpace& exec, int l) const;
  void coarse_solve(const ExecSpace& exec) const;
  void smooth(const ExecSpace& exec, int l, int first_colour) const;
  /// `steps` smoothings of level l (smooth's), by one team where the options say so.
  void smooth_steps(const ExecSpace& exec, int l, int first_colour, int steps) const;
  /// Ghost exchange of level l's block (nothing on one block).
  template <class View>
  void sync(const ExecSpace& exec, int l, const View& v) const {
    halo_.exchange(exec, levels_[l].grid, v);
  }
  void setup_coarse_solve(const Stencil& coarsest);
  kernels::host_mirror_t<Kokkos::View<double*, MemSpace>> coarsest_rows(
      const Stencil& coarsest) const;

 private:
  MacMultigridOptions options_;
  mesh::mac::LatticeGhostExchange halo_;
  Stencil fine_;
  std::vector<LevelStencil> levels_;
  std::vector<int> parity_;             // per level: (global i + k of the block's first cell) % 2
  std::vector<LevelVector> x_, b_, r_;  // per level
  std::vector<std::string> regions_;    // per level: its Kokkos::Profiling region
  // the coarsest grid gathered from every block: this block's interior cells (k, j, i order),
  // where the gathered values go in the whole coarsest grid, and its fluid cells' numbering
  Kokkos::View<int*, MemSpace> coarse_cells_;
  std::vector<int> gathered_index_, counts_, displacements_;
  int my_offset_ = 0;
  CompactNumbering coarse_numbering_;
  std::unique_ptr<CoarseCholesky> coarse_;
  mutable Kokkos::View<float*, MemSpace> coarse_local_;
  kernels::host_mirror_t<Kokkos::View<float*, MemSpace>> coarse_send_;  // coarse_local_'s host side
  mutable std::vector<float> coarse_gathered_;
  mutable std::vector<double> coarse_lattice_, coarse_rhs_;
};

extern template class MacMultigrid<kernels::DefaultExecSpace>;
#if defined(KOKKOS_ENABLE_SERIAL) && defined(KOKKOS_ENABLE_OPENMP)
extern template class MacMultigrid<Kokkos::Serial>;
#endif

}  // namespace amphora::solvers::mac
