#pragma once
// hypre's Struct interface for the 7-point MAC pressure matrix: CG preconditioned by one PFMG
// V-cycle (Ashby & Falgout 1996; Falgout & Jones 2000), the reference solver of uniform grids.
// The box of cells a rank owns is given in global indices; values come on the padded lattice
// of its MacGrid, whose ghost layer holds the conductances towards neighbouring ranks.
#include <mpi.h>

#include <array>
#include <memory>

#include "kernels/mac/mac_grid.hpp"
#include "solvers/hypre_boomeramg.hpp"

namespace amphora::solvers {

struct StructPfmgOptions {
  int relax_type = 2;  ///< symmetric red-black Gauss–Seidel
  int pre_relax = 1, post_relax = 1;
  int rap_type = 0;  ///< Galerkin coarse operators
  int skip_relax = 1;
};

class StructPfmgCG {
 public:
  /// diag/cx/cy/cz: host arrays on g's padded lattice (MacPoisson stencil form). Cells with
  /// diag 0 become identity rows (their right-hand side must be zero).
  StructPfmgCG(MPI_Comm comm, const kernels::mac::MacGrid& g, std::array<int, 3> global_lower,
               const double* diag, const float* cx, const float* cy, const float* cz,
               const StructPfmgOptions& options = {});
  ~StructPfmgCG();
  StructPfmgCG(const StructPfmgCG&) = delete;
  StructPfmgCG& operator=(const StructPfmgCG&) = delete;

  /// PFMG-CG to ||r|| <= rel ||b|| from the guess in x (padded host arrays); the PFMG setup is
  /// done in the first solve.
  HypreSolveResult solve(const double* b, double* x, double relative_tolerance, int max_iterations);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace amphora::solvers
