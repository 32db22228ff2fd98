#include "solvers/mac/lattice_pressure.hpp"

#include "kernels/mac/tall_cell_transfer.hpp"
#include "mesh/mac/tall_cell_grid.hpp"

namespace amphora::solvers::mac {

template <class ExecSpace>
LatticePressure<ExecSpace>::LatticePressure(const ExecSpace& exec, PressureBackend backend,
                                            int optical_depth, const Stencil& A,
                                            const mesh::mac::MacBlock& block, const Vector& b,
                                            const Vector& p, KeptCoarseStencils<Mem>* kept)
    : b_(b), p_(p) {
  if (optical_depth == 0) {
    solver_ = make_pressure_solver(backend, exec, A, block);
    return;
  }
  Kokkos::Profiling::pushRegion("amphora::water::tall_cell_grid");
  const mesh::mac::TallCellGrid T(exec, A, optical_depth, block);
  Kokkos::Profiling::popRegion();
  layout_ = T.layout<Mem>();
  bt_ = Vector("amphora::water::b_tall", T.unknowns());
  y_ = Vector("amphora::water::p_tall", T.unknowns());
  kernels::mac::tall_cell_restrict(exec, *layout_, b_, bt_);
  kernels::mac::tall_cell_restrict(exec, *layout_, p_, y_);
  kernels::mac::tall_cell_gram_solve(exec, *layout_, y_);
  Kokkos::Profiling::pushRegion("amphora::water::tall_cell_solver_setup");
  solver_ = make_tall_cell_pressure_solver(backend, exec, T, A, kept);
  Kokkos::Profiling::popRegion();
  global_unknowns_ = T.global_unknowns();
}

template <class ExecSpace>
SolverResult LatticePressure<ExecSpace>::solve(const ExecSpace& exec,
                                               const SolverControl& control) {
  if (!layout_) return solver_->solve(exec, b_, p_, control);
  const SolverResult r = solver_->solve(exec, bt_, y_, control);
  kernels::mac::tall_cell_prolongate(exec, *layout_, y_, p_);
  return r;
}

template class LatticePressure<kernels::DefaultExecSpace>;
#if defined(KOKKOS_ENABLE_SERIAL) && defined(KOKKOS_ENABLE_OPENMP)
template class LatticePressure<Kokkos::Serial>;
#endif

}  // namespace amphora::solvers::mac
