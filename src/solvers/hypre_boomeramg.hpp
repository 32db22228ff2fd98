#pragma once
// hypre's BoomerAMG on an assembled CSR matrix: one V-cycle as a coarse-grid solver or
// preconditioner, or BoomerAMG-preconditioned CG (hypre's own PCG) for comparisons. The matrix
// is rank-local, or the rows first_row.. of a matrix distributed over a communicator (column
// numbers global).
// Defaults are the best setting measured for 3D Poisson here (one level of aggressive
// coarsening, HMIS, extended+i interpolation, l1 symmetric hybrid Gauss–Seidel).
#include <mpi.h>

#include <memory>

#include "solvers/csr_matrix.hpp"

namespace amphora::solvers {

struct BoomerAMGOptions {
  double strong_threshold = 0.5;
  int aggressive_levels = 1;
  int coarsen_type = 10;  // HMIS
  int interp_type = 6;    // extended+i
  int relax_type = 8;     // l1 symmetric hybrid Gauss–Seidel
  int p_max = 4;          // interpolation entries per row
};

struct HypreSolveResult {
  int iterations = 0;
  double final_relative_residual = 0.0;
};

class BoomerAMG {
 public:
  BoomerAMG(const CsrMatrix& A, const BoomerAMGOptions& options = {});
  /// This rank's rows [first_row, first_row + A.n) of a matrix distributed over comm
  /// (collective; vectors are this rank's n entries).
  BoomerAMG(MPI_Comm comm, long first_row, const CsrMatrix& A,
            const BoomerAMGOptions& options = {});
  ~BoomerAMG();
  BoomerAMG(const BoomerAMG&) = delete;
  BoomerAMG& operator=(const BoomerAMG&) = delete;

  /// x = one V-cycle applied to b, from x = 0 (host arrays of n entries); sets up on first use.
  void vcycle(const double* b, double* x) const;
  /// BoomerAMG-preconditioned CG to ||r|| <= rel ||b||, from x (a fresh setup is done: its
  /// time is part of what a caller measures).
  HypreSolveResult pcg(const double* b, double* x, double relative_tolerance,
                       int max_iterations) const;
  /// BoomerAMG-preconditioned restarted GMRES (hypre's own; right preconditioning) for
  /// non-symmetric systems, the same way.
  HypreSolveResult gmres(const double* b, double* x, double relative_tolerance, int max_iterations,
                         int restart = 60) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace amphora::solvers
