#pragma once
// The interface every physics module offers the run driver: it owns its state, advances it,
// knows its stable step, says what it writes out and which diagnostics it reports, and can
// save and restore its state for a bit-for-bit restart. Host-side interface only: the work
// happens in the kernels each module launches.
#include <optional>
#include <string>
#include <vector>

#include "base/output_block.hpp"

namespace amphora::physics {

/// Where a run first went non-finite (or, with `reason`, where a module saw it fail otherwise,
/// e.g. unbounded growth).
struct NonFiniteReport {
  std::string field;
  std::string block;
  long long index = -1;
  double x = 0.0;
  std::vector<double> point;  ///< the place in 2D/3D; empty: `x` alone names it
  std::string reason;         ///< empty: "non-finite value"
};

class Module {
 public:
  virtual ~Module() = default;
  virtual std::string name() const = 0;
  /// Largest stable time step for the current state [s].
  virtual double stable_dt() const = 0;
  /// The step the run will use, before the first advance; a module may refuse it
  /// (std::invalid_argument naming its limit).
  virtual void set_time_step(double /*dt*/) {}
  /// Advances the state from time t to t + dt. Collective.
  virtual void advance(double t, double dt) = 0;
  /// Global amount of work in one step and its unit, for throughput ("point-steps/s").
  virtual long long work_per_step() const = 0;
  virtual std::string work_unit() const = 0;
  /// This rank's output blocks at time t.
  virtual std::vector<OutputBlock> output(double t) const = 0;
  /// Global diagnostics at time t (same values on every rank). Collective.
  virtual Diagnostics diagnostics(double t) const = 0;
  /// Name of the diagnostic that measures the error against the reference, for studies.
  virtual std::string error_diagnostic() const = 0;
  /// The first non-finite state value, on every rank, or nothing. Collective.
  virtual std::optional<NonFiniteReport> find_nonfinite() const = 0;
  /// This rank's state blocks, and their restoration (blocks this rank owns, by name).
  virtual std::vector<StateBlock> state() const = 0;
  virtual void restore(const std::vector<StateBlock>& blocks) = 0;
  virtual std::vector<std::string> owned_blocks() const = 0;
  /// Wall seconds this rank has spent in each phase of advance() so far, in the module's order
  /// of its phases (empty: the module does not time them). For the run's closing [timing] lines
  /// and the studies that chart where a step's time goes; never part of the diagnostics, which
  /// must not depend on the machine.
  virtual Diagnostics phase_seconds() const { return {}; }
};

}  // namespace amphora::physics
