#pragma once
// Traveling waves of the beam model problem with an inviscid fluid: a channel -H < y < 0
// (slip wall at y = -H) under a periodic Euler–Bernoulli beam at y = 0 (physics/beam).
// Potential flow phi = A cosh(k (y + H)) e^{i(kx - omega t)} with phi_y(0) = eta_t gives the
// pressure on the beam p = rho omega^2 eta / (k tanh kH): the fluid adds the mass
// rho / (k tanh kH) per unit length, so (Banks, Henshaw & Schwendeman 2016, section 3)
//   omega^2 = (K + T k^2 + B k^4) / (rho_h + rho / (k tanh kH)).
// This added mass against rho_h is what decides whether the traditional partitioned scheme is
// stable: it fails once rho / (k tanh kH) dominates rho_h.
#include <cmath>

#include "physics/beam/euler_bernoulli_beam.hpp"

namespace amphora::coupling::fsi {

/// Added mass per unit length of the inviscid channel of depth H and density rho, mode k.
inline double channel_added_mass(double k, double H, double rho) {
  return rho / (k * std::tanh(k * H));
}

/// omega of the traveling wave of mode k of the beam over the channel.
inline double beam_channel_frequency(const physics::beam::BeamParameters& p, double k, double H,
                                     double rho) {
  const double restoring = p.spring + p.tension * k * k + p.stiffness * k * k * k * k;
  return std::sqrt(restoring / (p.rho_h + channel_added_mass(k, H, rho)));
}

}  // namespace amphora::coupling::fsi
