// Verification of the Hertz–Mindlin contact law and its integration: restitution and contact
// duration of head-on collisions, bounces on a plane and inside a cylinder, a sliding sphere
// that ends up rolling at 5/7 of its speed, and energy conservation without dissipation.
#include <cmath>

#include "physics/dem/dem_system.hpp"
#include "test_backend.hpp"

namespace amphora::physics::dem {
namespace {

using System = DemSystem<test::TestExecSpace>;
constexpr double kR = 1.5e-3;  // 3 mm glass beads

Material glass(double e, double mu = 0.0) {
  Material m;
  m.density = 2500;
  m.youngs_modulus = 1e7;
  m.poisson_ratio = 0.3;
  m.restitution = e;
  m.friction = mu;
  return m;
}

DemConfig config(double e, double mu, double dt) {
  DemConfig c;
  c.materials = {glass(e, mu)};
  c.gravity = {0, 0, 0};
  c.domain_lo = {-0.05, -0.05, -0.05};
  c.domain_hi = {0.05, 0.05, 0.05};
  c.dt = dt;
  c.max_radius = kR;
  c.skin = 0.5 * kR;
  return c;
}

struct Host {
  std::vector<double> x, v, omega;
};
Host host(const System& s) {
  const auto& p = s.particles();
  auto x = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), p.x);
  auto v = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), p.v);
  auto w = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), p.omega);
  auto gid = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), p.gid);
  Host h;
  h.x.resize(3 * p.n_owned);
  h.v.resize(3 * p.n_owned);
  h.omega.resize(3 * p.n_owned);
  for (int i = 0; i < p.n_owned; ++i) {  // indexed by gid (0..n-1 in these tests)
    const int g = static_cast<int>(gid(i));
    for (int d = 0; d < 3; ++d) {
      h.x[3 * g + d] = x(i, d);
      h.v[3 * g + d] = v(i, d);
      h.omega[3 * g + d] = w(i, d);
    }
  }
  return h;
}

double effective_modulus(const Material& m) {
  return 1.0 / (2 * (1 - m.poisson_ratio * m.poisson_ratio) / m.youngs_modulus);
}

TEST(DemContact, DampingCalibrationHitsTheRestitution) {
  for (double e : {0.1, 0.5, 0.9, 0.99}) {
    EXPECT_NEAR(restitution_of_damping(damping_for_restitution(e)), e, 1e-6) << e;
  }
  EXPECT_EQ(damping_for_restitution(1.0), 0.0);
  // Undamped Hertz (Johnson, Contact Mechanics, 11.1): tau = 2 s_max int_0^1 du/sqrt(1-u^{5/2})
  // with s_max = (5/4)^{2/5}, the integral being B(2/5, 1/2) / (5/2); t_c = 2.8686 (...)^{1/5}.
  const double tau =
      2 * std::pow(1.25, 0.4) * 0.4 * std::tgamma(0.4) * std::tgamma(0.5) / std::tgamma(0.9);
  EXPECT_NEAR(scaled_contact_duration(0.0), tau, 1e-6);
}

