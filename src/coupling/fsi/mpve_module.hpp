#pragma once
// MP-VE as a scene module (`module = "mpve"`): a viscous fluid on an elastic solid coupled by
// the traditional partitioned scheme (mpve_partitioned.hpp), from the exact traveling wave,
// whose frequency the module finds from the MP-VE check case by continuation; the fluid and
// the solid written for ParaView with the exact fields beside, errors as diagnostics, a
// blow-up stopped with a message.
#include <memory>

#include "base/communicator.hpp"
#include "physics/module.hpp"
#include "base/parameters.hpp"

namespace amphora::coupling::fsi {

ParamTable mpve_parameter_table();
std::unique_ptr<physics::Module> create_mpve(const Parameters& p, const Communicator& comm);

}  // namespace amphora::coupling::fsi
