#include "io/runner.hpp"

#include <Kokkos_Core.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>

#include "io/diagnostics_csv.hpp"
#include "io/field_series.hpp"
#include "io/hdf5_file.hpp"
#include "io/progress.hpp"
#include "io/module_registry.hpp"
#include "kernels/kernel_profile.hpp"

namespace amphora::io {

namespace {

namespace fs = std::filesystem;

std::unique_ptr<physics::Module> make_module(const Scene& scene, const Communicator& comm) {
  return find_module(scene.module)->create(scene.module_parameters, comm);
}

/// Creates the output directory and proves it writable, on rank 0; every rank learns the result.
void prepare_output_dir(const std::string& dir, const Communicator& comm) {
  std::string error;
  if (comm.is_root()) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) {
      error = "output directory '" + dir + "' cannot be created: " + ec.message();
    } else {
      const std::string probe = dir + "/.amphora_write_probe";
      std::ofstream out(probe);
      out << "probe";
      out.close();
      if (!out) error = "output directory '" + dir + "' is not writable";
      fs::remove(probe, ec);
    }
  }
  error = comm.broadcast(error);
  if (!error.empty()) throw RunError(error);
}

std::string fmt(double x) {
  std::ostringstream s;
  s.precision(6);
  s << x;
  return s.str();
}

/// "x = 0.5", or "(x, y, z) = (0.1, 0.2, 0.3)" where the module gave a point.
std::string place(const physics::NonFiniteReport& r) {
  if (r.point.empty()) return "x = " + fmt(r.x);
  static const char* names[] = {"x", "y", "z"};
  std::string n, v;
  for (size_t d = 0; d < r.point.size() && d < 3; ++d) {
    n += (d ? ", " : "") + std::string(names[d]);
    v += (d ? ", " : "") + fmt(r.point[d]);
  }
  return "(" + n + ") = (" + v + ")";
}

/// The next step of an adaptive run: cfl times the module's stable step in its current state,
/// at most 20 % over the last step (variable-step BDF2 stays zero-stable for ratios below
/// 1 + sqrt 2), shortened to land on end_time (the rest halved rather than a sliver left).
double adaptive_dt(const physics::Module& module, double cfl, double last_dt, double remaining) {
  const double dt = std::min(cfl * module.stable_dt(), 1.2 * last_dt);
  if (remaining <= dt * (1.0 + 1e-9)) return remaining;
  return remaining < 2.0 * dt ? 0.5 * remaining : dt;
}

struct Checkpoint {
  long long step;
  double time, dt;
  long long n_steps;
};

void write_checkpoint(const std::string& dir, const Scene& scene, const Communicator& comm,
                      const physics::Module& module, const FieldSeries& series,
                      const Checkpoint& c) {
  std::vector<H5Group> groups;
  for (auto& b : module.state()) groups.push_back({b.name, std::move(b.arrays)});
  H5Metadata meta;
  meta.integers["step"] = c.step;
  meta.integers["n_steps"] = c.n_steps;
  meta.reals["time"] = c.time;
  meta.reals["dt"] = c.dt;
  meta.texts["fingerprint"] = scene.fingerprint;
  meta.texts["scene"] = scene.name;
  meta.texts["series"] = series.save();
  const std::string path = dir + "/checkpoint.h5";
  // Written whole under a temporary name, then renamed: a run killed mid-write leaves the
  // previous checkpoint intact.
  write_h5(path + ".tmp", comm, groups, meta);
  if (comm.is_root() && std::rename((path + ".tmp").c_str(), path.c_str()) != 0)
    throw std::runtime_error("cannot rename checkpoint to '" + path + "'");
  comm.barrier();
}

