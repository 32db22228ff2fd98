#include "solvers/hypre_boomeramg.hpp"

#include <mpi.h>

#include <HYPRE.h>
#include <HYPRE_krylov.h>
#include <HYPRE_parcsr_ls.h>

#include <stdexcept>
#include <vector>

namespace amphora::solvers {

struct BoomerAMG::Impl {
  BoomerAMGOptions options;
  HYPRE_IJMatrix ij = nullptr;
  HYPRE_ParCSRMatrix A = nullptr;
  HYPRE_IJVector bij = nullptr, xij = nullptr;
  HYPRE_ParVector b = nullptr, x = nullptr;
  HYPRE_Solver amg = nullptr;
  MPI_Comm comm = MPI_COMM_SELF;
  HYPRE_BigInt n = 0;
  std::vector<HYPRE_BigInt> index;
  std::vector<double> zero;  // n zeros: the initial guess of a V-cycle

  static void configure(HYPRE_Solver s, const BoomerAMGOptions& o) {
    HYPRE_BoomerAMGSetPrintLevel(s, 0);
    HYPRE_BoomerAMGSetStrongThreshold(s, o.strong_threshold);
    HYPRE_BoomerAMGSetAggNumLevels(s, o.aggressive_levels);
    HYPRE_BoomerAMGSetCoarsenType(s, o.coarsen_type);
    HYPRE_BoomerAMGSetInterpType(s, o.interp_type);
    HYPRE_BoomerAMGSetRelaxType(s, o.relax_type);
    HYPRE_BoomerAMGSetPMaxElmts(s, o.p_max);
    HYPRE_BoomerAMGSetMaxIter(s, 1);
    HYPRE_BoomerAMGSetTol(s, 0.0);
  }

