#pragma once
// Where a flow step failed, for the runner's one-line report: the state entry's field and DoF
// point, and the free velocity entry of largest magnitude (where a failed solve or a step over
// the CFL limit left the flow wildest).
#include <cmath>
#include <string>
#include <vector>

#include <Kokkos_Core.hpp>

#include "physics/module.hpp"

namespace amphora::physics::ins_fem {

/// The field and the DoF point of state entry i (velocity components first, then pressure).
template <int dim, class Solver>
NonFiniteReport flow_report_at(const Solver& solver, long i, const std::string& reason) {
  const long n = solver.n_dofs();
  NonFiniteReport r;
  r.field = i / n < dim ? "velocity" : "pressure";
  r.block = "flow";
  r.index = i % n;
  const std::vector<double> p = solver.space().dof_points();
  for (int d = 0; d < dim; ++d) r.point.push_back(p[d * n + r.index]);
  r.reason = reason;
  return r;
}

/// The state entry of the free velocity component of largest magnitude (Dirichlet values are
/// the data, not the failure). A host copy: called once, when a run stops.
template <int dim, class Solver>
long largest_free_velocity(const Solver& solver) {
  const auto u = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), solver.state());
  const auto cons =
      Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), solver.space().constrained_dofs());
  const long n = solver.n_dofs();
  std::vector<char> fixed(n, 0);
  for (size_t i = 0; i < cons.extent(0); ++i) fixed[cons(i)] = 1;
  long at = 0;
  double largest = -1.0;
  for (long i = 0; i < dim * n; ++i)
    if (!fixed[i % n] && !(std::abs(u(i)) <= largest)) largest = std::abs(u(i)), at = i;
  return at;
}

}  // namespace amphora::physics::ins_fem