/// The checkpoint a run continues from (nullptr: none asked), checked to be an amphora
/// checkpoint of this scene.
std::unique_ptr<H5Reader> open_restart(const std::string& file, const Scene& scene,
                                       const Communicator& comm) {
  if (file.empty()) return nullptr;
  if (!fs::exists(file)) throw RunError("restart file '" + file + "' not found");
  std::unique_ptr<H5Reader> restart;
  try {
    restart = std::make_unique<H5Reader>(file, comm);
  } catch (const std::exception& e) {
    throw RunError("restart file '" + file + "' is not an amphora checkpoint (" + e.what() + ")");
  }
  if (!restart->has("fingerprint") || !restart->has("scene"))
    throw RunError("restart file '" + file + "' is not an amphora checkpoint");
  const std::string fp = restart->text("fingerprint");
  if (fp != scene.fingerprint) {
    throw RunError("restart file '" + file + "' was written by scene '" + restart->text("scene") +
                   "' (fingerprint " + fp + "), not by this scene '" + scene.name +
                   "' (fingerprint " + scene.fingerprint +
                   "): name, module and module parameters must match");
  }
  return restart;
}

/// --kernel-profile: every kernel from start() to the end of the stepping loop timed, written as
/// CSV when the loop ends (a diverged run's too). The file is opened at construction, so a path
/// that cannot be written fails before the set-up.
class LoopProfile {
 public:
  LoopProfile(std::string file, const Communicator& comm) : file_(std::move(file)) {
    if (file_.empty()) return;
    if (comm.size() > 1 && !comm.is_root()) file_ += ".rank" + std::to_string(comm.rank());
    if (!std::ofstream(file_)) throw RunError("--kernel-profile: cannot write " + file_);
  }
  void start() {
    if (!file_.empty()) profile_ = std::make_unique<kernels::KernelProfile>();
  }
  ~LoopProfile() {
    if (!profile_) return;
    std::ofstream out(file_);
    kernels::write_kernel_profile_csv(out, *profile_);
  }
  LoopProfile(const LoopProfile&) = delete;
  LoopProfile& operator=(const LoopProfile&) = delete;

 private:
  std::string file_;
  std::unique_ptr<kernels::KernelProfile> profile_;
};

}  // namespace

void check_scene(const Scene& scene, const Communicator& comm) { make_module(scene, comm); }