/// Head-on collision of two equal spheres at relative speed 2 v0; returns (restitution,
/// contact duration / Hertz's elastic duration).
std::pair<double, double> collide(double e, double v0, double steps_per_contact) {
  const Material m = glass(e);
  const double mass = m.density * 4.0 / 3.0 * M_PI * kR * kR * kR;
  const double t_hertz = hertz_contact_time(0.5 * mass, 0.5 * kR, effective_modulus(m), 2 * v0);
  System s(config(e, 0.0, t_hertz / steps_per_contact), Communicator());
  const double gap = 0.2 * kR;
  ParticleSpec a, b;
  a.x[0] = -kR - gap;
  a.v[0] = v0;
  a.radius = kR;
  a.gid = 0;
  b.x[0] = kR + gap;
  b.v[0] = -v0;
  b.radius = kR;
  b.gid = 1;
  s.add_particles({a, b});
  double prev_sep = 2 * gap, t_start = -1, t_end = -1;
  for (int it = 0; it < 100000 && t_end < 0; ++it) {
    s.step();
    const Host h = host(s);
    const double sep = h.x[3] - h.x[0] - 2 * kR;
    // Crossing times of the separation through zero, by linear interpolation within a step.
    const double frac = prev_sep / (prev_sep - sep);
    if (prev_sep > 0 && sep <= 0) t_start = s.time() - s.config().dt * (1 - frac);
    if (prev_sep <= 0 && sep > 0) t_end = s.time() - s.config().dt * (1 - frac);
    prev_sep = sep;
  }
  const Host h = host(s);
  return {(h.v[3] - h.v[0]) / (2 * v0), (t_end - t_start) / t_hertz};
}

TEST(DemContact, HeadOnCollisionRestitutionAndHertzDuration) {
  for (double steps : {50.0, 100.0}) {  // dt = t_c / 50 and t_c / 100
    const auto [e_el, dur_el] = collide(1.0, 0.2, steps);
    EXPECT_NEAR(e_el, 1.0, 0.01) << "steps per contact " << steps;
    EXPECT_NEAR(dur_el, 1.0, 0.02) << "elastic contact duration against Hertz";
    for (double e : {0.9, 0.5}) {
      const auto [e_meas, dur] = collide(e, 0.2, steps);
      EXPECT_NEAR(e_meas / e, 1.0, 0.01) << "target restitution " << e;
      // Damping shortens the contact as the calibrated scaled duration predicts.
      const double expected =
          scaled_contact_duration(damping_for_restitution(e)) / scaled_contact_duration(0.0);
      EXPECT_NEAR(dur / expected, 1.0, 0.02) << "damped contact duration, e = " << e;
    }
  }
  // Restitution of the calibrated model does not depend on the impact speed.
  EXPECT_NEAR(collide(0.7, 1.0, 50).first / 0.7, 1.0, 0.01);
}

/// A sphere thrown at a wall at speed v0 along -n; returns the rebound speed ratio.
double bounce(const Wall& wall, const double x0[3], const double normal[3], double e) {
  const Material m = glass(e);
  const double mass = m.density * 4.0 / 3.0 * M_PI * kR * kR * kR;
  const double v0 = 0.3;
  // Wall of the same material: E* = E / (2 (1 - nu^2)), R* = r, m* = m.
  const double t_c = hertz_contact_time(mass, kR, effective_modulus(m), v0);
  DemConfig c = config(e, 0.0, t_c / 50);
  c.walls = {wall};
  System s(c, Communicator());
  ParticleSpec p;
  for (int d = 0; d < 3; ++d) {
    p.x[d] = x0[d];
    p.v[d] = -v0 * normal[d];
  }
  p.radius = kR;
  s.add_particles({p});
  for (int it = 0; it < 2000; ++it) s.step();
  const Host h = host(s);
  const double vn = h.v[0] * normal[0] + h.v[1] * normal[1] + h.v[2] * normal[2];
  return vn / v0;
}

TEST(DemContact, BounceOnAPlaneAndInsideACylinder) {
  Wall plane;
  plane.type = kPlane;
  plane.axis[0] = 0, plane.axis[1] = 0, plane.axis[2] = 1;
  const double above[3] = {0, 0, 1.2 * kR}, up[3] = {0, 0, 1};
  EXPECT_NEAR(bounce(plane, above, up, 0.8) / 0.8, 1.0, 0.01);

  Wall drum;
  drum.type = kCylinder;
  drum.axis[0] = 0, drum.axis[1] = 0, drum.axis[2] = 1;
  drum.point[2] = -0.01;
  drum.radius = 0.02;
  drum.length = 0.02;
  const double inside[3] = {0.02 - 1.2 * kR, 0, 0}, inward[3] = {-1, 0, 0};
  EXPECT_NEAR(bounce(drum, inside, inward, 0.8) / 0.8, 1.0, 0.01);
}

