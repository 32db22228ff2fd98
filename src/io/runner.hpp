#pragma once
// The run driver: builds the scene's module, steps it to the end time, writes field output,
// diagnostics, progress and checkpoints, and continues from a checkpoint bit for bit.
#include <stdexcept>
#include <string>

#include "io/scene.hpp"
#include "kernels/deep_copy_counter.hpp"
#include "base/communicator.hpp"
#include "physics/module.hpp"

namespace amphora::io {

/// Bad input discovered when setting up a run (output directory, restart file, ranks).
class RunError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct RunOptions {
  std::string restart;       ///< checkpoint to continue from ("" for a fresh run)
  long long max_steps = -1;  ///< stop (with a checkpoint) after this many steps of this run
  bool write_output = true;  ///< fields, series, diagnostics and checkpoints
  bool quiet = false;        ///< no progress lines
  /// CSV of every kernel of the stepping loop, timed (kernels/kernel_profile.hpp; "" for none);
  /// rank r > 0 of several writes FILE.rank<r>.
  std::string kernel_profile;
};

struct RunResult {
  bool diverged = false;
  std::string message;  ///< why a diverged run stopped
  long long steps = 0;  ///< steps taken by this run
  long long final_step = 0;
  double time = 0.0;
  double dt = 0.0;
  double wall_seconds = 0.0;  ///< stepping only (set-up and output excluded)
  double rate = 0.0;          ///< work units per second while stepping
  long long work_per_step = 0;
  std::string work_unit;
  Diagnostics diagnostics;        ///< at the final step
  Diagnostics phase_seconds;      ///< Module::phase_seconds of this run, the largest over the ranks
  double error = 0.0;             ///< the module's error diagnostic at the final step
  kernels::DeepCopyCount copies;  ///< Kokkos deep copies made while stepping (this rank's)
};

/// Collective. Throws RunError (bad set-up input), DecompositionError (more ranks than
/// blocks) or std::invalid_argument (parameters the module rejects) before writing anything.
RunResult run_scene(const Scene& scene, const Communicator& comm, const RunOptions& options);

/// Constructs the scene's module without stepping it (what `amphora check` validates).
void check_scene(const Scene& scene, const Communicator& comm);

}  // namespace amphora::io
