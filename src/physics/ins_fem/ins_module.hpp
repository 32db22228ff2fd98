#pragma once
// Incompressible Navier-Stokes on matrix-free Q_k (InsSolver) as a scene: the 2D and 3D
// Taylor-Green vortices (periodic), Kovasznay flow (steady, Dirichlet all round) and a
// regularised lid-driven cavity (walls). Diagnostics every step: kinetic energy, its decay
// rate, the viscous dissipation and their gap (the numerical dissipation), the divergence, the
// CFL number, GMRES iterations, and the errors where the flow is known exactly.
#include <memory>

#include "base/communicator.hpp"
#include "base/parameters.hpp"
#include "physics/module.hpp"

namespace amphora::physics::ins_fem {

/// The scene table `[ins_fem]`.
ParamTable parameter_table();

/// The module for the flow and dimension the parameters name.
std::unique_ptr<Module> create(const Parameters& p, const Communicator& comm);

}  // namespace amphora::physics::ins_fem
