#include "io/module_registry.hpp"

#include "coupling/cfd_dem/cfd_dem_module.hpp"
#include "coupling/fsi/beam_channel_module.hpp"
#include "coupling/fsi/mpve_module.hpp"
#include "physics/advection_diffusion_1d/advection_diffusion_1d.hpp"
#include "physics/dem/dem_module.hpp"
#include "physics/ins_fem/ins_module.hpp"
#include "physics/poisson_fem/poisson_fem.hpp"
#include "physics/solid_fem/solid_module.hpp"
#include "physics/water_mac/water_mac.hpp"

namespace amphora::io {

const std::vector<ModuleInfo>& module_registry() {
  static const std::vector<ModuleInfo> modules = {
      {"advection_diffusion_1d", physics::advection_diffusion_1d::parameter_table,
       [](const Parameters& p, const Communicator& c) -> std::unique_ptr<physics::Module> {
         return std::make_unique<
             physics::advection_diffusion_1d::AdvectionDiffusion1D<kernels::DefaultExecSpace>>(p,
                                                                                               c);
       }},
      {"beam_channel", coupling::fsi::beam_channel_parameter_table,
       coupling::fsi::create_beam_channel},
      {"cfd_dem", coupling::cfd_dem::cfd_dem_parameter_table, coupling::cfd_dem::create_cfd_dem},
      {"dem", physics::dem::parameter_table,
       [](const Parameters& p, const Communicator& c) -> std::unique_ptr<physics::Module> {
         return std::make_unique<physics::dem::DemModule>(p, c);
       }},
      {"ins_fem", physics::ins_fem::parameter_table, physics::ins_fem::create, true},
      {"mpve", coupling::fsi::mpve_parameter_table, coupling::fsi::create_mpve},
      {"poisson_fem", physics::poisson_fem::parameter_table, physics::poisson_fem::create},
      {"solid_fem", physics::solid_fem::parameter_table, physics::solid_fem::create},
      {"water_mac", physics::water_mac::parameter_table, physics::water_mac::create},
  };
  return modules;
}

const ModuleInfo* find_module(const std::string& name) {
  for (const auto& m : module_registry())
    if (m.name == name) return &m;
  return nullptr;
}

std::vector<std::string> module_names() {
  std::vector<std::string> names;
  for (const auto& m : module_registry()) names.push_back(m.name);
  return names;
}

}  // namespace amphora::io
