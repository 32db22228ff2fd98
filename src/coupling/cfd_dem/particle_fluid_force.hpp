#pragma once
// The fluid's force on each particle of unresolved CFD-DEM (Zhou et al., J. Fluid Mech. 661
// (2010) 482): drag from the closure, the undisturbed flow's force rho V_p (nu lap u - grad p)
// with p the flow solver's kinematic pressure (no hydrostatic part), and buoyancy -rho V_p g.
// One point law (held_force) for the coupling and for one-way use; the fluid at each particle
// (velocity, void fraction, pressure gradient, the velocity's Laplacian) is sampled first.
#include "coupling/cfd_dem/drag_models.hpp"
#include "coupling/cfd_dem/lift_force.hpp"
#include "kernels/spaces.hpp"
#include "mesh/particles/particle_set.hpp"

namespace amphora::coupling::cfd_dem {

/// The fluid where each owned particle is (rows as the particles' storage order).
template <class MemSpace>
struct FluidAtParticles {
  typename mesh::particles::ParticleSet<MemSpace>::Vec velocity, pressure_gradient;
  /// The velocity's Laplacian (the viscous-stress force's; zero on Q1 cells).
  typename mesh::particles::ParticleSet<MemSpace>::Vec velocity_laplacian;
  typename mesh::particles::ParticleSet<MemSpace>::Scalar void_fraction;
  /// curl u (the lift's; zero without it).
  typename mesh::particles::ParticleSet<MemSpace>::Vec vorticity;
};

struct FluidProperties {
  double density = 1000.0;  ///< kg/m^3
  double viscosity = 1e-3;  ///< dynamic, Pa s
  DragModel drag = DragModel::di_felice;
  bool saffman_lift = false;  ///< add the Saffman-Mei lift
};

/// The held force F on a particle of diameter d at void fraction eps, slip u - v, kinematic
/// pressure gradient gp, velocity Laplacian lap and vorticity w, under gravity g; also the
/// undisturbed flow's force per unit fluid density, V_p (nu lap - gp), which model B returns to
/// the fluid, and the lift in F (zero without it), which the fluid takes back like the drag.
/// Returns the drag coefficient beta (F_drag = beta slip).
KOKKOS_INLINE_FUNCTION double held_force(const FluidProperties& fl, double d, double eps,
                                         const double slip[3], const double gp[3],
                                         const double lap[3], const double w[3], const double g[3],
                                         double F[3], double undisturbed[3], double lift[3]) {
  const double s2 = slip[0] * slip[0] + slip[1] * slip[1] + slip[2] * slip[2];
  const double volume = M_PI * d * d * d / 6.0, nu = fl.viscosity / fl.density;
  const double beta =
      drag_coefficient(fl.drag, fl.density, fl.viscosity, d, eps, kernels::math::sqrt(s2));
  for (int c = 0; c < 3; ++c) lift[c] = 0.0;
  if (fl.saffman_lift) saffman_mei_lift(fl.density, fl.viscosity, d, slip, w, lift);
  for (int c = 0; c < 3; ++c) {
    undisturbed[c] = volume * (nu * lap[c] - gp[c]);
    F[c] = beta * slip[c] + fl.density * (undisturbed[c] - volume * g[c]) + lift[c];
  }
  return beta;
}

/// force(i) = the fluid's held force on owned particle i under gravity g.
template <class ExecSpace, class MemSpace>
void particle_fluid_force(const ExecSpace& exec, const FluidProperties& fluid,
                          const double (&gravity)[3],
                          const mesh::particles::ParticleSet<MemSpace>& p,
                          const FluidAtParticles<MemSpace>& at,
                          const typename mesh::particles::ParticleSet<MemSpace>::Vec& force) {
  const auto v = p.v, u = at.velocity, gp = at.pressure_gradient, lap = at.velocity_laplacian;
  const auto vort = at.vorticity;
  const auto r = p.radius;
  const auto eps = at.void_fraction;
  const FluidProperties fl = fluid;
  const double g[3] = {gravity[0], gravity[1], gravity[2]};
  Kokkos::parallel_for(
      "amphora::cfd_dem::particle_fluid_force", kernels::RangePolicy<ExecSpace>(exec, 0, p.n_owned),
      KOKKOS_LAMBDA(int i) {
        double slip[3], gpi[3], lapi[3], w[3] = {0, 0, 0}, F[3], undisturbed[3], lift[3];
        for (int c = 0; c < 3; ++c)
          slip[c] = u(i, c) - v(i, c), gpi[c] = gp(i, c), lapi[c] = lap(i, c);
        if (fl.saffman_lift)
          for (int c = 0; c < 3; ++c) w[c] = vort(i, c);
        held_force(fl, 2.0 * r(i), eps(i), slip, gpi, lapi, w, g, F, undisturbed, lift);
        for (int c = 0; c < 3; ++c) force(i, c) = F[c];
      });
}

}  // namespace amphora::coupling::cfd_dem
