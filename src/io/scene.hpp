#pragma once
// Scene files (TOML): a `[run]` table for the driver and one table for the module it names.
// Everything is checked against the declared parameters before anything runs or is written:
// unknown tables or keys, wrong types and out-of-range values are errors naming the file, the
// line, the key and what is allowed.
#include <stdexcept>
#include <string>
#include <vector>

#include "base/parameters.hpp"

namespace amphora::io {

class SceneError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct Scene {
  std::string path;
  std::string name;
  std::string module;
  Parameters run;
  Parameters module_parameters;
  /// Hash of the scene name, module and module parameters: a checkpoint from a scene with a
  /// different fingerprint cannot be continued by this one.
  std::string fingerprint;
};

/// The `[run]` table every scene has.
ParamTable run_parameter_table();

/// Reads and validates a scene. `overrides` are "table.key=value" with a TOML value, applied
/// before validation (the study command uses them). Throws SceneError.
Scene load_scene(const std::string& path, const std::vector<std::string>& overrides = {});

/// `key = default  # unit; allowed; doc` lines for a table, valid TOML.
std::string describe_defaults(const ParamTable& table);

}  // namespace amphora::io
