#pragma once
// The fluid's force on each particle of unresolved CFD-DEM: drag from the closure plus the
// pressure-gradient force, F = beta (u_f - u_p) - V_p grad p (buoyancy where the pressure is
// hydrostatic; Zhou et al., J. Fluid Mech. 661 (2010) 482, model A). The fluid at each
// particle (velocity, void fraction, pressure gradient) is sampled by the coupling first.
#include "coupling/cfd_dem/drag_models.hpp"
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
};

struct FluidProperties {
  double density = 1000.0;  ///< kg/m^3
  double viscosity = 1e-3;  ///< dynamic, Pa s
  DragModel drag = DragModel::di_felice;
};

/// force(i) = the fluid's force on owned particle i (drag and pressure gradient).
template <class ExecSpace, class MemSpace>
void particle_fluid_force(const ExecSpace& exec, const FluidProperties& fluid,
                          const mesh::particles::ParticleSet<MemSpace>& p,
                          const FluidAtParticles<MemSpace>& at,
                          const typename mesh::particles::ParticleSet<MemSpace>::Vec& force) {
  const auto v = p.v, u = at.velocity, gp = at.pressure_gradient;
  const auto r = p.radius;
  const auto eps = at.void_fraction;
  const double rho = fluid.density, mu = fluid.viscosity;
  const DragModel model = fluid.drag;
  Kokkos::parallel_for(
      "amphora::cfd_dem::particle_fluid_force", kernels::RangePolicy<ExecSpace>(exec, 0, p.n_owned),
      KOKKOS_LAMBDA(int i) {
        const double slip[3] = {u(i, 0) - v(i, 0), u(i, 1) - v(i, 1), u(i, 2) - v(i, 2)};
        const double speed =
            kernels::math::sqrt(slip[0] * slip[0] + slip[1] * slip[1] + slip[2] * slip[2]);
        const double d = 2.0 * r(i);
        const double beta = drag_coefficient(model, rho, mu, d, eps(i), speed);
        const double volume = M_PI * d * d * d / 6.0;
        for (int c = 0; c < 3; ++c) force(i, c) = beta * slip[c] - volume * gp(i, c);
      });
}

}  // namespace amphora::coupling::cfd_dem
