#pragma once
// Regime of a rotating drum (Mellmann, Powder Technol. 118 (2001) 251: slipping, slumping,
// rolling, cascading, cataracting, centrifuging) from the particles' positions, velocities and
// contacts: centrifuging when a quarter of the bed rides in the drum's upper half with the
// wall; cataracting when particles fly free of all contacts well above the bed's surface;
// otherwise rolling or cascading
// by the shape of the free surface (flat, or the S/kidney shape of cascading).
#include <string>
#include <vector>

namespace amphora::physics::dem {

enum class DrumRegime { kRolling = 0, kCascading = 1, kCataracting = 2, kCentrifuging = 3 };
const char* to_string(DrumRegime r);

struct DrumState {
  double radius = 0;            ///< drum radius [m], axis along z through (0, 0)
  double angular_velocity = 0;  ///< [rad/s] about +z; gravity along -y
  double diameter = 0;          ///< particle diameter [m]
};

struct DrumClassification {
  DrumRegime regime = DrumRegime::kRolling;
  double upper_fraction = 0;     ///< particles above the axis moving with the wall
  double airborne_fraction = 0;  ///< particles in flight above the bed's surface
  double surface_angle = 0;      ///< free-surface inclination [degrees]
  double surface_deviation = 0;  ///< rms gap between cubic and linear surface fits [diameters]
};

/// The regime from (time-averaged) metrics: centrifuging when over a quarter of the bed rides
/// the wall's upper half, cataracting when over 5% fly above the surface, cascading when the
/// surface's cubic fit departs from its line by over 0.4 diameters (rms), else rolling.
DrumRegime regime_of(double upper_fraction, double airborne_fraction, double surface_deviation);

/// x, v: 3 per particle; contacts: per particle (particle and wall contacts).
DrumClassification classify_drum(const DrumState& drum, const std::vector<double>& x,
                                 const std::vector<double>& v, const std::vector<int>& contacts);

}  // namespace amphora::physics::dem
