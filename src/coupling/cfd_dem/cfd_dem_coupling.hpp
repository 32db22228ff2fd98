#pragma once
// One coupled step of unresolved CFD-DEM (VANS model A or B; Zhou et al., J. Fluid Mech. 661
// (2010) 482; the order of Lethe's coupling): the fluid at the particles (t^n), the fluid's
// force on each particle (drag from the closure, pressure gradient, viscous stress, buoyancy)
// held over N DEM sub-steps, the void fraction of the new positions, the particles' forces
// spread back to the fluid, and the fluid step. The fluid's pressure is the hydrostatic-free
// part: gravity acts on the particles (weight and buoyancy), not in the flow. Model A's fluid
// takes the drag alone (its -eps grad p and eps div tau hold the rest); model B's, whose
// momentum equation has -grad p, takes the pressure and viscous forces too (Lethe's theory
// guide, "Unresolved CFD-DEM").
#include <array>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <Kokkos_Core.hpp>

#include "coupling/cfd_dem/drag_models.hpp"
#include "coupling/cfd_dem/particle_fluid_force.hpp"
#include "coupling/cfd_dem/particle_mesh.hpp"
#include "coupling/cfd_dem/self_induced_velocity.hpp"
#include "coupling/cfd_dem/void_fraction.hpp"
#include "base/communicator.hpp"
#include "kernels/blas1.hpp"
#include "physics/dem/dem_system.hpp"
#include "physics/ins_fem/ins_solver.hpp"
#include "physics/phase_times.hpp"

namespace amphora::coupling::cfd_dem {

/// How the fluid takes the particles' drag: semi-implicitly (-beta (u^(n+1) - v_p), Lethe's
/// default: the particles' relaxation time is no step limit for the fluid) or as the explicit
/// load of the forces the particles were given (the exchange then balances to round-off).
enum class DragCoupling { semi_implicit, explicit_load };

/// A coupled step that cannot go on: eps out of (0, 1] at a node, or a fluid step over the CFL
/// limit. `node` is the flow DoF where it failed (-1: not one node; the report then names the
/// fastest velocity).
struct StepFailure : std::runtime_error {
  StepFailure(const std::string& what, std::string field_, long node_)
      : std::runtime_error(what), field(std::move(field_)), node(node_) {}
  std::string field;
  long node;
};

struct CfdDemOptions {
  FluidProperties fluid;
  VoidFractionOptions void_fraction;
  int dem_substeps = 1;  ///< DEM steps per fluid step: dt_fluid = N dt_dem
  DragCoupling drag_coupling = DragCoupling::semi_implicit;
  bool move_particles = true;  ///< false: a fixed bed (the DEM is not stepped)
  /// A fluid step whose convective CFL number (InsSolver::cfl) exceeds this stops the run.
  double max_cfl = 1.0;
  /// The viscous-stress force on each particle, V_p mu lap u (Lethe's "shear force"; zero on
  /// Q1 cells, where each cell's velocity is linear in every direction).
  bool viscous_force = true;
  /// Give the closures the undisturbed velocity: the fluid's at each particle less what the
  /// particle's own force induces there (self_induced_velocity.hpp; Q1 only). For lone
  /// particles in cells a few diameters wide; a bed's closures are fitted to the mean flow.
  bool self_induced_correction = false;
};

/// DEM steps per fluid step, N = dt_fluid / dt_dem; throws std::invalid_argument unless N is a
/// positive integer (within 1e-9 relative).
inline int dem_substeps_of(double dt_fluid, double dt_dem) {
  const double ratio = dt_fluid / dt_dem;
  const long n = std::lround(ratio);
  if (!(dt_fluid > 0.0 && dt_dem > 0.0) || n < 1 || std::abs(ratio - n) > 1e-9 * ratio) {
    std::ostringstream m;
    m << "cfd_dem: the DEM step " << dt_dem << " s must divide the fluid step " << dt_fluid
      << " s a whole number of times (ratio " << ratio << ")";
    throw std::invalid_argument(m.str());
  }
  return static_cast<int>(n);
}

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
  /// (model A or B) with the transient tau on Cartesian cells and N >= 1.
  CfdDemCoupling(Flow& flow, Dem& dem, const CfdDemOptions& options)
      : flow_(flow),
        dem_(dem),
        options_(options),
        void_fraction_(flow.distributed_space(), options.void_fraction),
        n_(flow.n_dofs()),
        model_b_(flow.options().model == physics::ins_fem::FlowModel::vans_b) {
    if (!flow.vans())
      throw std::invalid_argument(
          "cfd_dem: the flow must solve VANS model A or B (model = vans_a or vans_b)");
    // With the steady tau (~h / 2|u|, 0.6 s) over fluid steps of 0.1 s, the clear fluid below
    // a packed bed oscillated node by node (10x U) and the linear solves stalled.
    if (!flow.options().transient_tau)
      throw std::invalid_argument(
          "cfd_dem: the flow needs transient_tau = true (the SUPG/PSPG tau must shrink with the "
          "step)");
    if (options.dem_substeps < 1)
      throw std::invalid_argument("cfd_dem: dem_substeps must be at least 1, got " +
                                  std::to_string(options.dem_substeps));
    warn_unsmoothed_large_particles();
    check_split();
    if (options.self_induced_correction)  // throws unless Q1
      self_ = self_induced_velocity<ExecSpace>(void_fraction_.basis(),
                                               options.fluid.viscosity / options.fluid.density);
    eps_ = Vector("amphora::cfd_dem::eps", n_);
    drag_ = Vector("amphora::cfd_dem::drag", n_);
    load_ = Vector("amphora::cfd_dem::load", 3 * n_);
  }

