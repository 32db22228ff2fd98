#pragma once
// Water on a uniform MAC grid (Foster & Fedkiw 2001; Bridson 2015): level-set free surface
// (semi-Lagrangian advection, PDE reinitialisation), semi-Lagrangian velocity advection,
// gravity, pressure projection with ghost-fluid free-surface conditions and solid terrain,
// the pressure solved by the back end a scene names (multigrid, hypre, mic0), optionally on a
// tall-cell grid below an optical depth (Irving et al. 2006: pressure and velocity linear in
// height in the tall cells, conservative upwind advection there, the grid rebuilt every
// sub-step). Each run step is split into sub-steps that keep the CFL number at most `cfl`. On
// several ranks the grid is split horizontally into blocks (uniform or tall cells; multigrid or
// hypre).
//
// Scenes: a dam break (a water column of width a and height 2a collapsing along x; the front
// against Martin & Moyce 1952), a drop splashing into a deep pool, still water over uneven
// terrain (must stay at rest with hydrostatic pressure).
#include <memory>

#include "base/communicator.hpp"
#include "physics/module.hpp"
#include "base/parameters.hpp"
#include "physics/water_mac/water_diagnostics.hpp"

namespace amphora::physics::water_mac {

/// The scene table `[water_mac]`.
ParamTable parameter_table();

std::unique_ptr<Module> create(const Parameters& p, const Communicator& comm);

}  // namespace amphora::physics::water_mac
