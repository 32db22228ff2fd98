#pragma once
// Particle insertion: a lattice filling a region at once, or random non-overlapping placement
// in a box or a cylinder over time. Candidates come from a counter-based generator keyed by
// (seed, event, draw), so every rank draws the same ones and the result does not depend on the
// rank count; overlap checks see the particles of all ranks near the region.
#include <array>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "base/communicator.hpp"
#include "physics/dem/dem_system.hpp"

namespace amphora::physics::dem {

/// Insertion that cannot be satisfied: bad input (the scene asks for more than fits).
class InsertionError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// A box, or a cylinder with axis along z (centre cx, cy; from z_lo to z_hi), optionally cut
/// to y <= y_max.
struct InsertionRegion {
  enum Kind { kBox, kCylinder } kind = kBox;
  double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};  ///< box, or the cylinder's bounding box
  double cx = 0, cy = 0, radius = 0;
  double y_max = 1e300;
  /// True if a sphere of radius r at x lies wholly inside.
  bool contains(const double x[3], double r) const;
  double volume() const;
};

struct RadiusDistribution {
  double mean = 1e-3;
  double spread = 0;  ///< uniform in [mean (1 - spread), mean (1 + spread)]
  double max() const { return mean * (1 + spread); }
};

/// splitmix64 of a key: a counter-based generator, uniform in [0, 1).
double uniform01(std::uint64_t seed, std::uint64_t event, std::uint64_t draw);

/// Simple-cubic lattice of spacing `spacing` (>= the largest diameter, else InsertionError)
/// over the region, at most `count` particles (count <= 0: all sites); tiny deterministic
/// jitter breaks the lattice's symmetry. Gids start at first_gid. Along `periodic` directions
/// (of a box region spanning the periodic domain) the lattice tiles the length: the spacing
/// widened to length / floor(length / spacing), the sites half of it off the faces, so no seam
/// of another spacing lies across the periodic face.
std::vector<ParticleSpec> lattice_insertion(
    const InsertionRegion& region, const RadiusDistribution& radii, double spacing, long long count,
    double jitter, std::uint64_t seed, std::int64_t first_gid,
    const std::vector<double>& material_fractions,
    const std::array<bool, 3>& periodic = {false, false, false});

/// Up to `count` random particles in `region` that overlap neither each other nor the
/// particles of `system` (all ranks); `attempts` draws per particle. Throws InsertionError if
/// fewer than `count` fit. Collective.
template <class ExecSpace>
std::vector<ParticleSpec> random_insertion(const DemSystem<ExecSpace>& system,
                                           const InsertionRegion& region,
                                           const RadiusDistribution& radii, long long count,
                                           int attempts, std::uint64_t seed, std::uint64_t event,
                                           std::int64_t first_gid,
                                           const std::vector<double>& material_fractions);

}  // namespace amphora::physics::dem
