#include "solvers/mac/pressure_solver.hpp"

#include <mpi.h>

#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

#include "solvers/hypre_struct_pfmg.hpp"
#include "solvers/mac/mac_multigrid.hpp"
#include "solvers/mac/stencil_csr.hpp"
#include "solvers/hypre_boomeramg.hpp"
#include "solvers/mac/stencil_mic0.hpp"
#include "solvers/mac/tall_cell_matrix.hpp"
#include "solvers/mac/tall_cell_multigrid.hpp"
#include "solvers/modified_incomplete_cholesky.hpp"

namespace amphora::solvers::mac {

PressureBackend parse_pressure_backend(const std::string& name) {
  if (name == "multigrid") return PressureBackend::multigrid;
  if (name == "hypre") return PressureBackend::hypre;
  if (name == "mic0") return PressureBackend::mic0;
  throw std::invalid_argument("unknown pressure solver back end '" + name +
                              "' (allowed: multigrid, hypre, mic0)");
}

const char* to_string(PressureBackend backend) {
  switch (backend) {
    case PressureBackend::multigrid: return "multigrid";
    case PressureBackend::hypre: return "hypre";
    case PressureBackend::mic0: return "mic0";
  }
  return "?";
}

namespace {

/// A hypre result in the terms of CG: hypre reports the relative residual (b: this rank's part
/// of the right-hand side of a system distributed over comm).
template <class B>
SolverResult from_hypre(const HypreSolveResult& h, const B& b, double relative_tolerance,
                        MPI_Comm comm) {
  SolverResult r;
  r.iterations = h.iterations;
  r.converged = h.final_relative_residual <= relative_tolerance;
  double local = 0.0, bb = 0.0;
  for (std::size_t i = 0; i < b.extent(0); ++i) local += b(i) * b(i);
  MPI_Allreduce(&local, &bb, 1, MPI_DOUBLE, MPI_SUM, comm);
  r.rhs_norm = std::sqrt(bb);
  r.final_residual = h.final_relative_residual * r.rhs_norm;
  return r;
}

/// Copies b and x to the host and back around a host solve.
template <class ExecSpace, class HostSolve>
SolverResult solve_on_host(const ExecSpace& exec,
                           const Kokkos::View<double*, typename ExecSpace::memory_space>& b,
                           const Kokkos::View<double*, typename ExecSpace::memory_space>& x,
                           HostSolve&& host_solve) {
  exec.fence();
  const auto bh = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), b);
  const auto xh = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), x);
  const SolverResult r = host_solve(Kokkos::View<double*, kernels::HostMemSpace>(bh),
                                    Kokkos::View<double*, kernels::HostMemSpace>(xh));
  Kokkos::deep_copy(x, xh);
  return r;
}

/// Multigrid-preconditioned CG of either grid: Multigrid is MacMultigrid or TallCellMultigrid.
template <class ExecSpace, class Multigrid>
class MultigridPressureSolver final : public PressureSolver<ExecSpace> {
 public:
  using typename PressureSolver<ExecSpace>::Vector;
  template <class... Args>
  explicit MultigridPressureSolver(const ExecSpace& exec, Args&&... args)
      : mg_(exec, std::forward<Args>(args)...) {}
  SolverResult solve(const ExecSpace& exec, const Vector& b, const Vector& x,
                     const SolverControl& c) override {
    return mg_.solve(exec, b, x, c);
  }
  PressureBackend backend() const override { return PressureBackend::multigrid; }
  double bytes_per_iteration() const override {
    if constexpr (std::is_same_v<Multigrid, MacMultigrid<ExecSpace>>)
      return mg_.bytes_per_cg_iteration();
    else
      return 0.0;
  }

 private:
  Multigrid mg_;
};

template <class ExecSpace>
class PfmgPressureSolver final : public PressureSolver<ExecSpace> {
 public:
  using typename PressureSolver<ExecSpace>::Vector;
  PfmgPressureSolver(const kernels::mac::PoissonStencil<typename ExecSpace::memory_space>& A,
                     const MacBlock& block) {
    const auto d = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), A.diag);
    const auto x = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), A.cx);
    const auto y = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), A.cy);
    const auto z = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), A.cz);
    comm_ = block.comm;
    pfmg_ = std::make_unique<StructPfmgCG>(block.comm, A.grid, block.global_lower, d.data(),
                                           x.data(), y.data(), z.data());
  }
  SolverResult solve(const ExecSpace& exec, const Vector& b, const Vector& x,
                     const SolverControl& c) override {
    return solve_on_host(exec, b, x, [&](const auto& bh, const auto& xh) {
      return from_hypre(pfmg_->solve(bh.data(), xh.data(), c.relative_tolerance, c.max_iterations),
                        bh, c.relative_tolerance, comm_);
    });
  }
  PressureBackend backend() const override { return PressureBackend::hypre; }

 private:
  std::unique_ptr<StructPfmgCG> pfmg_;
  MPI_Comm comm_ = MPI_COMM_SELF;
};

