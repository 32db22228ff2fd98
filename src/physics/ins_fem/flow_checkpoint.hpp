#pragma once
// The flow solver's checkpoint block "flow", shared by the modules that own a solver: the
// state, the previous velocity, VANS's void fraction history, the multigrid's smoother state
// and a "history" of {previous dt, steps, then the owner's own entries}. The fields are in the
// whole box's DoF order (gathered from the ranks' slabs), so a checkpoint restarts on any rank
// count; a continuation from it on the same ranks is the uninterrupted run bit for bit.
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <Kokkos_Core.hpp>

#include "base/output_block.hpp"

namespace amphora::physics::ins_fem {

/// The block of `solver` with `extra` appended to its history. Collective: every rank gathers,
/// and every rank gets the block (the module hands it to the writer on one rank).
template <class Solver>
StateBlock flow_state_block(const Solver& solver, const std::vector<double>& extra) {
  constexpr int dim = Solver::dimension;
  const auto& space = solver.distributed_space();
  std::vector<double> history = {solver.previous_dt(), static_cast<double>(solver.steps())};
  history.insert(history.end(), extra.begin(), extra.end());
  StateBlock b{"flow",
               {{"state", space.gather(solver.state(), dim + 1)},
                {"u_old", space.gather(solver.previous_velocity(), dim)}}};
  if (solver.vans()) b.arrays.push_back({"eps", solver.void_fraction_history()});
  b.arrays.push_back({"history", std::move(history)});
  std::vector<double> pc = solver.preconditioner_state();
  if (!pc.empty()) b.arrays.push_back({"preconditioner", std::move(pc)});
  return b;
}

/// Restores `solver` from block b and returns the owner's history entries (at least
/// `extra` of them); `owner` names the module in the one-line refusal of a block that does
/// not fit.
template <int dim, class Solver>
std::vector<double> restore_flow_block(Solver& solver, const StateBlock& b,
                                       const std::string& owner, size_t extra) {
  std::vector<double> state, u_old, eps, history, preconditioner;
  for (const auto& [key, v] : b.arrays)
    (key == "state"            ? state
     : key == "u_old"          ? u_old
     : key == "eps"            ? eps
     : key == "preconditioner" ? preconditioner
                               : history) = v;
  const long n = solver.n_global_dofs(), entries = (dim + 1) * n;
  const auto refuse = [&](const std::string& why) {
    throw std::runtime_error(owner + ": the checkpoint's flow block does not fit this scene (" +
                             why + ")");
  };
  if (b.arrays.empty())
    throw std::runtime_error(owner +
                             ": the checkpoint has no flow block (written by another "
                             "module?)");
  if (static_cast<long>(state.size()) != entries)
    refuse(std::to_string(state.size()) + " state entries, the scene has " +
           std::to_string(entries));
  if (history.size() < 2 + extra)
    refuse(std::to_string(history.size()) + " history entries, this module needs " +
           std::to_string(2 + extra));
  if (solver.vans() && static_cast<long>(eps.size()) != 3 * n + 1)
    refuse(std::to_string(eps.size()) + " void fraction history entries, the scene has " +
           std::to_string(3 * n + 1));
  if (static_cast<long>(u_old.size()) != dim * n)
    refuse(std::to_string(u_old.size()) + " previous velocity entries, the scene has " +
           std::to_string(dim * n));
  const auto& space = solver.distributed_space();
  solver.set_state(space.local_entries(state, dim + 1));
  solver.set_history(space.local_entries(u_old, dim), history[0], static_cast<long>(history[1]));
  if (solver.vans()) solver.set_void_fraction_history(eps);
  solver.set_preconditioner_state(preconditioner);
  return std::vector<double>(history.begin() + 2, history.end());
}

}  // namespace amphora::physics::ins_fem
