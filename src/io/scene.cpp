#include "io/scene.hpp"

#include <toml++/toml.h>

#include <cstdint>
#include <filesystem>
#include <sstream>

#include "io/module_registry.hpp"

namespace amphora::io {

ParamTable run_parameter_table() {
  return {
      "run",
      "what to run, for how long, and where its output goes",
      {
          string_param("name", std::nullopt, "scene name (default: the file's stem)"),
          string_param("module", std::nullopt, "the physics module to run (required)",
                       module_names()),
          string_param("output_dir", std::string("output"),
                       "output directory (fields, series, diagnostics, checkpoint)"),
          real_param("end_time", std::nullopt, "s", above(0.0), "end time (required)"),
          real_param("dt", std::nullopt, "s", above(0.0), "time step (default: cfl * stable step)"),
          real_param("cfl", 0.8, "1", above(0.0) & at_most(1.0),
                     "fraction of the module's stable step"),
          string_param("time_step", std::string("fixed"),
                       "fixed: one step, cfl times the stable step at the start (or dt); "
                       "adaptive: cfl times the stable step of the current state, every step",
                       {"fixed", "adaptive"}),
          int_param("output_every", 0, at_least(0),
                    "steps between field outputs (0: first and last)"),
          int_param("checkpoint_every", 0, at_least(0),
                    "steps between checkpoints (0: at the end)"),
          int_param("diagnostics_every", 10, at_least(1), "steps between diagnostics rows"),
          real_param("progress_seconds", 2.0, "s", at_least(0.0),
                     "wall time between progress lines"),
      }};
}

namespace {

std::string where(const std::string& path, const toml::source_region& src) {
  std::ostringstream s;
  s << path << ":" << src.begin.line;
  return s.str();
}

/// An adaptive step needs a module that takes one and no fixed dt beside it.
void check_time_step(const toml::table& run_table, const std::string& path, const Parameters& run,
                     const ModuleInfo& info) {
  if (run.string("time_step") != "adaptive") return;
  const std::string loc = where(path, run_table.get("time_step")->source());
  if (!info.variable_dt)
    throw SceneError(loc +
                     ": key 'run.time_step' = \"adaptive\" needs a module that takes a "
                     "variable step; module '" +
                     info.name + "' allows only \"fixed\"");
  if (run.has("dt"))
    throw SceneError(loc +
                     ": key 'run.time_step' = \"adaptive\" takes its step from cfl; "
                     "remove run.dt or set time_step = \"fixed\"");
}

std::string valid_keys(const ParamTable& t) {
  std::string s;
  for (const auto& spec : t.specs) s += (s.empty() ? "" : ", ") + spec.key;
  return s;
}

/// The TOML value as a parameter value of the declared type, or an error message.
ParamValue convert(const toml::node& node, const ParamSpec& spec, const std::string& loc,
                   const std::string& table) {
  const std::string key = table + "." + spec.key;
  auto wrong_type = [&](const char* got) {
    return SceneError(loc + ": key '" + key + "' must be " + spec.allowed() + " (" +
                      type_name(spec.type) + "), got a " + got);
  };
  const char* got = node.is_integer()          ? "integer"
                    : node.is_floating_point() ? "real number"
                    : node.is_boolean()        ? "boolean"
                    : node.is_string()         ? "string"
                    : node.is_table()          ? "table"
                    : node.is_array()          ? "array"
                                               : "date/time";
  switch (spec.type) {
    case ParamType::Real:
      if (node.is_floating_point()) return node.as_floating_point()->get();
      if (node.is_integer()) return double(node.as_integer()->get());
      throw wrong_type(got);
    case ParamType::Integer:
      if (node.is_integer()) return std::int64_t(node.as_integer()->get());
      throw wrong_type(got);
    case ParamType::Boolean:
      if (node.is_boolean()) return node.as_boolean()->get();
      throw wrong_type(got);
    case ParamType::String:
      if (node.is_string()) return node.as_string()->get();
      throw wrong_type(got);
  }
  throw wrong_type(got);
}

void read_table(const toml::table& tbl, const ParamTable& spec, const std::string& path,
                Parameters& out) {
  for (auto&& [k, node] : tbl) {
    const std::string key(k.str());
    const std::string loc = where(path, node.source());
    const ParamSpec* s = spec.find(key);
    if (!s) {
      throw SceneError(loc + ": unknown key '" + spec.name + "." + key + "'; valid keys in [" +
                       spec.name + "]: " + valid_keys(spec));
    }
    ParamValue v = convert(node, *s, loc, spec.name);
    const std::string why = s->check(v);
    if (!why.empty()) {
      throw SceneError(loc + ": key '" + spec.name + "." + key + "' = " + to_string(v) + " is " +
                       why + "; allowed: " + s->allowed());
    }
    out.set(key, std::move(v));
  }
}

void apply_override(toml::table& root, const std::string& assignment) {
  const auto eq = assignment.find('=');
  const auto dot = assignment.find('.');
  if (eq == std::string::npos || dot == std::string::npos || dot > eq) {
    throw SceneError("override '" + assignment + "': expected table.key=value");
  }
  const std::string table = assignment.substr(0, dot);
  const std::string key = assignment.substr(dot + 1, eq - dot - 1);
  toml::table parsed;
  try {
    parsed = toml::parse(std::string_view("v = " + assignment.substr(eq + 1)),
                         std::string_view("override"));
  } catch (const toml::parse_error& e) {
    throw SceneError("override '" + assignment + "': " + std::string(e.description()));
  }
  if (!root[table].is_table()) root.insert(table, toml::table{});
  root[table].as_table()->insert_or_assign(key, *parsed["v"].node());
}

std::string fnv1a_hex(const std::string& s) {
  std::uint64_t h = 1469598103934665603ULL;
  for (unsigned char c : s) {
    h ^= c;
    h *= 1099511628211ULL;
  }
  std::ostringstream o;
  o << std::hex << h;
  return o.str();
}

}  // namespace

Scene load_scene(const std::string& path, const std::vector<std::string>& overrides) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::exists(path, ec)) throw SceneError(path + ": scene file not found");
  if (!fs::is_regular_file(path, ec)) throw SceneError(path + ": not a regular file");

  toml::table root;
  try {
    root = toml::parse_file(path);
  } catch (const toml::parse_error& e) {
    std::ostringstream m;
    m << path << ":" << e.source().begin.line << ":" << e.source().begin.column
      << ": TOML syntax error: " << e.description();
    throw SceneError(m.str());
  }
  for (const auto& o : overrides) apply_override(root, o);

  const ParamTable run_table = run_parameter_table();
  Scene scene;
  scene.path = path;
  scene.run = Parameters(run_table);

  // [run] first: it names the module, which decides what other table is allowed.
  const toml::node* run_node = root.get("run");
  if (!run_node || !run_node->is_table()) {
    throw SceneError(path + ": missing table [run] (with at least module and end_time)");
  }
  read_table(*run_node->as_table(), run_table, path, scene.run);
  const std::string run_loc = where(path, run_node->source());
  for (const char* required : {"module", "end_time"}) {
    if (!scene.run.has(required)) {
      const ParamSpec* s = run_table.find(required);
      throw SceneError(run_loc + ": [run] lacks the required key '" + required + "' (" +
                       s->allowed() + ")");
    }
  }
  scene.module = scene.run.string("module");
  const ModuleInfo* info = find_module(scene.module);  // known: checked by the choices
  check_time_step(*run_node->as_table(), path, scene.run, *info);
  const ParamTable module_table = info->parameters();
  scene.module_parameters = Parameters(module_table);

  for (auto&& [k, node] : root) {
    const std::string name(k.str());
    if (name == "run") continue;
    const std::string loc = where(path, node.source());
    if (!node.is_table()) {
      throw SceneError(loc + ": top-level key '" + name +
                       "' must be inside a table; allowed "
                       "tables: [run], [" +
                       scene.module + "]");
    }
    if (name != scene.module) {
      const bool is_module = find_module(name) != nullptr;
      throw SceneError(loc + ": " +
                       (is_module ? "table [" + name +
                                        "] is for a module this scene does not "
                                        "run (run.module = \"" +
                                        scene.module + "\")"
                                  : "unknown table [" + name + "]") +
                       "; allowed tables: [run], [" + scene.module + "]");
    }
    read_table(*node.as_table(), module_table, path, scene.module_parameters);
  }

  scene.name = scene.run.has("name") ? scene.run.string("name") : fs::path(path).stem().string();
  std::string canonical = "name=" + scene.name + ";module=" + scene.module;
  for (const auto& [key, value] : scene.module_parameters.values())
    canonical += ";" + key + "=" + to_string(value);
  scene.fingerprint = fnv1a_hex(canonical);
  return scene;
}

std::string describe_defaults(const ParamTable& table) {
  std::ostringstream s;
  s << "# " << table.doc << "\n[" << table.name << "]\n";
  for (const auto& spec : table.specs) {
    std::ostringstream line;
    if (spec.default_value) {
      line << spec.key << " = " << to_string(*spec.default_value);
    } else {
      line << "# " << spec.key << " = (no default)";
    }
    std::string text = line.str();
    if (text.size() < 32) text.resize(32, ' ');
    s << text << "  # ";
    if (!spec.unit.empty()) s << "[" << spec.unit << "] ";
    s << spec.allowed() << "; " << spec.doc << "\n";
  }
  return s.str();
}

}  // namespace amphora::io
