#pragma once
// One interface to the three pressure back ends on a uniform MAC grid, chosen by name (a scene
// key): "multigrid" (own geometric MG-preconditioned CG on the execution space), "hypre" (hypre
// Struct PFMG-preconditioned CG), "mic0" (MIC(0)-preconditioned CG, host, sequential: the
// classical baseline). Vectors are on the padded lattice of the stencil's grid; b must vanish
// on non-fluid cells, and x is zero there on return.
//
// On a tall-cell grid the same names pick: "multigrid" (TallCellMultigrid-preconditioned CG),
// "hypre" (BoomerAMG-preconditioned CG), "mic0" (MIC(0)-CG on the assembled matrix); vectors
// are then in the tall-cell numbering.
#include <mpi.h>

#include <array>
#include <memory>
#include <string>

#include "kernels/mac/poisson_stencil.hpp"
#include "mesh/mac/lattice_halo.hpp"
#include "mesh/mac/tall_cell_grid.hpp"
#include "solvers/conjugate_gradient.hpp"
#include "solvers/csr_matrix.hpp"

namespace amphora::solvers::mac {

enum class PressureBackend { multigrid, hypre, mic0 };

/// Throws std::invalid_argument naming the allowed values.
PressureBackend parse_pressure_backend(const std::string& name);
const char* to_string(PressureBackend backend);

template <class ExecSpace>
class PressureSolver {
 public:
  using MemSpace = typename ExecSpace::memory_space;
  using Vector = Kokkos::View<double*, MemSpace>;
  virtual ~PressureSolver() = default;
  /// Solves A x = b to control's tolerances from the guess in x. On the uniform grid b is a
  /// padded lattice whose ghost ring must hold zeros: every back end counts it in the norms
  /// (multigrid and MIC(0) in their residuals too; with a non-zero ring neither converges).
  /// kernels::mac::pressure_rhs writes it so.
  virtual SolverResult solve(const ExecSpace& exec, const Vector& b, const Vector& x,
                             const SolverControl& control) = 0;
  virtual PressureBackend backend() const = 0;
  /// Bytes one iteration moves through memory by a streaming model of its kernels (the bound a
  /// benchmark divides the measured bandwidth by), or 0 where the back end has no such model.
  virtual double bytes_per_iteration() const { return 0.0; }
};

/// A grid split over ranks: `block` says where this rank's part lies (mesh::mac::MacBlock; its
/// stencil's ghost conductances exchanged). The multigrid and hypre back ends solve a split
/// grid; MIC(0), sequential by nature, refuses one.
using mesh::mac::MacBlock;

template <class ExecSpace>
std::unique_ptr<PressureSolver<ExecSpace>> make_pressure_solver(
    PressureBackend backend, const ExecSpace& exec,
    const kernels::mac::PoissonStencil<typename ExecSpace::memory_space>& A,
    const MacBlock& block = {});

template <class MemSpace>
struct KeptCoarseStencils;  // tall_cell_multigrid.hpp

/// A_t = P^T A P of the tall-cell grid T over the uniform stencil A (on a split grid: this
/// block's rows; MIC(0) refuses one), assembled where its back end reads it: the multigrid's on
/// the device, hypre's and IC(0)'s on the host.
/// `kept`: the multigrid's coarse lattice stencils, kept between solvers (the other back ends
/// have none).
template <class ExecSpace>
std::unique_ptr<PressureSolver<ExecSpace>> make_tall_cell_pressure_solver(
    PressureBackend backend, const ExecSpace& exec, const mesh::mac::TallCellGrid& T,
    const kernels::mac::PoissonStencil<typename ExecSpace::memory_space>& A,
    KeptCoarseStencils<typename ExecSpace::memory_space>* kept = nullptr);

}  // namespace amphora::solvers::mac
