#pragma once
// The operator GMRES applies in a flow step and its timed wrapper (InsSolver, ins_solver.hpp).
#include "physics/ins_fem/ins_options.hpp"
#include "physics/phase_times.hpp"

namespace amphora::physics::ins_fem {

/// An operator or preconditioner whose applications are booked to a phase (the time before
/// each, since the last lap, to ins_other).
template <class Op>
struct TimedApply {
  const Op* op;
  PhaseTimes* times;
  int phase;
  template <class E, class X, class Y>
  void apply(const E& exec, const X& x, const Y& y) const {
    if (times) times->lap(ins_other);
    op->apply(exec, x, y);
    if (times) times->lap(phase);
  }
};

/// An operator plus the backflow term of the open faces (nullptr: the operator alone) on the
/// slabs of a DistributedQkSpace: x's ghost layer from its owners, then both terms on this
/// rank's cells and faces, then the shared layer's partial sums added.
template <class Space, class Op, class Backflow>
struct WithBackflow {
  const Space* space;
  const Op* op;
  const Backflow* backflow;
  template <class E, class X, class Y>
  void apply(const E& exec, const X& x, const Y& y) const {
    const int nc = op->options().components;
    space->update_ghosts(exec, x, nc);
    op->apply(exec, x, y);
    if (backflow) backflow->apply_add(exec, x, y);
    space->compress_add(exec, y, nc, op->constrained_components());
  }
};

}  // namespace amphora::physics::ins_fem