/// CG with MIC(0) on the stencil, host, sequential.
template <class ExecSpace>
class Mic0PressureSolver final : public PressureSolver<ExecSpace> {
 public:
  using typename PressureSolver<ExecSpace>::Vector;
  using HostVector = Kokkos::View<double*, kernels::HostMemSpace>;
#if defined(KOKKOS_ENABLE_SERIAL)
  using SequentialSpace = Kokkos::Serial;
#else
  using SequentialSpace = kernels::HostExecSpace;
#endif
  using HostStencil = kernels::mac::PoissonStencil<kernels::HostMemSpace>;

  explicit Mic0PressureSolver(
      const kernels::mac::PoissonStencil<typename ExecSpace::memory_space>& A)
      : A_(kernels::mac::copy_stencil<kernels::HostMemSpace>(A)), mic_(A_) {}
  SolverResult solve(const ExecSpace& exec, const Vector& b, const Vector& x,
                     const SolverControl& c) override {
    return solve_on_host(exec, b, x, [&](const auto& bh, const auto& xh) {
      return conjugate_gradient(SequentialSpace(), Operator{A_}, bh, xh, c, mic_);
    });
  }
  PressureBackend backend() const override { return PressureBackend::mic0; }

 private:
  struct Operator {
    HostStencil A;
    void apply(const SequentialSpace& exec, const HostVector& x, const HostVector& y) const {
      kernels::mac::apply(exec, A, x, y);
    }
  };
  HostStencil A_;
  StencilMic0 mic_;
};

template <class ExecSpace>
class BoomerAMGPressureSolver final : public PressureSolver<ExecSpace> {
 public:
  using typename PressureSolver<ExecSpace>::Vector;
  /// Rows first_row.. of A_t, distributed over comm (one rank: MPI_COMM_SELF, 0).
  BoomerAMGPressureSolver(CsrMatrix A_t, MPI_Comm comm, long first_row)
      : A_(std::move(A_t)), comm_(comm), first_row_(first_row) {}
  SolverResult solve(const ExecSpace& exec, const Vector& b, const Vector& x,
                     const SolverControl& c) override {
    return solve_on_host(exec, b, x, [&](const auto& bh, const auto& xh) {
      const BoomerAMG amg(comm_, first_row_, A_);
      return from_hypre(amg.pcg(bh.data(), xh.data(), c.relative_tolerance, c.max_iterations), bh,
                        c.relative_tolerance, comm_);
    });
  }
  PressureBackend backend() const override { return PressureBackend::hypre; }

 private:
  CsrMatrix A_;
  MPI_Comm comm_;
  long first_row_;
};

template <class ExecSpace>
class CsrMic0PressureSolver final : public PressureSolver<ExecSpace> {
 public:
  using typename PressureSolver<ExecSpace>::Vector;
#if defined(KOKKOS_ENABLE_SERIAL)
  using SequentialSpace = Kokkos::Serial;
#else
  using SequentialSpace = kernels::HostExecSpace;
#endif
  // No modification (tau = 0): P^T A P is not an M-matrix (the linear weights couple a tall
  // cell's samples to its neighbours' with positive entries), and the row-sum compensation of
  // MIC then hurts (an order of magnitude more CG iterations on tall cells).
  explicit CsrMic0PressureSolver(CsrMatrix A_t) : A_(std::move(A_t)), mic_(A_, 0.0) {}
  SolverResult solve(const ExecSpace& exec, const Vector& b, const Vector& x,
                     const SolverControl& c) override {
    return solve_on_host(exec, b, x, [&](const auto& bh, const auto& xh) {
      return conjugate_gradient(SequentialSpace(), CsrOperator{&A_}, bh, xh, c, mic_);
    });
  }
  PressureBackend backend() const override { return PressureBackend::mic0; }

