#pragma once
// The invertible-FEM solid (TetSolid) as a scene: a box, ball, torus or Gmsh mesh of linear
// tetrahedra, squashed (or mirrored: inverted) along z at t = 0 or between moving plates and
// released, optionally pinned at its x = min face (a cantilever), under gravity, above a
// ground plane or ramp; stepped explicitly or by backward Euler. Diagnostics: energies, min
// det F, the volume and shape errors, the centroid height, the free end's sag, Newton's work.
#include <memory>

#include "base/communicator.hpp"
#include "base/parameters.hpp"
#include "physics/module.hpp"

namespace amphora::physics::solid_fem {

/// The scene table `[solid_fem]`.
ParamTable parameter_table();

std::unique_ptr<Module> create(const Parameters& p, const Communicator& comm);

}  // namespace amphora::physics::solid_fem
