// The amphora command line: run, check, defaults, info, study.
// Exit codes: 0 success, 1 internal error, 2 bad input, 3 run diverged.
#include <CLI/CLI.hpp>

#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "amphora/build_info.hpp"
#include "io/build_info.hpp"
#include "io/runner.hpp"
#include "io/scene.hpp"
#include "io/scene_catalog.hpp"
#include "mesh/box_decomposition.hpp"
#include "base/environment.hpp"
#include "io/module_registry.hpp"

namespace {

using namespace amphora;

int fail(const Communicator& comm, const std::string& message, int code) {
  if (comm.is_root()) std::cerr << "amphora: error: " << message << std::endl;
  return code;
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::stringstream in(s);
  std::string item;
  while (std::getline(in, item, sep))
    if (!item.empty()) out.push_back(item);
  return out;
}

int print_defaults(const std::string& name) {
  if (name == "run") {
    std::cout << io::describe_defaults(io::run_parameter_table());
    return 0;
  }
  if (const io::ModuleInfo* m = io::find_module(name)) {
    std::cout << io::describe_defaults(m->parameters());
    return 0;
  }
  std::cerr << "amphora: error: unknown module '" << name << "'; known: run";
  for (const auto& n : io::module_names()) std::cerr << ", " << n;
  std::cerr << std::endl;
  return 2;
}

/// `amphora run` without a scene: the scenes shipped, one line each.
int print_scenes() {
  const std::string dir = io::shipped_scene_dir();
  const auto scenes = io::list_scenes(dir);
  std::cout << "usage: amphora run SCENE [--restart FILE] [--max-steps N] [--no-output]\n"
            << "scenes shipped in " << dir << "/:\n";
  for (const auto& s : scenes)
    std::cout << "  " << std::left << std::setw(40) << s.path << s.summary << "\n";
  if (scenes.empty()) std::cout << "  (none found)\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Environment env(argc, argv);
  Communicator comm;

  CLI::App app{"amphora: GPU-portable multiphysics on Kokkos"};
  app.require_subcommand(1);
  app.set_version_flag(
      "--version", std::string("amphora ") + AMPHORA_VERSION + " (" + AMPHORA_GIT_REVISION + ")");

  std::string scene_path, restart, defaults_module, study_key, study_values, study_csv;
  long long max_steps = -1;
  bool no_output = false;

  auto* run = app.add_subcommand("run", "run a scene");
  run->add_option("scene", scene_path, "scene file (TOML); without one, the scenes shipped");
  run->add_option("--restart", restart, "continue from this checkpoint");
  run->add_option("--max-steps", max_steps, "stop after this many steps (writes a checkpoint)");
  run->add_flag("--no-output", no_output, "write nothing (for timing)");
  std::string kernel_profile;
  run->add_option("--kernel-profile", kernel_profile,
                  "time every kernel of the steps (fenced: slower) and write them to this CSV");

  auto* check = app.add_subcommand("check", "validate a scene without running it");
  check->add_option("scene", scene_path, "scene file (TOML)")->required();

  auto* defaults = app.add_subcommand("defaults", "print every key of a module with its default");
  defaults->add_option("module", defaults_module, "'run' or a module name")->required();

  auto* info = app.add_subcommand("info", "versions, backends, threads, ranks, revision");

  auto* study = app.add_subcommand("study", "run a scene over parameter values, write one CSV");
  study->add_option("scene", scene_path, "scene file (TOML)")->required();
  study->add_option("--set", study_key, "table.key to vary")->required();
  study->add_option("--values", study_values, "comma-separated values")->required();
  study->add_option("--csv", study_csv, "CSV to write")->required();

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return comm.is_root() ? app.exit(e) : (e.get_exit_code() == 0 ? 0 : 2);
  }