RunResult run_scene(const Scene& scene, const Communicator& comm, const RunOptions& options) {
  const Parameters& run = scene.run;
  const std::string dir = run.string("output_dir");
  LoopProfile profile(options.kernel_profile, comm);
  auto module = make_module(scene, comm);

  // The step: the requested (or cfl-scaled stable) one, shrunk to land on end_time exactly.
  const double end_time = run.real("end_time");
  double dt = run.has("dt") ? run.real("dt") : run.real("cfl") * module->stable_dt();
  long long n_steps = std::max(1LL, static_cast<long long>(std::ceil(end_time / dt - 1e-9)));
  dt = end_time / double(n_steps);
  module->set_time_step(dt);  // may refuse a step over the module's stability limit
  const bool adaptive = run.string("time_step") == "adaptive";
  long long step = 0;
  double t = 0.0;

  // Everything that can be wrong with the input is checked before the first byte is written.
  std::unique_ptr<H5Reader> restart = open_restart(options.restart, scene, comm);
  if (options.write_output) prepare_output_dir(dir, comm);

  FieldSeries series(dir, scene.name, comm);
  if (restart) {
    step = restart->integer("step");
    t = restart->real("time");
    dt = restart->real("dt");
    module->set_time_step(dt);
    n_steps = std::max(step, static_cast<long long>(std::llround(end_time / dt)));
    std::vector<StateBlock> blocks;
    for (const auto& name : module->owned_blocks()) blocks.push_back({name, restart->group(name)});
    module->restore(blocks);
    series.load(restart->text("series"));
    restart.reset();
  }
  DiagnosticsCsv csv(dir + "/diagnostics.csv", options.write_output && comm.is_root(),
                     options.restart.empty() ? -1 : step);
  const long long out_every = run.integer("output_every");
  const long long ck_every = run.integer("checkpoint_every");
  const long long diag_every = run.integer("diagnostics_every");

  if (comm.is_root() && !options.quiet) {
    std::cout << "[run] scene " << scene.name << " module " << scene.module << " ranks "
              << comm.size() << " steps " << step << ".." << n_steps << " dt " << fmt(dt)
              << " end_time " << fmt(end_time) << (options.restart.empty() ? "" : " (restart)")
              << "\n";
  }
  if (options.write_output && options.restart.empty()) {
    csv.write(step, t, dt, module->diagnostics(t));
    series.write(step, t, module->output(t));
  }

  RunResult result;
  result.work_per_step = module->work_per_step();
  result.work_unit = module->work_unit();
  Progress progress(std::cout, comm.is_root() && !options.quiet, step, n_steps, result.work_unit,
                    run.real("progress_seconds"));
  double work = 0.0;  // work units done by this run (a module's work per step may change)
  Diagnostics last_diagnostics;  // at the final step, computed once
  const long long first_step = step;
  double stepping = 0.0;  // wall time in advance() only
  profile.start();
  kernels::DeepCopyCounter
      copies;  // host-device traffic of the steps (not of output or checkpoints)
  kernels::DeepCopyCount copied;
  while ((adaptive ? t < end_time : step < n_steps) &&
         (options.max_steps < 0 || step - first_step < options.max_steps)) {
    const double t0 = progress.elapsed();
    if (adaptive) {
      dt = adaptive_dt(*module, run.real("cfl"), dt, end_time - t);
      module->set_time_step(dt);
    }
    work += double(module->work_per_step());
    const kernels::DeepCopyCount before = copies.count();
    Kokkos::Profiling::pushRegion("amphora::step");  // a profile's region (kernel_profile.hpp)
    module->advance(t, dt);
    Kokkos::Profiling::popRegion();
    copied = copied + (copies.count() - before);
    stepping += progress.elapsed() - t0;
    ++step;
    // Fixed steps: not accumulated, so the run lands on end_time and restarts identically.
    // Adaptive: the sum, exactly end_time on the step that was shortened to reach it.
    t = !adaptive ? double(step) * dt
                  : (t + dt >= end_time || dt == end_time - t ? end_time : t + dt);
    if (adaptive) n_steps = step + static_cast<long long>(std::ceil((end_time - t) / dt - 1e-9));
    progress.set_last_step(n_steps);
    if (auto bad = module->find_nonfinite()) {
      std::ostringstream m;
      m << "run diverged: " << (bad->reason.empty() ? "non-finite value" : bad->reason)
        << " in field '" << bad->field << "' of block '" << bad->block << "' at " << place(*bad)
        << " (index " << bad->index << ") at step " << step << ", t = " << fmt(t)
        << " (dt = " << fmt(dt) << "); last good output: "
        << (series.last_file().empty()
                ? "none"
                : series.last_file() + " (step " + std::to_string(series.last_step()) + ")");
      result.diverged = true;
      result.message = m.str();
      result.steps = step - first_step;
      result.final_step = step;
      result.time = t;
      result.dt = dt;
      return result;
    }
    const bool last = adaptive ? t >= end_time : step == n_steps;
    // Diagnostics are computed on schedule even when not written: a module may average them
    // (the drum's regime), and a study's result must not depend on whether files are written.
    if (last || step % diag_every == 0) {
      const Diagnostics d = module->diagnostics(t);
      if (options.write_output) csv.write(step, t, dt, d);
      if (last) last_diagnostics = d;
    }
    if (options.write_output) {
      if (last || (out_every > 0 && step % out_every == 0))
        series.write(step, t, module->output(t));
      if (!last && ck_every > 0 && step % ck_every == 0)
        write_checkpoint(dir, scene, comm, *module, series, {step, t, dt, n_steps});
    }
    progress.update(step, t, dt, work);
  }
  progress.update(step, t, dt, work, /*force=*/true);
  if (options.write_output)
    write_checkpoint(dir, scene, comm, *module, series, {step, t, dt, n_steps});

  result.steps = step - first_step;
  result.final_step = step;
  result.time = t;
  result.dt = dt;
  result.wall_seconds = stepping;
  result.work_per_step = module->work_per_step();
  result.rate = stepping > 0 ? work / stepping : 0;
  result.diagnostics = last_diagnostics.empty() ? module->diagnostics(t) : last_diagnostics;
  for (const auto& [name, v] : result.diagnostics)
    if (name == module->error_diagnostic()) result.error = v;
  result.copies = copied;
  result.phase_seconds = module->phase_seconds();
  for (auto& [name, seconds] : result.phase_seconds) seconds = comm.max(seconds);
  return result;
}

}  // namespace amphora::io