  double fluid_dt() const { return options_.dem_substeps * dem_.config().dt; }
  long steps() const { return steps_; }  ///< coupled steps taken
  const Vector& void_fraction() const { return eps_; }
  /// The particles' load on the fluid (3 n_dofs, per unit fluid mass) and the implicit drag
  /// field the last step used.
  const Vector& particle_load() const { return load_; }
  const Vector& drag_field() const { return drag_; }
  const VoidFraction<3, ExecSpace>& void_fraction_solver() const { return void_fraction_; }
  /// The fluid at the particles as last sampled (velocity, pressure gradient, void fraction).
  const FluidAtParticles<Mem>& fluid_at_particles() const { return at_; }
  /// The fluid's forces on the particles held over the last DEM window, per particle.
  Vec held_forces() { return dem_.external_force(); }
  void set_phase_times(physics::PhaseTimes* t) { times_ = t; }

  /// A restart after `steps` coupled steps, the flow's state and void fraction history and
  /// the particles restored: the void fraction now is the flow's eps^n, not computed anew (the
  /// projection's CG starts from the last one, so a new one would differ in round-off).
  void resume(long steps) {
    Kokkos::deep_copy(eps_, flow_.void_fraction());
    started_ = true;
    steps_ = steps;
  }

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
    check_cfl();
    const auto r = flow_.step(fluid_dt());
    ++steps_;
    lap(cfd_dem_fluid);
    return r;
  }

  // (public for CUDA: extended lambdas may not live in private member functions)

  /// The void fraction of the particles now, to the flow. On several ranks the particles first
  /// move to the ranks whose slabs hold them (DemSystem::redistribute), so that each spreads
  /// into and samples its own cells.
  void update_void_fraction(const ExecSpace& exec) {
    if (several_ranks() && (options_.move_particles || !started_)) dem_.redistribute();
    const Set& p = dem_.particles();
    std::array<bool, 3> own_images;
    for (int d = 0; d < 3; ++d)
      own_images[d] = dem_.decomposition().neighbor(d, 0) == comm().rank();
    const auto r =
        void_fraction_.compute(exec, p.x, p.radius, p.n_owned, eps_, p.n_owned + p.n_ghost,
                               own_images, dem_.build_positions());
    if (!r.converged)
      throw std::runtime_error("cfd_dem: the void fraction's projection did not converge");
    check_void_fraction(exec);
    flow_.set_void_fraction(eps_);
  }

  /// Throws StepFailure naming the node (and the step) where eps leaves (0, 1], on every rank
  /// alike. Collective.
  void check_void_fraction(const ExecSpace& exec) const {
    using Loc = Kokkos::MinLoc<double, int>;
    using Max = Kokkos::MaxLoc<double, int>;
    typename Loc::value_type lo;
    typename Max::value_type hi;
    const Vector e = eps_;
    const int n = static_cast<int>(n_);
    Kokkos::parallel_reduce(
        "amphora::cfd_dem::eps_min", kernels::RangePolicy<ExecSpace>(exec, 0, n),
        KOKKOS_LAMBDA(int i, typename Loc::value_type& a) {
          if (e(i) < a.val) a.val = e(i), a.loc = i;
        },
        Loc(lo));
    Kokkos::parallel_reduce(
        "amphora::cfd_dem::eps_max", kernels::RangePolicy<ExecSpace>(exec, 0, n),
        KOKKOS_LAMBDA(int i, typename Max::value_type& a) {
          if (e(i) > a.val) a.val = e(i), a.loc = i;
        },
        Max(hi));
    const double low = comm().min(lo.val), high = comm().max(hi.val);
    if (low > 0.0 && high <= 1.0 + 1e-9) return;
    const bool below = !(low > 0.0);
    const bool mine = below ? lo.val == low : hi.val == high;
    // The lowest rank holding the extreme names it.
    const int root = static_cast<int>(-comm().max(mine ? -static_cast<long long>(comm().rank())
                                                       : -static_cast<long long>(comm().size())));
    const int node = below ? lo.loc : hi.loc;
    const std::string what = comm().broadcast(
        comm().rank() == root ? void_fraction_message(below ? low : high, node) : std::string(),
        root);
    throw StepFailure(what, "eps", comm().rank() == root ? node : -1);
  }

  /// The fluid's velocity, kinematic pressure gradient and void fraction at the particles.
  void sample(const ExecSpace& exec) {
    const Set& p = dem_.particles();
    const int n = p.n_owned;
    if (static_cast<int>(at_.void_fraction.extent(0)) < n) {
      at_.velocity = Vec("amphora::cfd_dem::u_at", n);
      at_.pressure_gradient = Vec("amphora::cfd_dem::grad_p_at", n);
      at_.void_fraction = Vector("amphora::cfd_dem::eps_at", n);
      at_.velocity_laplacian = Vec("amphora::cfd_dem::lap_u_at", n);  // zeros
      at_.vorticity = Vec("amphora::cfd_dem::curl_u_at", n);          // zeros without lift
      eps_at_ = Kokkos::View<double* [3], Kokkos::LayoutRight, Mem>("amphora::cfd_dem::eps_at3", n);
      exchange_ = Vec("amphora::cfd_dem::exchange", n);
      self_correction_ =
          Vec("amphora::cfd_dem::self_correction", n);  // zeros without the correction
    }
    const auto& basis = void_fraction_.basis();
    interpolate(exec, basis, flow_.velocity(), 3, p.x, n, at_.velocity);
    interpolate_gradient(exec, basis, flow_.pressure(), p.x, n, at_.pressure_gradient);
    if (options_.viscous_force && basis.lattice.degree > 1)
      interpolate_laplacian(exec, basis, flow_.velocity(), 3, p.x, n, at_.velocity_laplacian);
    if (options_.fluid.saffman_lift)
      interpolate_curl(exec, basis, flow_.velocity(), p.x, n, at_.vorticity);
    interpolate(exec, basis, eps_, 1, p.x, n, eps_at_);
    const auto e3 = eps_at_;
    const auto e = at_.void_fraction;
    Kokkos::parallel_for(
        "amphora::cfd_dem::eps_at", kernels::RangePolicy<ExecSpace>(exec, 0, n),
        KOKKOS_LAMBDA(int i) { e(i) = e3(i, 0); });
    if (options_.self_induced_correction) remove_self_induced(exec);
  }

  /// The sampled velocity less each particle's own: u_und = u + S W beta (u_und - v) / rho (the
  /// force's reaction -beta slip spread and read back through W, screened by S), a fixed point
  /// in a few iterations (S beta |W| / rho is the self-induced share of the slip, well under 1).
  /// The correction u_und - u is kept for the fluid's exchange.
  void remove_self_induced(const ExecSpace& exec) {
    const Set& p = dem_.particles();
    const auto u = at_.velocity, corr = self_correction_, v = p.v, x = p.x;
    const auto r = p.radius;
    const Vector eps = at_.void_fraction;
    const FluidProperties fl = options_.fluid;
    const SelfInducedVelocity t = self_;
    Kokkos::parallel_for(
        "amphora::cfd_dem::self_induced", kernels::RangePolicy<ExecSpace>(exec, 0, p.n_owned),
        KOKKOS_LAMBDA(int i) {
          const double xi[3] = {x(i, 0), x(i, 1), x(i, 2)};
          double W[9], u0[3], und[3];
          t.response(xi, W);
          for (int c = 0; c < 3; ++c) u0[c] = und[c] = u(i, c);
          for (int it = 0; it < 8; ++it) {
            double slip[3], s2 = 0.0;
            for (int c = 0; c < 3; ++c) slip[c] = und[c] - v(i, c), s2 += slip[c] * slip[c];
            const double s = kernels::math::sqrt(s2);
            const double beta =
                drag_coefficient(fl.drag, fl.density, fl.viscosity, 2.0 * r(i), eps(i), s);
            const double k = t.screening(W, s) * beta / fl.density;
            for (int a = 0; a < 3; ++a)
              und[a] = u0[a] +
                       k * (W[3 * a] * slip[0] + W[3 * a + 1] * slip[1] + W[3 * a + 2] * slip[2]);
          }
          for (int c = 0; c < 3; ++c) u(i, c) = und[c], corr(i, c) = und[c] - u0[c];
        });
  }

  /// The fluid's velocity at the owned particles now, into u (n_owned x 3), leaving the last
  /// sample (which the step's forces used) as it is.
  void velocity_at_particles(const ExecSpace& exec, const Vec& u) const {
    const Set& p = dem_.particles();
    interpolate(exec, void_fraction_.basis(), flow_.velocity(), 3, p.x, p.n_owned, u);
  }

  /// The held forces: drag + pressure gradient + viscous stress + buoyancy; with an explicit
  /// load, their reaction less buoyancy's spread to the fluid (model A: the drag's alone).
  void particle_forces(const ExecSpace& exec) {
    const Set& p = dem_.particles();
    const int n = p.n_owned;
    const Vec F = dem_.external_force(), drag = exchange_;
    const auto v = p.v, u = at_.velocity, gp = at_.pressure_gradient;
    const auto lap = at_.velocity_laplacian, vort = at_.vorticity;
    const auto r = p.radius;
    const Vector eps = at_.void_fraction;
    const FluidProperties fl = options_.fluid;
    const double b = model_b_ ? 1.0 : 0.0;
    const auto& gc = dem_.config().gravity;
    const double g[3] = {gc[0], gc[1], gc[2]};
    Kokkos::parallel_for(
        "amphora::cfd_dem::held_forces", kernels::RangePolicy<ExecSpace>(exec, 0, n),
        KOKKOS_LAMBDA(int i) {
          double slip[3], gpi[3], lapi[3], w[3], Fi[3], undisturbed[3], lift[3];
          for (int c = 0; c < 3; ++c)
            slip[c] = u(i, c) - v(i, c), gpi[c] = gp(i, c), lapi[c] = lap(i, c), w[c] = vort(i, c);
          const double beta =
              held_force(fl, 2.0 * r(i), eps(i), slip, gpi, lapi, w, g, Fi, undisturbed, lift);
          for (int c = 0; c < 3; ++c) {  // the fluid's share, per unit mass
            drag(i, c) = -(beta * slip[c] + lift[c]) / fl.density - b * undisturbed[c];
            F(i, c) = Fi[c];
          }
        });
    if (options_.drag_coupling != DragCoupling::explicit_load) return;
    kernels::blas1::fill(exec, load_, 0.0);
    spread(exec, void_fraction_.basis(), drag, 3, p.x, n, load_);
    void_fraction_.slabs().compress_add(exec, load_, 3, 0);
  }

  /// The semi-implicit exchange at the new positions: beta_p / rho to the drag field (over
  /// each node's basis integral) and beta_p (v_p - (u_und - u)) / rho to the load; model B adds the
  /// pressure and viscous forces' reaction, V_p (grad p - nu lap u), to the load.
  void implicit_exchange(const ExecSpace& exec) {
    const Set& p = dem_.particles();
    const int n = p.n_owned;
    const Vec bv = exchange_;
    const auto b1 = eps_at_;  // reused: beta_p / rho in column 0
    const auto v = p.v, u = at_.velocity, gp = at_.pressure_gradient, corr = self_correction_;
    const auto lap = at_.velocity_laplacian, vort = at_.vorticity;
    const auto r = p.radius;
    const Vector eps = at_.void_fraction;
    const FluidProperties fl = options_.fluid;
    const double b = model_b_ ? 1.0 : 0.0;
    const double g[3] = {0.0, 0.0, 0.0};  // the held force itself is not used here
    Kokkos::parallel_for(
        "amphora::cfd_dem::implicit_drag", kernels::RangePolicy<ExecSpace>(exec, 0, n),
        KOKKOS_LAMBDA(int i) {
          double slip[3], gpi[3], lapi[3], w[3], F[3], undisturbed[3], lift[3];
          for (int c = 0; c < 3; ++c)
            slip[c] = u(i, c) - v(i, c), gpi[c] = gp(i, c), lapi[c] = lap(i, c), w[c] = vort(i, c);
          const double beta =
              held_force(fl, 2.0 * r(i), eps(i), slip, gpi, lapi, w, g, F, undisturbed, lift) /
              fl.density;
          b1(i, 0) = beta;
          // -beta (u^(n+1) + corr - v) - lift: the fluid takes what the particle is given
          for (int c = 0; c < 3; ++c)
            bv(i, c) = beta * (v(i, c) - corr(i, c)) - lift[c] / fl.density - b * undisturbed[c];
        });
    kernels::blas1::fill(exec, load_, 0.0);
    kernels::blas1::fill(exec, drag_, 0.0);
    spread(exec, void_fraction_.basis(), bv, 3, p.x, n, load_);
    spread(exec, void_fraction_.basis(), b1, 1, p.x, n, drag_);
    void_fraction_.slabs().compress_add(exec, load_, 3, 0);
    void_fraction_.slabs().compress_add(exec, drag_, 1, 0);
    const Vector dr = drag_, m = void_fraction_.basis_integrals();
    Kokkos::parallel_for(
        "amphora::cfd_dem::drag_field", kernels::RangePolicy<ExecSpace>(exec, 0, int(n_)),
        KOKKOS_LAMBDA(int j) { dr(j) /= m(j); });
  }

 private:
  std::string void_fraction_message(double value, int node) const {
    const std::vector<double> x =
        flow_.space().interpolate([](const mesh::hex::Point3& p, int c) { return p[c]; }, 3);
    std::ostringstream v, m;
    v << std::setprecision(10) << value;  // an overshoot past 1 shows in the tenth digit
    m << "cfd_dem: void fraction " << v.str() << " outside (0, 1] at node (" << x[node] << ", "
      << x[n_ + node] << ", " << x[2 * n_ + node] << ") after fluid step " << steps_
      << ": particles too large or too dense for the cells; set void_fraction "
         "smoothing_length (about 2 d; a lone sphere on a line of nodes needs 1.5 cells) or "
         "use larger cells";
    return m.str();
  }
  const Communicator& comm() const { return void_fraction_.slabs().communicator(); }
  bool several_ranks() const { return comm().size() > 1; }
  /// On several ranks the DEM's subdomains must be the flow's slabs (DemConfig::layout) and,
  /// for QCM, its ghosts must reach over a reference sphere and a particle radius.
  void check_split() const {
    if (!several_ranks()) return;
    const auto& slabs = void_fraction_.slabs();
    const auto& m = slabs.global_mesh();
    const double h = (m.upper[2] - m.lower[2]) / m.cells[2];
    const double lo = m.lower[2] + h * slabs.first_cell(), hi = m.lower[2] + h * slabs.end_cell();
    const auto& d = dem_.decomposition();
    const double dlo = d.lo(comm().rank())[2], dhi = d.hi(comm().rank())[2];
    if (std::abs(dlo - lo) > 1e-9 * h || std::abs(dhi - hi) > 1e-9 * h)
      throw std::invalid_argument(
          "cfd_dem: on several ranks the DEM's subdomains must be the flow's slabs along z "
          "(DemConfig::layout: the flow's cells, split along z only); rank " +
          std::to_string(comm().rank()) + " has z in [" + std::to_string(dlo) + ", " +
          std::to_string(dhi) + ") against the flow's [" + std::to_string(lo) + ", " +
          std::to_string(hi) + ")");
    if (options_.void_fraction.method != VoidFractionMethod::qcm) return;
    const double reach = qcm_reach();
    if (dem_.halo_width() < reach)
      throw std::invalid_argument("cfd_dem: QCM on several ranks needs the DEM's ghosts to reach " +
                                  std::to_string(reach) + " m (DemConfig::min_halo_width), not " +
                                  std::to_string(dem_.halo_width()) + " m");
  }

 public:
  /// How far QCM's reference spheres reach past a cell: their radius and a particle's.
  double qcm_reach() const {
    return qcm_reach(flow_.distributed_space().global_mesh(), options_.void_fraction,
                     dem_.config().max_radius);
  }
  static double qcm_reach(const mesh::hex::StructuredHexMesh<3>& m, const VoidFractionOptions& o,
                          double max_radius) {
    double cell = 1.0;
    for (int a = 0; a < 3; ++a) cell *= (m.upper[a] - m.lower[a]) / m.cells[a];
    const double R = o.qcm_radius > 0 ? o.qcm_radius : std::cbrt(3.0 * cell / (4.0 * M_PI));
    return R + max_radius;
  }

 private:
  void check_cfl() const {
    const double c = flow_.cfl(fluid_dt());
    if (c <= options_.max_cfl) return;
    std::ostringstream m;
    m << "cfd_dem: fluid step " << fluid_dt() << " s gives CFL " << c << " over max_cfl "
      << options_.max_cfl << " at fluid step " << steps_ << " (t = " << steps_ * fluid_dt()
      << " s): shorten the step (fewer DEM sub-steps)";
    throw StepFailure(m.str(), "velocity", -1);
  }
  /// PCM without smoothing puts a particle's volume into one cell's nodes: particles wider
  /// than a cell make eps overshoot and go negative. One line on stderr with the ratio.
  void warn_unsmoothed_large_particles() const {
    if (options_.void_fraction.method != VoidFractionMethod::pcm ||
        options_.void_fraction.smoothing_length > 0.0)
      return;
    const auto& m = flow_.space().mesh();
    double h = 1e300;
    for (int a = 0; a < 3; ++a) h = std::min(h, (m.upper[a] - m.lower[a]) / m.cells[a]);
    const double d = 2.0 * dem_.config().max_radius;
    if (d > h && comm().is_root())
      std::cerr << "cfd_dem: warning: particles of d = " << d << " are " << d / h
                << " times the smallest cell (" << h
                << ") and PCM has no smoothing; set void_fraction smoothing_length (about 2 d)\n";
  }
  void lap(int phase) {
    if (times_) times_->lap(phase);
  }

  Flow& flow_;
  Dem& dem_;
  CfdDemOptions options_;
  VoidFraction<3, ExecSpace> void_fraction_;
  long n_;
  bool model_b_;
  Vector eps_, drag_, load_;
  FluidAtParticles<Mem> at_;
  Kokkos::View<double* [3], Kokkos::LayoutRight, Mem> eps_at_;
  Vec exchange_, self_correction_;
  SelfInducedVelocity self_;
  bool started_ = false;
  long steps_ = 0;
  physics::PhaseTimes* times_ = nullptr;
};

}  // namespace amphora::coupling::cfd_dem
