#pragma once
// A DEM test system: n particles of radius 1 mm (+-30 %) on a jittered lattice with overlaps,
// shaken by random velocities (of up to speed / 2), in a box of side L with a small skin (many
// rebuilds), walled across the directions that are not periodic.
#include <array>
#include <stdexcept>

#include "physics/dem/dem_system.hpp"
#include "physics/dem/insertion.hpp"

namespace amphora::physics::dem::test_systems {

/// The box's configuration: one material, gravity along -z, walls where not periodic.
inline DemConfig shaken_config(double L,
                               const std::array<bool, 3>& periodic = {false, false, false}) {
  const double r = 1e-3;
  Material m;
  m.youngs_modulus = 1e6;
  m.restitution = 0.5;
  m.friction = 0.3;
  DemConfig c;
  c.materials = {m};
  c.domain_lo = {0, 0, 0};
  c.domain_hi = {L, L, L};
  c.periodic = periodic;
  c.gravity = {0, 0, -9.81};
  c.max_radius = 1.3 * r;
  c.skin = 0.3 * r;  // small: many rebuilds
  c.dt = 2e-5;
  for (int d = 0; d < 3; ++d) {
    if (periodic[d]) continue;
    Wall lo, hi;
    lo.axis[0] = lo.axis[1] = lo.axis[2] = 0;
    lo.axis[d] = 1;
    hi = lo;
    hi.axis[d] = -1;
    hi.point[d] = L;
    c.walls.push_back(lo);
    c.walls.push_back(hi);
  }
  return c;
}

template <class ExecSpace>
DemSystem<ExecSpace> shaken_packing(int n, double L,
                                    const std::array<bool, 3>& periodic = {false, false, false},
                                    double speed = 0.3) {
  const double r = 1e-3;
  DemSystem<ExecSpace> s(shaken_config(L, periodic), Communicator());
  InsertionRegion box;
  for (int d = 0; d < 3; ++d) box.hi[d] = L;
  auto ps = lattice_insertion(box, {r, 0.3}, 2.7 * r, n, 0.5 * r, 7, 0, {1.0}, periodic);
  if (int(ps.size()) != n)
    throw std::logic_error("shaken_packing: the box does not hold n particles");
  for (auto& p : ps)
    for (int d = 0; d < 3; ++d) p.v[d] = speed * (uniform01(11, d, p.gid) - 0.5);
  s.add_particles(ps);
  return s;
}

}  // namespace amphora::physics::dem::test_systems