  try {
    if (*info) {
      if (comm.is_root())
        for (const auto& [k, v] : io::build_info())
          std::cout << std::left << std::setw(26) << k << v << "\n";
      return 0;
    }
    if (*defaults) return comm.is_root() ? print_defaults(defaults_module) : 0;
    if (*run && scene_path.empty()) return comm.is_root() ? print_scenes() : 0;

    const io::Scene scene = io::load_scene(scene_path);
    if (*check) {
      io::check_scene(scene, comm);
      if (comm.is_root())
        std::cout << scene_path << ": ok (scene '" << scene.name << "', module " << scene.module
                  << ")\n";
      return 0;
    }
    if (*run) {
      io::RunOptions opt;
      opt.restart = restart;
      opt.max_steps = max_steps;
      opt.write_output = !no_output;
      opt.kernel_profile = kernel_profile;
      const io::RunResult r = io::run_scene(scene, comm, opt);
      if (r.diverged) return fail(comm, r.message, 3);
      if (comm.is_root()) {
        std::cout << "[done] " << r.steps << " steps to t=" << r.time << " in " << r.wall_seconds
                  << " s stepping, " << r.rate << " " << r.work_unit << "/s";
        for (const auto& [k, v] : r.diagnostics) std::cout << ", " << k << "=" << v;
        std::cout << "\n";
        // where the stepping time went, per phase (the slowest rank's), one greppable line each
        if (r.steps > 0) {
          const auto per_step = [&](long long n) { return double(n) / double(r.steps); };
          const kernels::DeepCopyCount& c = r.copies;
          std::cout << "[transfers] per step (rank 0): " << per_step(c.copies) << " deep copies, "
                    << per_step(c.bytes) << " B; host-device " << per_step(c.host_device()) << ", "
                    << per_step(c.host_device_bytes()) << " B; fills " << per_step(c.fills)
                    << "; scalar reads " << per_step(c.scalar_reads) << "\n";
        }
        for (const auto& [phase, seconds] : r.phase_seconds)
          std::cout << "[timing] " << phase << " " << seconds << " s "
                    << (r.wall_seconds > 0 ? 100.0 * seconds / r.wall_seconds : 0.0) << " %\n";
      }
      return 0;
    }
    if (*study) {
      std::ostringstream csv;
      csv << std::setprecision(10);
      bool header = false;
      for (const auto& value : split(study_values, ',')) {
        const io::Scene s = io::load_scene(scene_path, {study_key + "=" + value});
        io::RunOptions opt;
        opt.write_output = false;
        opt.quiet = true;
        const io::RunResult r = io::run_scene(s, comm, opt);
        if (r.diverged) return fail(comm, study_key + "=" + value + ": " + r.message, 3);
        if (!header) {  // the module's final diagnostics follow the fixed columns
          csv << "parameter,value,error,wall_time,steps,work_per_step,rate,unit";
          for (const auto& [name, v] : r.diagnostics) csv << "," << name;
          csv << "\n";
          header = true;
        }
        csv << study_key << "," << value << "," << r.error << "," << r.wall_seconds << ","
            << r.steps << "," << r.work_per_step << "," << r.rate << "," << r.work_unit;
        for (const auto& [name, v] : r.diagnostics) csv << "," << v;
        csv << "\n";
        if (comm.is_root())
          std::cout << "[study] " << study_key << "=" << value << " error=" << r.error
                    << " wall=" << r.wall_seconds << " s rate=" << r.rate << " " << r.work_unit
                    << "/s" << std::endl;
      }
      if (comm.is_root()) {
        std::ofstream out(study_csv);
        out << csv.str();
        if (!out) return fail(comm, "cannot write '" + study_csv + "'", 2);
      }
      return 0;
    }
  } catch (const io::SceneError& e) {
    return fail(comm, e.what(), 2);
  } catch (const io::RunError& e) {
    return fail(comm, e.what(), 2);
  } catch (const mesh::DecompositionError& e) {
    return fail(comm, scene_path + ": " + e.what(), 2);
  } catch (const std::invalid_argument& e) {
    return fail(comm, scene_path + ": " + e.what(), 2);
  } catch (const std::exception& e) {
    return fail(comm, e.what(), 1);
  }
  return 0;
}
