#pragma once
// The flow solver's checkpoint block "flow", shared by the modules that own a solver: the
// state, the previous velocity, VANS's void fraction history, the multigrid's smoother state
// and a "history" of {previous dt, steps, then the owner's own entries}. A continuation from
// it is the uninterrupted run bit for bit.
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <Kokkos_Core.hpp>

#include "base/output_block.hpp"

namespace amphora::physics::ins_fem {

/// The block of `solver` with `extra` appended to its history.
template <class Solver>
StateBlock flow_state_block(const Solver& solver, const std::vector<double>& extra) {
  const auto sh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), solver.state());
  const auto oh =
      Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), solver.previous_velocity());
  std::vector<double> history = {solver.previous_dt(), static_cast<double>(solver.steps())};
  history.insert(history.end(), extra.begin(), extra.end());
  StateBlock b{"flow",
               {{"state", std::vector<double>(sh.data(), sh.data() + sh.extent(0))},
                {"u_old", std::vector<double>(oh.data(), oh.data() + oh.extent(0))}}};
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
  const long n = solver.n_dofs(), entries = (dim + 1) * n;
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
  solver.set_state(state);
  solver.set_history(u_old, history[0], static_cast<long>(history[1]));
  if (solver.vans()) solver.set_void_fraction_history(eps);
  solver.set_preconditioner_state(preconditioner);
  return std::vector<double>(history.begin() + 2, history.end());
}

}  // namespace amphora::physics::ins_fem