  void set_vectors(const double* bv, const double* xv) const {
    HYPRE_IJVectorInitialize(bij);
    HYPRE_IJVectorSetValues(bij, static_cast<HYPRE_Int>(n), index.data(), bv);
    HYPRE_IJVectorAssemble(bij);
    HYPRE_IJVectorInitialize(xij);
    HYPRE_IJVectorSetValues(xij, static_cast<HYPRE_Int>(n), index.data(), xv);
    HYPRE_IJVectorAssemble(xij);
  }
};

namespace {
void ensure_hypre_initialised() {
  static const bool done = [] {
    HYPRE_Init();
    return true;
  }();
  (void)done;
}
}  // namespace

BoomerAMG::BoomerAMG(const CsrMatrix& M, const BoomerAMGOptions& options)
    : BoomerAMG(MPI_COMM_SELF, 0, M, options) {}

BoomerAMG::BoomerAMG(MPI_Comm comm, long first_row, const CsrMatrix& M,
                     const BoomerAMGOptions& options)
    : impl_(std::make_unique<Impl>()) {
  ensure_hypre_initialised();
  auto& s = *impl_;
  s.options = options;
  s.comm = comm;
  s.n = static_cast<HYPRE_BigInt>(M.n);
  long total = M.n;
  MPI_Allreduce(&M.n, &total, 1, MPI_LONG, MPI_SUM, comm);
  if (total <= 0) throw std::invalid_argument("BoomerAMG: empty matrix");
  const HYPRE_BigInt lo = static_cast<HYPRE_BigInt>(first_row), hi = lo + s.n - 1;
  HYPRE_IJMatrixCreate(comm, lo, hi, lo, hi, &s.ij);
  HYPRE_IJMatrixSetObjectType(s.ij, HYPRE_PARCSR);
  std::vector<HYPRE_Int> row_sizes(M.n);
  for (long i = 0; i < M.n; ++i)
    row_sizes[i] = static_cast<HYPRE_Int>(M.row_ptr[i + 1] - M.row_ptr[i]);
  HYPRE_IJMatrixSetRowSizes(s.ij, row_sizes.data());
  HYPRE_IJMatrixInitialize(s.ij);
  s.index.resize(M.n);
  for (long i = 0; i < M.n; ++i) s.index[i] = lo + static_cast<HYPRE_BigInt>(i);
  std::vector<HYPRE_BigInt> cols(M.cols.begin(), M.cols.end());
  HYPRE_IJMatrixSetValues(s.ij, static_cast<HYPRE_Int>(M.n), row_sizes.data(), s.index.data(),
                          cols.data(), M.values.data());
  HYPRE_IJMatrixAssemble(s.ij);
  HYPRE_IJMatrixGetObject(s.ij, reinterpret_cast<void**>(&s.A));
  HYPRE_IJVectorCreate(comm, lo, hi, &s.bij);
  HYPRE_IJVectorSetObjectType(s.bij, HYPRE_PARCSR);
  HYPRE_IJVectorCreate(comm, lo, hi, &s.xij);
  HYPRE_IJVectorSetObjectType(s.xij, HYPRE_PARCSR);
  s.zero.assign(M.n, 0.0);
  s.set_vectors(s.zero.data(), s.zero.data());
  HYPRE_IJVectorGetObject(s.bij, reinterpret_cast<void**>(&s.b));
  HYPRE_IJVectorGetObject(s.xij, reinterpret_cast<void**>(&s.x));
}

BoomerAMG::~BoomerAMG() {
  auto& s = *impl_;
  if (s.amg) HYPRE_BoomerAMGDestroy(s.amg);
  if (s.bij) HYPRE_IJVectorDestroy(s.bij);
  if (s.xij) HYPRE_IJVectorDestroy(s.xij);
  if (s.ij) HYPRE_IJMatrixDestroy(s.ij);
}

void BoomerAMG::vcycle(const double* b, double* x) const {
  auto& s = *impl_;
  s.set_vectors(b, s.zero.data());
  if (!s.amg) {  // set up on first use
    HYPRE_BoomerAMGCreate(&s.amg);
    Impl::configure(s.amg, s.options);
    HYPRE_BoomerAMGSetup(s.amg, s.A, s.b, s.x);
  }
  HYPRE_BoomerAMGSolve(s.amg, s.A, s.b, s.x);
  HYPRE_IJVectorGetValues(s.xij, static_cast<HYPRE_Int>(s.n), s.index.data(), x);
}

HypreSolveResult BoomerAMG::pcg(const double* b, double* x, double relative_tolerance,
                                int max_iterations) const {
  auto& s = *impl_;
  s.set_vectors(b, x);
  HYPRE_Solver pcg = nullptr, amg = nullptr;
  HYPRE_ParCSRPCGCreate(s.comm, &pcg);
  HYPRE_PCGSetTol(pcg, relative_tolerance);
  HYPRE_PCGSetMaxIter(pcg, max_iterations);
  HYPRE_PCGSetTwoNorm(pcg, 1);
  HYPRE_PCGSetPrintLevel(pcg, 0);
  HYPRE_BoomerAMGCreate(&amg);
  Impl::configure(amg, s.options);
  HYPRE_PCGSetPrecond(pcg, reinterpret_cast<HYPRE_PtrToSolverFcn>(HYPRE_BoomerAMGSolve),
                      reinterpret_cast<HYPRE_PtrToSolverFcn>(HYPRE_BoomerAMGSetup), amg);
  HYPRE_ParCSRPCGSetup(pcg, s.A, s.b, s.x);
  HYPRE_ParCSRPCGSolve(pcg, s.A, s.b, s.x);
  HypreSolveResult r;
  HYPRE_Int it = 0;
  HYPRE_PCGGetNumIterations(pcg, &it);
  r.iterations = it;
  HYPRE_PCGGetFinalRelativeResidualNorm(pcg, &r.final_relative_residual);
  HYPRE_IJVectorGetValues(s.xij, static_cast<HYPRE_Int>(s.n), s.index.data(), x);
  HYPRE_BoomerAMGDestroy(amg);
  HYPRE_ParCSRPCGDestroy(pcg);
  return r;
}

HypreSolveResult BoomerAMG::gmres(const double* b, double* x, double relative_tolerance,
                                  int max_iterations, int restart) const {
  auto& s = *impl_;
  s.set_vectors(b, x);
  HYPRE_Solver gmres = nullptr, amg = nullptr;
  HYPRE_ParCSRGMRESCreate(s.comm, &gmres);
  HYPRE_GMRESSetTol(gmres, relative_tolerance);
  HYPRE_GMRESSetMaxIter(gmres, max_iterations);
  HYPRE_GMRESSetKDim(gmres, restart);
  HYPRE_GMRESSetPrintLevel(gmres, 0);
  HYPRE_BoomerAMGCreate(&amg);
  Impl::configure(amg, s.options);
  HYPRE_GMRESSetPrecond(gmres, reinterpret_cast<HYPRE_PtrToSolverFcn>(HYPRE_BoomerAMGSolve),
                        reinterpret_cast<HYPRE_PtrToSolverFcn>(HYPRE_BoomerAMGSetup), amg);
  HYPRE_ParCSRGMRESSetup(gmres, s.A, s.b, s.x);
  HYPRE_ParCSRGMRESSolve(gmres, s.A, s.b, s.x);
  HypreSolveResult r;
  HYPRE_Int it = 0;
  HYPRE_GMRESGetNumIterations(gmres, &it);
  r.iterations = it;
  HYPRE_GMRESGetFinalRelativeResidualNorm(gmres, &r.final_relative_residual);
  HYPRE_IJVectorGetValues(s.xij, static_cast<HYPRE_Int>(s.n), s.index.data(), x);
  HYPRE_BoomerAMGDestroy(amg);
  HYPRE_ParCSRGMRESDestroy(gmres);
  return r;
}

}  // namespace amphora::solvers
