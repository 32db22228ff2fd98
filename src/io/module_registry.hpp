#pragma once
// The modules a scene can name (physics modules and couplings), with their parameter tables
// and factories.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "base/communicator.hpp"
#include "physics/module.hpp"
#include "base/parameters.hpp"

namespace amphora::io {

struct ModuleInfo {
  std::string name;
  std::function<ParamTable()> parameters;
  std::function<std::unique_ptr<physics::Module>(const Parameters&, const Communicator&)> create;
  /// Whether the module takes a different step each time ([run] time_step = "adaptive").
  bool variable_dt = false;
};

const std::vector<ModuleInfo>& module_registry();
/// nullptr if no module has that name.
const ModuleInfo* find_module(const std::string& name);
std::vector<std::string> module_names();

}  // namespace amphora::io