TEST(DemContact, SlidingSphereEndsUpRollingAtFiveSeventhsOfItsSpeed) {
  // Coulomb friction decelerates the centre and spins the sphere up until v = omega r; then
  // angular momentum about the contact point gives v = 5/7 v0 (solid sphere).
  const double v0 = 0.2;
  DemConfig c = config(0.5, 0.3, 2e-6);
  c.gravity = {0, 0, -9.81};
  Wall floor;
  floor.axis[2] = 1;
  c.walls = {floor};
  System s(c, Communicator());
  ParticleSpec p;
  p.radius = kR;
  // Start at the static overlap m g / k so the sphere does not bounce.
  p.x[2] = kR * (1 - 1e-4);
  p.v[0] = v0;
  s.add_particles({p});
  for (int it = 0; it < 60000; ++it) s.step();  // sliding lasts 2 v0 / (7 mu g) ~ 19 ms
  const Host h = host(s);
  EXPECT_NEAR(h.v[0] / v0, 5.0 / 7.0, 0.01 * 5.0 / 7.0);
  EXPECT_NEAR(h.omega[1] * kR / h.v[0], 1.0, 0.01) << "rolling without slip: v = omega r";
}

TEST(DemContact, EnergyIsConservedWithoutDampingOrFriction) {
  // A gas of 64 beads in a closed box, elastic and frictionless, no gravity: kinetic plus
  // Hertz elastic energy is conserved by velocity Verlet up to O(dt^2) fluctuations.
  const Material m = glass(1.0);
  const double mass = m.density * 4.0 / 3.0 * M_PI * kR * kR * kR;
  const double vmax = 0.5;
  const double t_c = hertz_contact_time(0.5 * mass, 0.5 * kR, effective_modulus(m), 2 * vmax);
  DemConfig c = config(1.0, 0.0, t_c / 400);
  const double L = 12 * kR;
  c.domain_lo = {0, 0, 0};
  c.domain_hi = {L, L, L};
  for (int d = 0; d < 3; ++d) {
    Wall lo, hi;
    lo.axis[0] = lo.axis[1] = lo.axis[2] = 0;
    hi = lo;
    lo.axis[d] = 1;
    hi.axis[d] = -1;
    hi.point[d] = L;
    c.walls.push_back(lo);
    c.walls.push_back(hi);
  }
  System s(c, Communicator());
  std::vector<ParticleSpec> ps;
  unsigned seed = 12345;
  auto rnd = [&]() {
    seed = seed * 1103515245u + 12345u;
    return ((seed >> 8) & 0xffff) / 65536.0 - 0.5;
  };
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      for (int k = 0; k < 4; ++k) {
        ParticleSpec p;
        p.x[0] = (1.5 + 3 * i) * kR;
        p.x[1] = (1.5 + 3 * j) * kR;
        p.x[2] = (1.5 + 3 * k) * kR;
        for (int d = 0; d < 3; ++d) p.v[d] = vmax * rnd();
        p.radius = kR;
        p.gid = ps.size();
        ps.push_back(p);
      }
  s.add_particles(ps);
  s.step();
  const double e0 = s.diagnostics().total_energy();
  double worst = 0;
  long long contacts = 0;
  for (int it = 0; it < 10000; ++it) {
    s.step();
    if (it % 50 == 0) {
      const DemDiagnostics d = s.diagnostics();
      worst = std::max(worst, std::abs(d.total_energy() - e0) / e0);
      contacts += d.contacts + d.wall_contacts;
    }
  }
  EXPECT_GT(contacts, 10) << "the gas must actually collide";
  EXPECT_LT(worst, 1e-6);
}

}  // namespace
}  // namespace amphora::physics::dem