 private:
  CsrMatrix A_;
  ModifiedIncompleteCholesky mic_;
};

}  // namespace

template <class ExecSpace>
std::unique_ptr<PressureSolver<ExecSpace>> make_tall_cell_pressure_solver(
    PressureBackend backend, const ExecSpace& exec, const mesh::mac::TallCellGrid& T,
    const kernels::mac::PoissonStencil<typename ExecSpace::memory_space>& A,
    KeptCoarseStencils<typename ExecSpace::memory_space>* kept) {
  if (T.block().split() && backend == PressureBackend::mic0)
    throw std::invalid_argument(
        std::string("pressure back end '") + to_string(backend) +
        "' solves tall cells on one rank; for tall cells split over ranks use 'multigrid' "
        "or 'hypre'");
  switch (backend) {
    case PressureBackend::multigrid:
      return std::make_unique<MultigridPressureSolver<ExecSpace, TallCellMultigrid<ExecSpace>>>(
          exec, T, A, TallCellMultigridOptions{}, kept);
    case PressureBackend::hypre:
      return std::make_unique<BoomerAMGPressureSolver<ExecSpace>>(
          assemble_tall_cell_matrix(T, kernels::mac::host_stencil(A)), T.block().comm,
          T.first_unknown());
    case PressureBackend::mic0:
      return std::make_unique<CsrMic0PressureSolver<ExecSpace>>(
          assemble_tall_cell_matrix(T, kernels::mac::host_stencil(A)));
  }
  throw std::invalid_argument("make_tall_cell_pressure_solver: unknown back end");
}

template <class ExecSpace>
std::unique_ptr<PressureSolver<ExecSpace>> make_pressure_solver(
    PressureBackend backend, const ExecSpace& exec,
    const kernels::mac::PoissonStencil<typename ExecSpace::memory_space>& A,
    const MacBlock& block) {
  bool split = false;
  for (const auto f : A.box) split = split || f == kernels::mac::MacBoundary::neighbour;
  if (split && backend == PressureBackend::mic0)
    throw std::invalid_argument(
        std::string("pressure back end '") + to_string(backend) +
        "' solves a grid on one rank; for a grid split over ranks use 'multigrid' or 'hypre'");
  if (split != block.split())
    throw std::invalid_argument(
        "make_pressure_solver: the stencil's neighbour faces and the block's neighbours differ");
  switch (backend) {
    case PressureBackend::multigrid:
      return std::make_unique<MultigridPressureSolver<ExecSpace, MacMultigrid<ExecSpace>>>(
          exec, A, MacMultigridOptions{}, block);
    case PressureBackend::hypre: return std::make_unique<PfmgPressureSolver<ExecSpace>>(A, block);
    case PressureBackend::mic0: return std::make_unique<Mic0PressureSolver<ExecSpace>>(A);
  }
  throw std::invalid_argument("make_pressure_solver: unknown back end");
}

template std::unique_ptr<PressureSolver<kernels::DefaultExecSpace>> make_pressure_solver(
    PressureBackend, const kernels::DefaultExecSpace&,
    const kernels::mac::PoissonStencil<kernels::DefaultMemSpace>&, const MacBlock&);
template std::unique_ptr<PressureSolver<kernels::DefaultExecSpace>> make_tall_cell_pressure_solver(
    PressureBackend, const kernels::DefaultExecSpace&, const mesh::mac::TallCellGrid&,
    const kernels::mac::PoissonStencil<kernels::DefaultMemSpace>&,
    KeptCoarseStencils<kernels::DefaultMemSpace>*);
#if defined(KOKKOS_ENABLE_SERIAL) && defined(KOKKOS_ENABLE_OPENMP)
template std::unique_ptr<PressureSolver<Kokkos::Serial>> make_pressure_solver(
    PressureBackend, const Kokkos::Serial&, const kernels::mac::PoissonStencil<Kokkos::HostSpace>&,
    const MacBlock&);
template std::unique_ptr<PressureSolver<Kokkos::Serial>> make_tall_cell_pressure_solver(
    PressureBackend, const Kokkos::Serial&, const mesh::mac::TallCellGrid&,
    const kernels::mac::PoissonStencil<Kokkos::HostSpace>&, KeptCoarseStencils<Kokkos::HostSpace>*);
#endif

}  // namespace amphora::solvers::mac
