#pragma once
// The pressure of one projection on a MAC lattice: A p = b on the lattice's fluid cells, or,
// with an optical depth D > 0, on the tall-cell grid of A's fluid cells (Irving et al. 2006):
// P^T A P y = P^T b for the tall-cell unknowns y, then p = P y on the lattice. The module hands
// over the stencil, the right-hand side and the pressure (its last values are the guess); the
// change of variables, guess, solver and prolongation are done here. Two calls, so a caller can
// time the setup and the solve apart.
#include <memory>
#include <optional>

#include "kernels/mac/poisson_stencil.hpp"
#include "kernels/mac/tall_cell_layout.hpp"
#include "mesh/mac/lattice_halo.hpp"
#include "solvers/mac/pressure_solver.hpp"
#include "solvers/mac/tall_cell_multigrid.hpp"

namespace amphora::solvers::mac {

template <class ExecSpace>
class LatticePressure {
 public:
  using Mem = typename ExecSpace::memory_space;
  using Vector = Kokkos::View<double*, Mem>;
  using Stencil = kernels::mac::PoissonStencil<Mem>;

  /// Prepares the solve of A p = b (optical_depth 0) or of the tall-cell system (> 0): on tall
  /// cells the grid, its matrix, P^T b and the guess G^-1 P^T p (the last pressure fitted to
  /// this grid by least squares, as the uniform solve starts from p itself). `kept`: the
  /// tall-cell multigrid's coarse stencils, kept between projections (may be null). Collective
  /// on a split grid.
  LatticePressure(const ExecSpace& exec, PressureBackend backend, int optical_depth,
                  const Stencil& A, const mesh::mac::MacBlock& block, const Vector& b,
                  const Vector& p, KeptCoarseStencils<Mem>* kept = nullptr);
  /// Solves to `control` and leaves the lattice pressure in p.
  SolverResult solve(const ExecSpace& exec, const SolverControl& control);
  /// The unknowns of the solve over all blocks: the tall-cell grid's, or (uniform) none known
  /// here (-1: the fluid cells, which the caller counts when it needs them).
  long global_unknowns() const { return global_unknowns_; }

 private:
  std::unique_ptr<PressureSolver<ExecSpace>> solver_;
  Vector b_, p_, bt_, y_;  ///< lattice right-hand side and pressure; tall-cell ones
  std::optional<kernels::mac::TallCellLayout<Mem>> layout_;
  long global_unknowns_ = -1;
};

}  // namespace amphora::solvers::mac
