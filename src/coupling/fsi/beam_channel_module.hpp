#pragma once
// The beam-channel model problem as a scene module (`module = "beam_channel"`): the
// partitioned schemes of beam_channel_fsi.hpp from the exact traveling wave, with the beam and
// the channel pressure written for ParaView, errors against the exact wave as diagnostics, and
// an unstable coupling stopped with a message saying when and by how much it grew.
#include <memory>

#include "base/communicator.hpp"
#include "physics/module.hpp"
#include "base/parameters.hpp"

namespace amphora::coupling::fsi {

/// The scene table `[beam_channel]`.
ParamTable beam_channel_parameter_table();

std::unique_ptr<physics::Module> create_beam_channel(const Parameters& p, const Communicator& comm);

}  // namespace amphora::coupling::fsi
