#pragma once
// One coupled step of unresolved CFD-DEM (VANS model A; Zhou et al., J. Fluid Mech. 661 (2010)
// 482; the order of Lethe's coupling): the fluid at the particles (t^n), the fluid's force on
// each particle (drag from the closure, pressure gradient, buoyancy) held over N DEM sub-steps,
// the void fraction of the new positions, the particles' drag spread back to the fluid, and
// the fluid step. The fluid's pressure is the hydrostatic-free part: gravity acts on the
// particles (weight and buoyancy), not in the flow.
#include <array>
#include <stdexcept>
#include <string>
#include <vector>

#include <Kokkos_Core.hpp>

#include "coupling/cfd_dem/drag_models.hpp"
#include "coupling/cfd_dem/particle_fluid_force.hpp"
#include "coupling/cfd_dem/particle_mesh.hpp"
#include "coupling/cfd_dem/void_fraction.hpp"
#include "kernels/blas1.hpp"
#include "physics/dem/dem_system.hpp"
#include "physics/ins_fem/ins_solver.hpp"
#include "physics/phase_times.hpp"

namespace amphora::coupling::cfd_dem {

/// How the fluid takes the particles' drag: semi-implicitly (-beta (u^(n+1) - v_p), Lethe's
/// default: the particles' relaxation time is no step limit for the fluid) or as the explicit
/// load of the forces the particles were given (the exchange then balances to round-off).
enum class DragCoupling { semi_implicit, explicit_load };

struct CfdDemOptions {
  FluidProperties fluid;
  VoidFractionOptions void_fraction;
  int dem_substeps = 1;  ///< DEM steps per fluid step: dt_fluid = N dt_dem
  DragCoupling drag_coupling = DragCoupling::semi_implicit;
  bool move_particles = true;  ///< false: a fixed bed (the DEM is not stepped)
};

/// The phases a coupled step's time is booked to (PhaseTimes indices).
enum CfdDemPhase {
  cfd_dem_void_fraction = 0,
  cfd_dem_forces = 1,
  cfd_dem_dem = 2,
  cfd_dem_fluid = 3
};
inline std::vector<std::string> cfd_dem_phase_names() {
  return {"void fraction", "forces", "DEM", "fluid"};
}

template <class ExecSpace>
class CfdDemCoupling {
 public:
  using Flow = physics::ins_fem::InsSolver<3, ExecSpace>;
  using Dem = physics::dem::DemSystem<ExecSpace>;
  using Mem = typename ExecSpace::memory_space;
  using Vector = Kokkos::View<double*, Mem>;
  using Set = mesh::particles::ParticleSet<Mem>;
  using Vec = typename Set::Vec;

  /// flow and dem must outlive this. Throws std::invalid_argument unless the flow solves VANS
  /// model A on Cartesian cells and N >= 1.
  CfdDemCoupling(Flow& flow, Dem& dem, const CfdDemOptions& options)
      : flow_(flow),
        dem_(dem),
        options_(options),
        void_fraction_(flow.space(), options.void_fraction),
        n_(flow.n_dofs()) {
    if (flow.options().model != physics::ins_fem::FlowModel::vans_a)
      throw std::invalid_argument("cfd_dem: the flow must solve VANS model A (model = vans_a)");
    if (options.dem_substeps < 1)
      throw std::invalid_argument("cfd_dem: dem_substeps must be at least 1, got " +
                                  std::to_string(options.dem_substeps));
    eps_ = Vector("amphora::cfd_dem::eps", n_);
    drag_ = Vector("amphora::cfd_dem::drag", n_);
    load_ = Vector("amphora::cfd_dem::load", 3 * n_);
  }

  double fluid_dt() const { return options_.dem_substeps * dem_.config().dt; }
  const Vector& void_fraction() const { return eps_; }
  /// The particles' load on the fluid (3 n_dofs, per unit fluid mass) and the implicit drag
  /// field the last step used.
  const Vector& particle_load() const { return load_; }
  const Vector& drag_field() const { return drag_; }
  const VoidFraction<3, ExecSpace>& void_fraction_solver() const { return void_fraction_; }
  /// The fluid's forces on the particles held over the last DEM window, per particle.
  Vec held_forces() { return dem_.external_force(); }
  void set_phase_times(physics::PhaseTimes* t) { times_ = t; }

  /// One fluid step of N DEM sub-steps.
  physics::ins_fem::InsStepReport step() {
    const ExecSpace exec;
    if (times_) times_->start();
    if (!started_) update_void_fraction(exec);  // eps^0
    started_ = true;
    lap(cfd_dem_void_fraction);
    sample(exec);
    particle_forces(exec);
    lap(cfd_dem_forces);
    if (options_.move_particles)
      for (int s = 0; s < options_.dem_substeps; ++s) dem_.step();
    lap(cfd_dem_dem);
    update_void_fraction(exec);
    lap(cfd_dem_void_fraction);
    if (options_.drag_coupling == DragCoupling::semi_implicit) {
      sample(exec);
      implicit_exchange(exec);
    }
    flow_.set_drag(drag_);
    flow_.set_particle_load(load_);
    lap(cfd_dem_forces);
    const auto r = flow_.step(fluid_dt());
    lap(cfd_dem_fluid);
    return r;
  }

  // (public for CUDA: extended lambdas may not live in private member functions)

  /// The void fraction of the particles now, to the flow.
  void update_void_fraction(const ExecSpace& exec) {
    const Set& p = dem_.particles();
    const auto r = void_fraction_.compute(exec, p.x, p.radius, p.n_owned, eps_);
    if (!r.converged)
      throw std::runtime_error("cfd_dem: the void fraction's projection did not converge");
    flow_.set_void_fraction(eps_);
  }

