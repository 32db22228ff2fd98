#pragma once
// Unresolved CFD-DEM as a scene module (`module = "cfd_dem"`): a square column of water with a
// uniform inflow at the bottom and an open top, particles on a lattice at its bottom, the
// DEM module (physics/dem) and the VANS flow solver (physics/ins_fem) composed by
// CfdDemCoupling. Scenes: a liquid fluidised bed (Ferreira et al. 2023's alumina in water,
// scaled down by default) and a fixed packed bed. Fluid and particles in one output series;
// diagnostics: the pressure drop against the bed's buoyant weight, the bed's height and void
// fraction against Richardson-Zaki, the void fraction's volume balance.
#include <memory>

#include "base/communicator.hpp"
#include "base/parameters.hpp"
#include "physics/module.hpp"

namespace amphora::coupling::cfd_dem {

/// The scene table `[cfd_dem]`.
ParamTable cfd_dem_parameter_table();
std::unique_ptr<physics::Module> create_cfd_dem(const Parameters& p, const Communicator& comm);

}  // namespace amphora::coupling::cfd_dem
