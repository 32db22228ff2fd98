#pragma once
// A single glass sphere settling through water with the water solved (unresolved CFD-DEM, two
// way): the run the two-way settling tests share.
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "coupling/cfd_dem/cfd_dem_coupling.hpp"
#include "coupling/settling_sphere.hpp"
#include "test_backend.hpp"

namespace amphora::coupling::cfd_dem::settling_two_way {

using Exec = test::TestExecSpace;
using Flow = physics::ins_fem::InsSolver<3, Exec>;
using Dem = physics::dem::DemSystem<Exec>;
using namespace settling_sphere;

struct Settling {
  double speed[2] = {0, 0};  ///< the sphere's fall speed after falling 3 and 4 cells
  double fluid[2] = {0, 0};  ///< the water's downward velocity at the sphere then (undisturbed)
  double raw[2] = {0, 0};    ///< the water's downward velocity there, as interpolated
  double terminal = 0.0;     ///< the drag law's
};

/// One sphere settling at Reynolds number re from the top of a laterally periodic column of
/// cubic Q1 cells `cells_per_diameter` diameters wide (width x width x height cells, closed
/// below, open above), PCM with smoothing length `smoothing` diameters, until it has fallen four
/// cells at the drag law's speed; `correct`: the closure takes the undisturbed velocity.
inline Settling settle(double re, double cells_per_diameter, double smoothing, bool correct = false,
                       int width = 4, int height = 8) {
  const auto [d, v_t] = terminal(re);
  const double h = cells_per_diameter * d;
  mesh::hex::StructuredHexMesh<3> m;
  m.cells = {width, width, height};
  m.upper = {width * h, width * h, height * h};
  for (int f = 0; f < 4; ++f) m.faces[f] = mesh::hex::FaceCondition::periodic;
  m.faces[5] = mesh::hex::FaceCondition::neumann;
  physics::ins_fem::InsOptions fo;
  fo.model = physics::ins_fem::FlowModel::vans_a;
  fo.nu = kMu / kRhoF;
  fo.tolerance = 1e-10;
  fo.transient_tau = true;
  Flow flow(m, 1, fo);

  physics::dem::Material glass;
  glass.density = kRhoP;
  physics::dem::DemConfig c;
  c.materials = {glass};
  c.domain_lo = {0.0, 0.0, 0.0};
  c.domain_hi = {width * h, width * h, height * h};
  c.max_radius = 0.5 * d;
  c.skin = 0.5 * d;
  // The sphere relaxes in tau = rho_p d^2 / (18 mu) or faster: fluid steps of tau / 2 (as the
  // one-way test), or of a tenth of a cell's crossing where that is shorter (Re 100); 5 DEM
  // sub-steps each.
  const double tau = kRhoP * d * d / (18 * kMu);
  const int substeps = 5;
  c.dt = std::min(0.5 * tau, 0.1 * h / v_t) / substeps;
  Dem dem(c, Communicator());
  physics::dem::ParticleSpec s;
  s.x[0] = s.x[1] = (width / 2 - 0.5) * h;  // inside a cell, a cell below the top
  s.x[2] = (height - 1) * h;
  s.radius = 0.5 * d;
  dem.add_particles({s});

  CfdDemOptions o;
  o.fluid = {kRhoF, kMu, DragModel::di_felice};
  o.void_fraction.smoothing_length = smoothing * d;
  o.dem_substeps = substeps;
  o.self_induced_correction = correct;
  CfdDemCoupling<Exec> coupling(flow, dem, o);
  Settling r;
  r.terminal = v_t;
  for (int k = 0; k < 2; ++k) {
    const double time = (3 + k) * h / v_t;
    while (coupling.steps() * coupling.fluid_dt() < time) {
      if (coupling.step().converged) continue;
      ADD_FAILURE() << "the fluid did not converge at step " << coupling.steps();
      return r;
    }
    coupling.sample(Exec());
    const auto v = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), dem.particles().v);
    const auto u = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(),
                                                       coupling.fluid_at_particles().velocity);
    r.speed[k] = -v(0, 2), r.fluid[k] = -u(0, 2);
    typename Dem::Vec raw("amphora::test::u_raw", 1);
    coupling.velocity_at_particles(Exec(), raw);
    r.raw[k] = -Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), raw)(0, 2);
  }
  return r;
}

}  // namespace amphora::coupling::cfd_dem::settling_two_way