  /// The fluid's velocity, kinematic pressure gradient and void fraction at the particles.
  void sample(const ExecSpace& exec) {
    const Set& p = dem_.particles();
    const int n = p.n_owned;
    if (static_cast<int>(at_.void_fraction.extent(0)) < n) {
      at_.velocity = Vec("amphora::cfd_dem::u_at", n);
      at_.pressure_gradient = Vec("amphora::cfd_dem::grad_p_at", n);
      at_.void_fraction = Vector("amphora::cfd_dem::eps_at", n);
      eps_at_ = Kokkos::View<double* [3], Kokkos::LayoutRight, Mem>("amphora::cfd_dem::eps_at3", n);
      exchange_ = Vec("amphora::cfd_dem::exchange", n);
    }
    const auto& basis = void_fraction_.basis();
    interpolate(exec, basis, flow_.velocity(), 3, p.x, n, at_.velocity);
    interpolate_gradient(exec, basis, flow_.pressure(), p.x, n, at_.pressure_gradient);
    interpolate(exec, basis, eps_, 1, p.x, n, eps_at_);
    const auto e3 = eps_at_;
    const auto e = at_.void_fraction;
    Kokkos::parallel_for(
        "amphora::cfd_dem::eps_at", kernels::RangePolicy<ExecSpace>(exec, 0, n),
        KOKKOS_LAMBDA(int i) { e(i) = e3(i, 0); });
  }

  /// The held forces: drag + pressure gradient + buoyancy; with an explicit load, the drag's
  /// reaction spread to the fluid.
  void particle_forces(const ExecSpace& exec) {
    const Set& p = dem_.particles();
    const int n = p.n_owned;
    const Vec F = dem_.external_force(), drag = exchange_;
    const auto v = p.v, u = at_.velocity, gp = at_.pressure_gradient;
    const auto r = p.radius;
    const Vector eps = at_.void_fraction;
    const FluidProperties fl = options_.fluid;
    const auto& gc = dem_.config().gravity;
    const double g[3] = {gc[0], gc[1], gc[2]};
    Kokkos::parallel_for(
        "amphora::cfd_dem::held_forces", kernels::RangePolicy<ExecSpace>(exec, 0, n),
        KOKKOS_LAMBDA(int i) {
          double slip[3], s2 = 0.0;
          for (int c = 0; c < 3; ++c) slip[c] = u(i, c) - v(i, c), s2 += slip[c] * slip[c];
          const double d = 2.0 * r(i), volume = M_PI * d * d * d / 6.0;
          const double beta = drag_coefficient(fl.drag, fl.density, fl.viscosity, d, eps(i),
                                               kernels::math::sqrt(s2));
          for (int c = 0; c < 3; ++c) {
            drag(i, c) = -beta * slip[c] / fl.density;  // the fluid's share, per unit mass
            F(i, c) = beta * slip[c] - volume * fl.density * (gp(i, c) + g[c]);
          }
        });
    if (options_.drag_coupling != DragCoupling::explicit_load) return;
    kernels::blas1::fill(exec, load_, 0.0);
    spread(exec, void_fraction_.basis(), drag, 3, p.x, n, load_);
  }

  /// The semi-implicit exchange at the new positions: beta_p / rho to the drag field (over
  /// each node's basis integral) and beta_p v_p / rho to the load.
  void implicit_exchange(const ExecSpace& exec) {
    const Set& p = dem_.particles();
    const int n = p.n_owned;
    const Vec bv = exchange_;
    const auto b1 = eps_at_;  // reused: beta_p / rho in column 0
    const auto v = p.v, u = at_.velocity;
    const auto r = p.radius;
    const Vector eps = at_.void_fraction;
    const FluidProperties fl = options_.fluid;
    Kokkos::parallel_for(
        "amphora::cfd_dem::implicit_drag", kernels::RangePolicy<ExecSpace>(exec, 0, n),
        KOKKOS_LAMBDA(int i) {
          double s2 = 0.0;
          for (int c = 0; c < 3; ++c) s2 += (u(i, c) - v(i, c)) * (u(i, c) - v(i, c));
          const double beta = drag_coefficient(fl.drag, fl.density, fl.viscosity, 2.0 * r(i),
                                               eps(i), kernels::math::sqrt(s2)) /
                              fl.density;
          b1(i, 0) = beta;
          for (int c = 0; c < 3; ++c) bv(i, c) = beta * v(i, c);
        });
    kernels::blas1::fill(exec, load_, 0.0);
    kernels::blas1::fill(exec, drag_, 0.0);
    spread(exec, void_fraction_.basis(), bv, 3, p.x, n, load_);
    spread(exec, void_fraction_.basis(), b1, 1, p.x, n, drag_);
    const Vector dr = drag_, m = void_fraction_.basis_integrals();
    Kokkos::parallel_for(
        "amphora::cfd_dem::drag_field", kernels::RangePolicy<ExecSpace>(exec, 0, int(n_)),
        KOKKOS_LAMBDA(int j) { dr(j) /= m(j); });
  }

 private:
  void lap(int phase) {
    if (times_) times_->lap(phase);
  }

  Flow& flow_;
  Dem& dem_;
  CfdDemOptions options_;
  VoidFraction<3, ExecSpace> void_fraction_;
  long n_;
  Vector eps_, drag_, load_;
  FluidAtParticles<Mem> at_;
  Kokkos::View<double* [3], Kokkos::LayoutRight, Mem> eps_at_;
  Vec exchange_;
  bool started_ = false;
  physics::PhaseTimes* times_ = nullptr;
};

}  // namespace amphora::coupling::cfd_dem
