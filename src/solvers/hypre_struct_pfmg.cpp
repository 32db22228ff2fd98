#include "solvers/hypre_struct_pfmg.hpp"

#include <HYPRE.h>
#include <HYPRE_struct_ls.h>

#include <vector>

namespace amphora::solvers {

struct StructPfmgCG::Impl {
  kernels::mac::MacGrid g;
  StructPfmgOptions options;
  HYPRE_Int lower[3], upper[3];
  HYPRE_StructGrid grid = nullptr;
  HYPRE_StructStencil stencil = nullptr;
  HYPRE_StructMatrix A = nullptr;
  HYPRE_StructVector b = nullptr, x = nullptr;
  HYPRE_StructSolver pcg = nullptr, pfmg = nullptr;
  bool set_up = false;
  std::vector<double> buffer;

  /// Copies the interior of a padded array to/from hypre's box order (x fastest).
  void pack(const double* padded) {
    long u = 0;
    for (int k = 0; k < g.nz; ++k)
      for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i) buffer[u++] = padded[g.index(i, j, k)];
  }
  void unpack(double* padded) const {
    long u = 0;
    for (int k = 0; k < g.nz; ++k)
      for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i) padded[g.index(i, j, k)] = buffer[u++];
  }
};

StructPfmgCG::StructPfmgCG(MPI_Comm comm, const kernels::mac::MacGrid& g,
                           std::array<int, 3> global_lower, const double* diag, const float* cx,
                           const float* cy, const float* cz, const StructPfmgOptions& options)
    : impl_(std::make_unique<Impl>()) {
  HYPRE_Init();  // idempotent in hypre 2.26
  Impl& s = *impl_;
  s.g = g;
  s.options = options;
  const int n[3] = {g.nx, g.ny, g.nz};
  for (int d = 0; d < 3; ++d) {
    s.lower[d] = global_lower[d];
    s.upper[d] = global_lower[d] + n[d] - 1;
  }
  HYPRE_StructGridCreate(comm, 3, &s.grid);
  HYPRE_StructGridSetExtents(s.grid, s.lower, s.upper);
  HYPRE_StructGridAssemble(s.grid);
  HYPRE_StructStencilCreate(3, 7, &s.stencil);
  HYPRE_Int offsets[7][3] = {{0, 0, 0}, {-1, 0, 0}, {1, 0, 0}, {0, -1, 0},
                             {0, 1, 0}, {0, 0, -1}, {0, 0, 1}};
  for (int e = 0; e < 7; ++e) HYPRE_StructStencilSetElement(s.stencil, e, offsets[e]);
  HYPRE_StructMatrixCreate(comm, s.grid, s.stencil, &s.A);
  HYPRE_StructMatrixInitialize(s.A);
  const long cells = g.cells();
  std::vector<double> values(7 * cells);
  const int sy = g.stride_y(), sz = g.stride_z();
  long u = 0;
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i, ++u) {
        const int c = g.index(i, j, k);
        double* v = &values[7 * u];
        if (diag[c] > 0.0) {
          v[0] = diag[c];
          v[1] = -cx[c - 1], v[2] = -cx[c], v[3] = -cy[c - sy], v[4] = -cy[c], v[5] = -cz[c - sz],
          v[6] = -cz[c];
        } else {
          v[0] = 1.0;
          for (int e = 1; e < 7; ++e) v[e] = 0.0;
        }
      }
  HYPRE_Int entries[7] = {0, 1, 2, 3, 4, 5, 6};
  HYPRE_StructMatrixSetBoxValues(s.A, s.lower, s.upper, 7, entries, values.data());
  HYPRE_StructMatrixAssemble(s.A);
  HYPRE_StructVectorCreate(comm, s.grid, &s.b);
  HYPRE_StructVectorCreate(comm, s.grid, &s.x);
  HYPRE_StructVectorInitialize(s.b);
  HYPRE_StructVectorInitialize(s.x);
  s.buffer.resize(cells);

  HYPRE_StructPCGCreate(comm, &s.pcg);
  HYPRE_StructPCGSetTwoNorm(s.pcg, 1);
  HYPRE_StructPCGSetRelChange(s.pcg, 0);
  HYPRE_StructPFMGCreate(comm, &s.pfmg);
  HYPRE_StructPFMGSetMaxIter(s.pfmg, 1);
  HYPRE_StructPFMGSetTol(s.pfmg, 0.0);
  HYPRE_StructPFMGSetZeroGuess(s.pfmg);
  HYPRE_StructPFMGSetRAPType(s.pfmg, options.rap_type);
  HYPRE_StructPFMGSetRelaxType(s.pfmg, options.relax_type);
  HYPRE_StructPFMGSetNumPreRelax(s.pfmg, options.pre_relax);
  HYPRE_StructPFMGSetNumPostRelax(s.pfmg, options.post_relax);
  HYPRE_StructPFMGSetSkipRelax(s.pfmg, options.skip_relax);
  HYPRE_StructPCGSetPrecond(s.pcg, HYPRE_StructPFMGSolve, HYPRE_StructPFMGSetup, s.pfmg);
}

StructPfmgCG::~StructPfmgCG() {
  Impl& s = *impl_;
  HYPRE_StructPCGDestroy(s.pcg);
  HYPRE_StructPFMGDestroy(s.pfmg);
  HYPRE_StructVectorDestroy(s.b);
  HYPRE_StructVectorDestroy(s.x);
  HYPRE_StructMatrixDestroy(s.A);
  HYPRE_StructStencilDestroy(s.stencil);
  HYPRE_StructGridDestroy(s.grid);
}

HypreSolveResult StructPfmgCG::solve(const double* b, double* x, double relative_tolerance,
                                     int max_iterations) {
  Impl& s = *impl_;
  s.pack(b);
  HYPRE_StructVectorSetBoxValues(s.b, s.lower, s.upper, s.buffer.data());
  HYPRE_StructVectorAssemble(s.b);
  s.pack(x);
  HYPRE_StructVectorSetBoxValues(s.x, s.lower, s.upper, s.buffer.data());
  HYPRE_StructVectorAssemble(s.x);
  HYPRE_StructPCGSetTol(s.pcg, relative_tolerance);
  HYPRE_StructPCGSetMaxIter(s.pcg, max_iterations);
  if (!s.set_up) {
    HYPRE_StructPCGSetup(s.pcg, s.A, s.b, s.x);
    s.set_up = true;
  }
  HYPRE_StructPCGSolve(s.pcg, s.A, s.b, s.x);
  HypreSolveResult r;
  HYPRE_Int its = 0;
  HYPRE_StructPCGGetNumIterations(s.pcg, &its);
  HYPRE_StructPCGGetFinalRelativeResidualNorm(s.pcg, &r.final_relative_residual);
  r.iterations = static_cast<int>(its);
  HYPRE_StructVectorGetBoxValues(s.x, s.lower, s.upper, s.buffer.data());
  s.unpack(x);
  return r;
}

}  // namespace amphora::solvers
