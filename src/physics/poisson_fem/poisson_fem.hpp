#pragma once
// -lap u = f on the unit square/cube meshed by curved Q_k hexahedra (a smooth deformation of a
// structured box), homogeneous Dirichlet, manufactured solution u = prod sin(pi x_d): the
// matrix-free operators, multigrid and error norms of src/solvers as a scene. Steady: the
// first step solves; output is the solution on every Q_k node (a curvilinear grid for
// ParaView) with the exact solution and the error.
#include <memory>

#include "base/communicator.hpp"
#include "physics/module.hpp"
#include "base/parameters.hpp"

namespace amphora::physics::poisson_fem {

/// The scene table `[poisson_fem]`.
ParamTable parameter_table();

/// The module for the dimension the parameters name.
std::unique_ptr<Module> create(const Parameters& p, const Communicator& comm);

}  // namespace amphora::physics::poisson_fem
