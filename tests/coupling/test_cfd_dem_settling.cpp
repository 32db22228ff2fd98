// Single spheres settling in water at rest (unresolved CFD-DEM, one way): the fluid's force
// (drag + buoyancy, particle_fluid_force) is computed once per fluid step and held over the
// DEM's sub-steps, as the coupled solver does. Each sphere must reach the terminal velocity of
// its drag law, found here in closed form, for particle Reynolds numbers 0.1 to 100.
#include <cmath>

#include "coupling/cfd_dem/particle_fluid_force.hpp"
#include "coupling/settling_sphere.hpp"
#include "physics/dem/dem_system.hpp"
#include "test_backend.hpp"

namespace amphora::coupling::cfd_dem {
namespace {

using Exec = test::TestExecSpace;
using Mem = Exec::memory_space;
using System = physics::dem::DemSystem<Exec>;
using namespace settling_sphere;

physics::dem::DemConfig config(const double* res) {
  physics::dem::Material glass;
  glass.density = kRhoP;
  physics::dem::DemConfig c;
  c.materials = {glass};
  c.domain_lo = {-0.012, -0.003, -0.045};  // small: the DEM bins the whole domain
  c.domain_hi = {0.012, 0.003, 0.003};
  c.max_radius = 0.5 * terminal(res[3]).first;
  c.skin = 0.5 * c.max_radius;
  return c;
}

/// Four spheres side by side at z = 0, of the diameters settling at Reynolds numbers res.
std::vector<physics::dem::ParticleSpec> spheres(const double* res) {
  std::vector<physics::dem::ParticleSpec> specs;
  for (int k = 0; k < 4; ++k) {
    physics::dem::ParticleSpec s;
    s.x[0] = -0.009 + 0.006 * k;  // apart: no contacts (one way: no wakes)
    s.radius = 0.5 * terminal(res[k]).first;
    s.gid = k;
    specs.push_back(s);
  }
  return specs;
}

TEST(CfdDemSettling, HeldForcesFollowTheirParticlesThroughRebuilds) {
  // Constant forces, larger for larger gid, and no gravity: the spheres fall at accelerations
  // gid + 1 m/s^2, overtake one another in the DEM's storage order (sorted by cell at
  // each rebuild), and must keep their own force throughout.
  const double res[] = {0.1, 1.0, 10.0, 100.0};
  physics::dem::DemConfig c = config(res);
  c.gravity = {0, 0, 0};
  c.dt = 1e-4;
  System sys(c, Communicator());
  sys.add_particles(spheres(res));
  {
    const auto& p = sys.particles();
    auto f = Kokkos::create_mirror_view(sys.external_force());
    auto m = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), p.mass);
    auto gid = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), p.gid);
    for (int i = 0; i < p.n_owned; ++i) f(i, 2) = -double(gid(i) + 1) * m(i);
    Kokkos::deep_copy(sys.external_force(), f);
  }
  const int steps = 800;  // 0.08 s: the last falls 1.3 cm, the first 3 mm
  for (int n = 0; n < steps; ++n) sys.step();
  const auto& p = sys.particles();
  auto v = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), p.v);
  auto gid = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), p.gid);
  ASSERT_EQ(p.n_owned, 4);
  EXPECT_EQ(gid(0), 3);  // the storage order did change
  for (int i = 0; i < p.n_owned; ++i) {
    EXPECT_NEAR(-v(i, 2) / (double(gid(i) + 1) * steps * c.dt), 1.0, 1e-12) << gid(i);
  }
}

TEST(CfdDemSettling, SpheresReachTheirDragLawsTerminalVelocity) {
  const double res[] = {0.1, 1.0, 10.0, 100.0};
  physics::dem::DemConfig c = config(res);
  // The smallest sphere relaxes in tau = rho_p d^2 / (18 mu) = 0.3 ms; the fluid step is half
  // of it (explicit drag: the held force overshoots from dt / tau = 2 on), the DEM takes 5
  // sub-steps per fluid step.
  const double tau = kRhoP * std::pow(terminal(0.1).first, 2) / (18 * kMu);
  const int substeps = 5;
  c.dt = 0.5 * tau / substeps;
  System sys(c, Communicator());
  sys.add_particles(spheres(res));

  FluidProperties water{kRhoF, kMu, DragModel::di_felice};
  using Vec = mesh::particles::ParticleSet<Mem>::Vec;
  FluidAtParticles<Mem> at;
  at.velocity = Vec("u", 4);                // water at rest
  at.pressure_gradient = Vec("grad_p", 4);  // the solver's pressure: no hydrostatic part
  at.velocity_laplacian = Vec("lap_u", 4);
  at.void_fraction = mesh::particles::ParticleSet<Mem>::Scalar("eps", 4);
  Kokkos::deep_copy(at.void_fraction, 1.0);
  const double g[3] = {c.gravity[0], c.gravity[1], c.gravity[2]};  // buoyancy: -rho V g
  const double end_time = 0.2;  // 9 relaxation times of the largest sphere (22 ms)
  const int fluid_steps = int(std::ceil(end_time / (substeps * c.dt)));
  for (int n = 0; n < fluid_steps; ++n) {
    particle_fluid_force(Exec(), water, g, sys.particles(), at, sys.external_force());
    for (int s = 0; s < substeps; ++s) sys.step();
  }
  const auto& p = sys.particles();
  auto v = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), p.v);
  auto gid = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), p.gid);
  ASSERT_EQ(p.n_owned, 4);
  for (int i = 0; i < 4; ++i) {
    const int k = int(gid(i));
    const double v_t = terminal(res[k]).second;
    // The held force's fixed point is the drag law's balance itself: what is left is the
    // relaxation, e^-9 of the largest sphere's start.
    EXPECT_NEAR(-v(i, 2) / v_t, 1.0, 5e-4) << "Re " << res[k];
    EXPECT_NEAR(v(i, 0), 0.0, 1e-12);
    EXPECT_NEAR(v(i, 1), 0.0, 1e-12);
  }
}

}  // namespace
}  // namespace amphora::coupling::cfd_dem
