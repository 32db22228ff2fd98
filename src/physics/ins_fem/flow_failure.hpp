#pragma once
// Where a flow step failed, for the runner's one-line report: the state entry's field and DoF
// point, and the free velocity entry of largest magnitude (where a failed solve or a step over
// the CFL limit left the flow wildest), on one rank or collectively over the ranks of a slab
// decomposition.
#include <cmath>
#include <string>
#include <vector>

#include <optional>

#include <Kokkos_Core.hpp>

#include "base/communicator.hpp"
#include "kernels/reductions.hpp"
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
/// the data, not the failure), and that magnitude. A host copy: called once, when a run stops.
template <int dim, class Solver>
long largest_free_velocity(const Solver& solver, double* magnitude = nullptr) {
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
  if (magnitude) *magnitude = largest;
  return at;
}

/// rank `owner`'s report r (its field, index and point) on every rank, the block named as the
/// rank's output block ("flow_<owner>") on several ranks; the reason is each rank's own.
/// Collective.
template <int dim, class Solver>
NonFiniteReport flow_report_from(const Solver& solver, NonFiniteReport r, int owner) {
  const Communicator& comm = solver.distributed_space().communicator();
  const char* fields[3] = {"velocity", "pressure", "eps"};
  double packed[5] = {0.0, static_cast<double>(r.index), 0, 0, 0};
  for (int f = 0; f < 3; ++f)
    if (r.field == fields[f]) packed[0] = f;
  for (int d = 0; d < dim; ++d) packed[2 + d] = r.point[d];
  MPI_Bcast(packed, 5, MPI_DOUBLE, owner, comm.get());
  r.field = fields[static_cast<int>(packed[0])];
  r.index = static_cast<long long>(packed[1]);
  for (int d = 0; d < dim; ++d) r.point[d] = packed[2 + d];
  if (comm.size() > 1) r.block = "flow_" + std::to_string(owner);
  return r;
}

/// Where the flow failed, the same report on every rank (collective): the first non-finite
/// state entry of the lowest rank that holds one; else, where `failure` (a failed solve, the
/// same on every rank) is not empty, the largest free velocity over the ranks; else none. On
/// several ranks the block is the rank's output block, "flow_<rank>", and the index its own.
template <int dim, class Solver>
std::optional<NonFiniteReport> find_flow_failure(const Solver& solver, const std::string& failure) {
  const Communicator& comm = solver.distributed_space().communicator();
  const long bad =
      kernels::reduce::first_nonfinite(typename Solver::Vector::execution_space(), solver.state());
  const bool nonfinite = comm.any(bad >= 0);
  if (!nonfinite && failure.empty()) return std::nullopt;
  double score = bad >= 0 ? 1.0 : 0.0;
  const long at = nonfinite ? bad : largest_free_velocity<dim>(solver, &score);
  const double best = comm.max(score);
  const int owner = static_cast<int>(comm.min(score == best ? comm.rank() : comm.size()));
  return flow_report_from<dim>(
      solver, flow_report_at<dim>(solver, at < 0 ? 0 : at, nonfinite ? std::string() : failure),
      owner);
}

}  // namespace amphora::physics::ins_fem
