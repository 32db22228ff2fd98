#pragma once
// Incompressible Navier-Stokes on equal-order continuous Q_k velocity and pressure, stabilised
// by SUPG/PSPG and grad-div (docs/ins.md): variable-step BDF2 (BDF1 for the first step), one
// linear Oseen problem per step with the advecting velocity extrapolated from the last two
// steps, or Picard iterations to a steady state. Each linear problem is solved by GMRES,
// preconditioned by a geometric multigrid V-cycle on the coupled operator (OseenMultigrid) or
// by the coupled point Jacobi; every operator is a matrix-free point functor on the device. State:
// (dim + 1) n_dofs blocked, velocity components then pressure.
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <Kokkos_Core.hpp>

#include "kernels/blas1.hpp"
#include "kernels/host_vector.hpp"
#include "mesh/hex/qk_space.hpp"
#include "physics/ins_fem/backflow_stabilisation.hpp"
#include "physics/phase_times.hpp"
#include "solvers/gmres.hpp"
#include "solvers/matrix_free/matrix_free_operator.hpp"
#include "solvers/matrix_free/oseen_multigrid.hpp"

namespace amphora::physics::ins_fem {

enum class InsPreconditioner { multigrid, jacobi };

/// The equations: incompressible Navier-Stokes, or the volume-averaged ones of unresolved
/// CFD-DEM (VANS) with a void fraction, model A or B (kernels::sumfac::VansPoint).
enum class FlowModel { navier_stokes, vans_a, vans_b };

/// VANS: how the continuity's d eps / dt is taken from the void fraction's history. bdf: the
/// velocity's BDF2. filtered: the second-order four-level difference that is blind to a
/// period-two-step alternation, (eps^(n+1) - eps^n / 2 - eps^(n-1) + eps^(n-2) / 2) / dt on
/// uniform steps (BDF2 while the history is short or the step changes): docs/cfd_dem.md.
enum class VoidFractionRate { bdf, filtered };

struct InsOptions {
  FlowModel model = FlowModel::navier_stokes;
  double nu = 0.01;       ///< kinematic viscosity
  double grad_div = 0.0;  ///< grad-div weight gamma
  /// beta of the backflow stabilisation on open (Neumann) faces (backflow_stabilisation.hpp);
  /// 0: none, the plain do-nothing condition.
  double backflow = 0.0;
  /// VANS: the continuity's -d eps / dt; false drops it (Lethe's "void fraction time
  /// derivative"), for beds that barely move: docs/cfd_dem.md.
  bool void_fraction_time_derivative = true;
  VoidFractionRate void_fraction_rate = VoidFractionRate::bdf;
  /// (2 / dt)^2 in the SUPG/PSPG parameter tau. Off by default: with it, tau ~ dt / 2 shrinks
  /// with the step and the pressure stabilisation with it (Bochev, Gunzburger & Shadid 2004,
  /// CMAME 193); the 2D Taylor-Green vortex then lost up to one order of convergence in space
  /// (tests/physics/test_ins_fem.cpp; docs/ins.md).
  bool transient_tau = false;
  double tolerance = 1e-9;  ///< GMRES: relative reduction of each step's residual
  int max_iterations = 5000;
  int restart = 60;
  InsPreconditioner preconditioner = InsPreconditioner::multigrid;
  solvers::matrix_free::OseenMultigridOptions multigrid;
  solvers::matrix_free::GeometryMode geometry = solvers::matrix_free::GeometryMode::stored;
};

/// What one step (or one Picard iteration) of the solver did.
struct InsStepReport {
  int linear_iterations = 0;
  bool converged = false;
  double residual = 0.0;  ///< final linear residual
  /// The multigrid failed to converge within one GMRES cycle and this step (and the run from
  /// here on) fell back to point Jacobi.
  bool fell_back = false;
};

/// The phases a step's time is booked to (PhaseTimes indices).
/// smoother: the V-cycles less their coarse solves (smoothing, residuals, transfers), or the
/// Jacobi preconditioner; coarse: the multigrid's coarsest level.
enum InsPhase { ins_setup = 0, ins_operator = 1, ins_smoother = 2, ins_coarse = 3, ins_other = 4 };
inline std::vector<std::string> ins_phase_names() {
  return {"setup", "operator", "smoother", "coarse solve", "other"};
}

/// An operator or preconditioner whose applications are booked to a phase (the time before
/// each, since the last lap, to ins_other).
template <class Op>
struct TimedApply {
  const Op* op;
  PhaseTimes* times;
  int phase;
  template <class E, class X, class Y>
  void apply(const E& exec, const X& x, const Y& y) const {
    if (times) times->lap(ins_other);
    op->apply(exec, x, y);
    if (times) times->lap(phase);
  }
};

/// An operator plus the backflow term of the open faces (nullptr: the operator alone).
template <class Op, class Backflow>
struct WithBackflow {
  const Op* op;
  const Backflow* backflow;
  template <class E, class X, class Y>
  void apply(const E& exec, const X& x, const Y& y) const {
    op->apply(exec, x, y);
    if (backflow) backflow->apply_add(exec, x, y);
  }
};

template <int dim, class ExecSpace>
class InsSolver {
 public:
  using Space = mesh::hex::QkSpace<dim, ExecSpace>;
  using Operator = solvers::matrix_free::MatrixFreeOperator<dim, ExecSpace>;
  using Vector = typename Operator::Vector;
  using Multigrid = solvers::matrix_free::OseenMultigrid<dim, ExecSpace>;
  using Backflow = BackflowStabilisation<dim, ExecSpace>;

  /// The pressure is fixed up to a constant where no face is Neumann (periodic or walls all
  /// round): its mean is then kept zero and each step's right-hand side made consistent.
  InsSolver(const mesh::hex::StructuredHexMesh<dim>& mesh, int degree, const InsOptions& options)
      : space_(mesh, degree), options_(options), n_(space_.n_dofs()) {
    if (!(options.nu > 0.0))
      throw std::invalid_argument("ins_fem: viscosity nu must be positive, got " +
                                  std::to_string(options.nu));
    pressure_null_space_ = true;
    for (int f = 0; f < 2 * dim; ++f)
      if (mesh.faces[f] == mesh::hex::FaceCondition::neumann) pressure_null_space_ = false;
    x_ = Vector("amphora::ins_fem::state", (dim + 1) * n_);
    u_old_ = Vector("amphora::ins_fem::u_old", dim * n_);
    field_ = Vector("amphora::ins_fem::field", (vans() ? dim + 2 : dim) * n_);
    advecting_ = Kokkos::subview(field_, Kokkos::make_pair(0L, dim * n_));
    if (vans()) make_void_fraction_fields();
    history_ = Vector("amphora::ins_fem::history", (dim + 1) * n_);
    rhs_ = Vector("amphora::ins_fem::rhs", (dim + 1) * n_);
    delta_ = Vector("amphora::ins_fem::delta", (dim + 1) * n_);
    diagonal_ = Vector("amphora::ins_fem::diagonal", (dim + 1) * n_);
    make_diagnostic_operators();
    if (options.backflow > 0.0) {
      backflow_ = std::make_unique<Backflow>(space_, options.backflow);
      if (!backflow_->active()) backflow_.reset();
    }
    if (options.preconditioner == InsPreconditioner::multigrid) {
      auto mo = options.multigrid;
      mo.field_components = vans() ? dim + 2 : dim;
      multigrid_ = std::make_unique<Multigrid>(space_, mo);
    }
  }

  /// True for the volume-averaged equations (FlowModel vans_a, vans_b).
  bool vans() const { return options_.model != FlowModel::navier_stokes; }

  /// VANS: the void fraction at the end of the next step (n_dofs nodal values, device). The
  /// first one set is also the past's (no d eps / dt at the start).
  void set_void_fraction(const Vector& eps) {
    require_vans("set_void_fraction");
    const ExecSpace exec;
    kernels::blas1::copy(exec, eps, void_fraction());
    if (!void_fraction_set_) {
      kernels::blas1::copy(exec, eps, eps_n_);
      kernels::blas1::copy(exec, eps, eps_nm1_);
      kernels::blas1::copy(exec, eps, eps_nm2_);
      void_fraction_set_ = true;
    }
  }
  /// VANS: the implicit particle drag beta (n_dofs nodal values, per unit fluid mass: the
  /// exchange force's u part is -beta u), kept until changed.
  void set_drag(const Vector& beta) {
    require_vans("set_drag");
    kernels::blas1::copy(ExecSpace(), beta, drag());
  }
  /// VANS: a load vector (dim n_dofs, already integrated against the basis: the particles'
  /// spread forces per unit fluid mass) added to every step's right-hand side until changed.
  /// Its density, load_j / (integral of phi_j), enters the SUPG/PSPG residual (as in Lethe):
  /// without it the stabilisation takes the load's balance for a residual, a mass source where
  /// the load changes (model B's packed bed lost a third of its pressure gradient).
  void set_particle_load(const Vector& load) {
    require_vans("set_particle_load");
    if (static_cast<long>(load.extent(0)) != dim * n_)
      throw std::invalid_argument("ins_fem: a particle load needs dim x n_dofs entries");
    const ExecSpace exec;
    if (particle_load_.extent(0) == 0) {
      particle_load_ = Vector("amphora::ins_fem::particle_load", dim * n_);
      load_density_ = Vector("amphora::ins_fem::load_density", (dim + 1) * n_);  // p: 0
      basis_integrals_ = Vector("amphora::ins_fem::basis_integrals", n_);
      const Vector one = Kokkos::subview(load_density_, Kokkos::make_pair(0L, n_));
      kernels::blas1::fill(exec, one, 1.0);
      scalar_mass_->apply(exec, one, basis_integrals_);
    }
    kernels::blas1::copy(exec, load, particle_load_);
    const Vector f = load_density_, m = basis_integrals_;
    const long n = n_;
    Kokkos::parallel_for(
        "amphora::ins_fem::load_density", kernels::RangePolicy<ExecSpace>(exec, 0, int(dim * n_)),
        KOKKOS_LAMBDA(int i) { f(i) = load(i) / m(i % n); });
  }
  /// VANS: the void fraction and the implicit drag the next step uses (views into the field).
  Vector void_fraction() const { return field_block(dim); }
  Vector drag() const { return field_block(dim + 1); }

  /// False once the multigrid has fallen back to Jacobi (or was never chosen); a checkpoint
  /// keeps this, so a restarted run solves as the uninterrupted one.
  bool multigrid_active() const { return multigrid_ != nullptr; }
  void disable_multigrid() { multigrid_.reset(); }
  /// The multigrid's reused smoother data (OseenMultigrid::state), for checkpoints.
  std::vector<double> preconditioner_state() const {
    return multigrid_ ? multigrid_->state() : std::vector<double>();
  }
  void set_preconditioner_state(const std::vector<double>& s) {
    if (multigrid_) multigrid_->set_state(s);
  }
  /// The multigrid's levels, or "point Jacobi".
  std::string describe_preconditioner() const {
    return multigrid_ ? multigrid_->describe() : std::string("point Jacobi");
  }

  const Space& space() const { return space_; }
  const InsOptions& options() const { return options_; }
  long n_dofs() const { return n_; }
  /// The state (velocity, pressure), blocked; Dirichlet values are those it holds on
  /// constrained velocity DoFs, kept from set_state on.
  const Vector& state() const { return x_; }
  Vector velocity() const { return Kokkos::subview(x_, Kokkos::make_pair(0L, dim * n_)); }
  Vector pressure() const {
    return Kokkos::subview(x_, Kokkos::make_pair(dim * n_, (dim + 1) * n_));
  }
  long steps() const { return steps_; }

  /// Sets the state from a host vector of (dim + 1) n_dofs entries; restarts the BDF history.
  void set_state(const std::vector<double>& state) {
    if (static_cast<long>(state.size()) != (dim + 1) * n_)
      throw std::invalid_argument("ins_fem: state needs (dim + 1) x n_dofs entries");
    Kokkos::deep_copy(x_, kernels::to_view<typename ExecSpace::memory_space>(state));
    steps_ = 0;
  }
  /// Restores the two-step history (checkpoints): state, previous velocity and step.
  void set_history(const std::vector<double>& u_old, double dt_old, long steps) {
    Kokkos::deep_copy(u_old_, kernels::to_view<typename ExecSpace::memory_space>(u_old));
    dt_old_ = dt_old, dt_older_ = dt_old, steps_ = steps;
  }
  const Vector& previous_velocity() const { return u_old_; }
  double previous_dt() const { return dt_old_; }

  /// VANS checkpoints: eps^n, eps^(n-1), eps^(n-2) (n_dofs each) and the step before the
  /// previous one, which the filtered rate's test for a uniform step reads.
  std::vector<double> void_fraction_history() const {
    std::vector<double> h;
    for (const Vector& e : {eps_n_, eps_nm1_, eps_nm2_}) {
      const auto eh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), e);
      h.insert(h.end(), eh.data(), eh.data() + eh.extent(0));
    }
    h.push_back(dt_older_);
    return h;
  }
  /// Restores void_fraction_history() after set_history; eps^n is also the void fraction now.
  void set_void_fraction_history(const std::vector<double>& h) {
    require_vans("set_void_fraction_history");
    if (h.size() != static_cast<size_t>(3 * n_ + 1))
      throw std::invalid_argument(
          "ins_fem: the void fraction's history needs 3 n_dofs + 1 entries");
    const Vector e[3] = {eps_n_, eps_nm1_, eps_nm2_};
    for (int l = 0; l < 3; ++l)
      Kokkos::deep_copy(e[l],
                        kernels::to_view<typename ExecSpace::memory_space>(
                            std::vector<double>(h.begin() + l * n_, h.begin() + (l + 1) * n_)));
    Kokkos::deep_copy(void_fraction(), eps_n_);
    void_fraction_set_ = true;
    dt_older_ = h.back();
  }

  /// A body force amplitude(t) F(x), F with dim n_dofs entries (host); set once.
  void set_force(const std::vector<double>& force) {
    force_ = kernels::to_view<typename ExecSpace::memory_space>(force);
  }

  /// Solves A delta = r for delta (zero on entry) in place of the built-in Jacobi-GMRES: the
  /// same scheme with other linear algebra (the assembled comparison of perf/ins_fem.cpp).
  using LinearSolver =
      std::function<InsStepReport(const ExecSpace&, const Operator&, const Vector&, const Vector&)>;
  void set_linear_solver(LinearSolver solver) { linear_solver_ = std::move(solver); }

  /// Books each step's time to the phases of ins_phase_names() (nullptr: no timing, no
  /// fences).
  void set_phase_times(PhaseTimes* times) {
    times_ = times;
    if (!multigrid_) return;
    if (times)
      multigrid_->set_coarse_hook(
          [times](bool entering) { times->lap(entering ? ins_smoother : ins_coarse); });
    else
      multigrid_->set_coarse_hook({});
  }

  /// One time step of length dt to time t + dt; force_amplitude scales F at t + dt.
  InsStepReport step(double dt, double force_amplitude = 0.0) {
    const ExecSpace exec;
    if (times_) times_->start();
    const bool bdf2 = steps_ > 0;
    const double w = bdf2 ? dt / dt_old_ : 0.0;  // BDF2 with variable steps
    const double a0 = bdf2 ? (1.0 + 2.0 * w) / (1.0 + w) : 1.0;
    const double a1 = bdf2 ? -(1.0 + w) : -1.0, a2 = bdf2 ? w * w / (1.0 + w) : 0.0;
    const Vector u = velocity();
    extrapolate(exec, u, bdf2 ? w : 0.0);
    update_backflow(exec);
    form_history(exec, u, -a1 / dt, -a2 / dt, force_amplitude);
    if (vans() && options_.void_fraction_time_derivative)
      void_fraction_rate(exec, rate_coefficients(dt, a0, a1, a2));
    typename Operator::Options o = oseen_options(a0 / dt, 1.0 / dt);
    const Operator& A = renew(a_, o);
    o.history = true;
    const Operator& H = renew(h_, o);
    H.apply(exec, history_, rhs_);
    add_particle_load(exec, o);
    kernels::blas1::copy(exec, u, u_old_);  // u^(n-1) <- u^n; the guess: extrapolated velocity
    kernels::blas1::copy(exec, advecting_, u);
    const InsStepReport report = solve(exec, A);
    if (vans()) {  // eps^(n-2) <- eps^(n-1) <- eps^n <- eps^(n+1); only the filter reads n-2
      if (options_.void_fraction_rate == VoidFractionRate::filtered)
        kernels::blas1::copy(exec, eps_nm1_, eps_nm2_);
      kernels::blas1::copy(exec, eps_n_, eps_nm1_);
      kernels::blas1::copy(exec, void_fraction(), eps_n_);
    }
    dt_older_ = dt_old_, dt_old_ = dt;
    ++steps_;
    return report;
  }

  /// Picard iterations to the steady state from the current state (force F at
  /// force_amplitude): stops when the velocity changes by less than `tolerance` relative to its
  /// norm. Restarts the BDF history.
  InsStepReport solve_steady(double tolerance, int max_picard, int* picard = nullptr,
                             double force_amplitude = 1.0) {
    steps_ = 0;
    const ExecSpace exec;
    InsStepReport total;
    const Vector u = velocity();
    for (int it = 0; it < max_picard; ++it) {
      kernels::blas1::copy(exec, u, advecting_);
      update_backflow(exec);
      form_history(exec, u, 0.0, 0.0, force_amplitude);
      typename Operator::Options o = oseen_options(0.0, 0.0);
      const Operator& A = renew(a_, o);
      o.history = true;
      const Operator& H = renew(h_, o);
      H.apply(exec, history_, rhs_);
      add_particle_load(exec, o);
      const InsStepReport r = solve(exec, A);
      total.linear_iterations += r.linear_iterations;
      total.residual = r.residual;
      kernels::blas1::axpy(exec, -1.0, u, advecting_);  // advecting <- u_old - u_new
      const double change = kernels::blas1::norm2(exec, advecting_);
      const double size = kernels::blas1::norm2(exec, u);
      if (picard) *picard = it + 1;
      if (!r.converged) return total;
      if (change <= tolerance * size) {
        total.converged = true;
        return total;
      }
    }
    return total;
  }

  // Diagnostics, as integrals over the domain divided by its volume.

  /// E_k = 1 / |Omega| int |u|^2 / 2.
  double kinetic_energy() const { return 0.5 * quadratic(*mass_) / volume_; }
  /// nu / |Omega| int |grad u|^2: -dE_k/dt for periodic or no-slip flows, and 2 nu times the
  /// enstrophy (int |omega|^2 / 2 / |Omega|) where the velocity is divergence-free.
  double viscous_dissipation() const { return options_.nu * quadratic(*laplace_) / volume_; }
  /// (1 / |Omega| int (div u)^2)^(1/2).
  double divergence_rms() const { return std::sqrt(std::max(0.0, quadratic(*div_) / volume_)); }
  double volume() const { return volume_; }
  /// max over nodes of |u|.
  double max_speed() const {
    const long n = n_;
    const Vector x = x_;
    double m = 0.0;
    Kokkos::parallel_reduce(
        "amphora::ins_fem::max_speed",
        kernels::RangePolicy<ExecSpace>(ExecSpace(), 0, static_cast<int>(n)),
        KOKKOS_LAMBDA(int i, double& acc) {
          double s = 0.0;
          for (int d = 0; d < dim; ++d) s += x(d * n + i) * x(d * n + i);
          if (s > acc) acc = s;
        },
        Kokkos::Max<double>(m));
    return std::sqrt(m);
  }
  /// Convective CFL number of step dt: dt max|u| k / h_min (h_min: the smallest cell width of
  /// the undeformed box).
  double cfl(double dt) const {
    const auto& m = space_.mesh();
    double h = 1e300;
    for (int d = 0; d < dim; ++d) h = std::min(h, (m.upper[d] - m.lower[d]) / m.cells[d]);
    return dt * max_speed() * space_.degree() / h;
  }

  // (public for CUDA: extended lambdas may not live in private member functions)

  /// The backflow term's coefficients from the advecting velocity (and the void fraction).
  void update_backflow(const ExecSpace& exec) {
    if (backflow_) backflow_->update(exec, advecting_, vans() ? void_fraction() : Vector());
  }
  /// The backflow term, or nullptr where there is none (no open face, or beta = 0).
  const Backflow* backflow() const { return backflow_.get(); }

  /// The advecting velocity (1 + w) u^n - w u^(n-1) (w = 0: u^n).
  void extrapolate(const ExecSpace& exec, const Vector& u, double w) {
    kernels::blas1::copy(exec, u, advecting_);
    if (w != 0.0) kernels::blas1::axpby(exec, -w, u_old_, 1.0 + w, advecting_);
  }
  /// d eps / dt ~ c[0] eps^(n+1) + c[1] eps^n + c[2] eps^(n-1) + c[3] eps^(n-2) for a step dt
  /// whose BDF weights are a0..a2 (VoidFractionRate).
  std::array<double, 4> rate_coefficients(double dt, double a0, double a1, double a2) const {
    const bool uniform = steps_ >= 3 && std::abs(dt - dt_old_) <= 1e-12 * dt &&
                         std::abs(dt - dt_older_) <= 1e-12 * dt;
    if (options_.void_fraction_rate == VoidFractionRate::filtered && uniform)
      return {1.0 / dt, -0.5 / dt, -1.0 / dt, 0.5 / dt};
    return {a0 / dt, a1 / dt, a2 / dt, 0.0};
  }
  /// VANS: the continuity's source -d eps / dt (the rate_coefficients c) into the pressure
  /// slot of the history.
  void void_fraction_rate(const ExecSpace& exec, const std::array<double, 4>& c) {
    const Vector hp = Kokkos::subview(history_, Kokkos::make_pair(dim * n_, (dim + 1) * n_));
    const Vector e = void_fraction(), en = eps_n_, enm1 = eps_nm1_, enm2 = eps_nm2_;
    const double c0 = c[0], c1 = c[1], c2 = c[2], c3 = c[3];
    Kokkos::parallel_for(
        "amphora::ins_fem::void_fraction_rate",
        kernels::RangePolicy<ExecSpace>(exec, 0, static_cast<int>(n_)),
        KOKKOS_LAMBDA(int i) { hp(i) = -(c0 * e(i) + c1 * en(i) + c2 * enm1(i) + c3 * enm2(i)); });
  }
  /// rhs += the particles' load and its density's stabilisation terms (VANS, where one is
  /// set); o: the step's history options.
  void add_particle_load(const ExecSpace& exec, typename Operator::Options o) {
    if (particle_load_.extent(0) == 0) return;
    const Vector ru = Kokkos::subview(rhs_, Kokkos::make_pair(0L, dim * n_));
    kernels::blas1::axpy(exec, 1.0, particle_load_, ru);
    o.load_only = true;
    const Operator& S = renew(s_, o);
    S.apply(exec, load_density_, work_);
    kernels::blas1::axpy(exec, 1.0, work_, rhs_);
  }
  /// history = (c1 u^n + c2 u^(n-1) + s F, 0).
  void form_history(const ExecSpace& exec, const Vector& u, double c1, double c2, double s) {
    const Vector h = history_, uo = u_old_, f = force_;
    const bool force = f.extent(0) > 0 && s != 0.0;
    const long nu = dim * n_;
    Kokkos::parallel_for(
        "amphora::ins_fem::history",
        kernels::RangePolicy<ExecSpace>(exec, 0, static_cast<int>(h.extent(0))),
        KOKKOS_LAMBDA(int i) {
          h(i) =
              i < nu ? c1 * u(i) + (c2 != 0.0 ? c2 * uo(i) : 0.0) + (force ? s * f(i) : 0.0) : 0.0;
        });
  }

  /// The step operator in `slot` rebuilt for options o in the device arrays of the one it
  /// replaces (the flow's operators change coefficients each step, not size).
  const Operator& renew(std::unique_ptr<Operator>& slot, const typename Operator::Options& o) {
    slot = slot ? std::make_unique<Operator>(space_, o, std::move(*slot))
                : std::make_unique<Operator>(space_, o);
    return *slot;
  }

  typename Operator::Options oseen_options(double alpha, double dt_inverse) const {
    typename Operator::Options o;
    o.kind = vans() ? solvers::matrix_free::OperatorKind::vans
                    : solvers::matrix_free::OperatorKind::oseen;
    o.model_b = options_.model == FlowModel::vans_b;
    o.geometry = options_.geometry;
    o.components = dim + 1;
    o.nu = options_.nu, o.alpha = alpha, o.grad_div = options_.grad_div;
    o.dt_inverse = options_.transient_tau ? dt_inverse : 0.0;
    o.field = field_;
    return o;
  }

  /// x += the solution of A delta = rhs - A x (zero on constrained DoFs), by Jacobi-GMRES.
  InsStepReport solve(const ExecSpace& exec, const Operator& A) {
    // The correction's residual cannot fall much below the round-off of A x ~ rhs: with a
    // small step the extrapolated guess is so good that tolerance |rhs - A x| lies below it.
    A.apply_unconstrained(exec, x_, delta_);  // with the Dirichlet values x holds
    if (backflow_) backflow_->apply_add(exec, x_, delta_);
    const double floor =
        1e-12 * std::max(kernels::blas1::norm2(exec, rhs_), kernels::blas1::norm2(exec, delta_));
    kernels::blas1::axpby(exec, 1.0, rhs_, -1.0, delta_);  // delta = rhs - A x
    zero_constrained(exec, delta_);
    if (pressure_null_space_) remove_pressure_mean(exec, delta_, false);
    kernels::blas1::copy(exec, delta_, rhs_);
    if (linear_solver_) {
      if (backflow_)
        throw std::invalid_argument("ins_fem: an external linear solver has no backflow term");
      kernels::blas1::fill(exec, delta_, 0.0);
      const InsStepReport r = linear_solver_(exec, A, rhs_, delta_);
      kernels::blas1::axpy(exec, 1.0, delta_, x_);
      if (pressure_null_space_) remove_pressure_mean(exec, x_, true);
      return r;
    }
    solvers::SolverControl control;
    control.relative_tolerance = options_.tolerance;
    control.max_iterations = options_.max_iterations;
    control.absolute_tolerance = floor;
    kernels::blas1::fill(exec, delta_, 0.0);
    const WithBackflow<Operator, Backflow> full{&A, backflow_.get()};
    const TimedApply<WithBackflow<Operator, Backflow>> timed_a{&full, times_, ins_operator};
    solvers::SolverResult r;
    bool fell_back = false;
    if (multigrid_) {
      multigrid_->update(exec, A);
      if (times_) times_->lap(ins_setup);
      // Point-Jacobi smoothing fails where viscosity dominates the cells (docs/ins.md): one
      // restart cycle without convergence hands this step and the rest of the run to Jacobi.
      solvers::SolverControl first = control;
      first.max_iterations = std::min(control.max_iterations, options_.restart);
      const TimedApply<Multigrid> timed_m{multigrid_.get(), times_, ins_smoother};
      r = solvers::gmres(exec, timed_a, rhs_, delta_, first, options_.restart, timed_m,
                         solvers::LocalInnerProduct(), gmres_work_);
      if (!r.converged) {
        multigrid_.reset();
        kernels::blas1::fill(exec, delta_, 0.0);
        fell_back = true;
      }
    }
    if (!multigrid_) {
      A.compute_diagonal(exec, diagonal_);
      if (backflow_) backflow_->add_diagonal(exec, diagonal_);
      kernels::blas1::reciprocal(exec, diagonal_);
      const solvers::JacobiPreconditioner<Vector> jacobi{diagonal_};
      if (times_) times_->lap(ins_setup);
      const TimedApply<solvers::JacobiPreconditioner<Vector>> timed_m{&jacobi, times_,
                                                                      ins_smoother};
      const int spent = r.iterations;
      r = solvers::gmres(exec, timed_a, rhs_, delta_, control, options_.restart, timed_m,
                         solvers::LocalInnerProduct(), gmres_work_);
      r.iterations += spent;
    }
    kernels::blas1::axpy(exec, 1.0, delta_, x_);
    if (pressure_null_space_) remove_pressure_mean(exec, x_, true);
    if (times_) times_->lap(ins_other);
    return {r.iterations, r.converged, r.final_residual, fell_back};
  }

  /// Zeroes the velocity entries of v at the constrained DoFs.
  void zero_constrained(const ExecSpace& exec, const Vector& v) const {
    const auto cons = space_.constrained_dofs();
    const long n = n_;
    const int nc = static_cast<int>(cons.extent(0));
    Kokkos::parallel_for(
        "amphora::ins_fem::zero_constrained", kernels::RangePolicy<ExecSpace>(exec, 0, dim * nc),
        KOKKOS_LAMBDA(int m) { v((m / nc) * n + cons(m % nc)) = 0.0; });
  }

  /// Subtracts from the pressure block of v its mean: the integral mean (mass-weighted, for a
  /// state) or the plain mean (a residual: orthogonal to the constant the operator annihilates).
  void remove_pressure_mean(const ExecSpace& exec, const Vector& v, bool weighted) const {
    const Vector p = Kokkos::subview(v, Kokkos::make_pair(dim * n_, (dim + 1) * n_));
    double mean = 0.0;
    if (weighted) {
      const Vector pm = Kokkos::subview(delta_, Kokkos::make_pair(0L, n_));
      scalar_mass_->apply(exec, p, pm);
      mean = kernels::blas1::sum(exec, pm) / volume_;
    } else {
      mean = kernels::blas1::sum(exec, p) / static_cast<double>(n_);
    }
    Kokkos::parallel_for(
        "amphora::ins_fem::pressure_mean",
        kernels::RangePolicy<ExecSpace>(exec, 0, static_cast<int>(n_)),
        KOKKOS_LAMBDA(int i) { p(i) -= mean; });
  }

  /// u . (B u) for a diagnostic operator B on the velocity (dim components).
  double quadratic(const Operator& B) const {
    const ExecSpace exec;
    const Vector u = velocity();
    const Vector bu = Kokkos::subview(work_, Kokkos::make_pair(0L, dim * n_));
    B.apply(exec, u, bu);
    return kernels::blas1::dot(exec, u, bu);
  }

 private:
  Vector field_block(int c) const {
    return Kokkos::subview(field_, Kokkos::make_pair(c * n_, (c + 1) * n_));
  }
  void require_vans(const char* what) const {
    if (!vans())
      throw std::invalid_argument(std::string("ins_fem: ") + what +
                                  " needs the volume-averaged equations (model vans_a or vans_b)");
  }
  /// eps = 1 and beta = 0 (clear fluid) until set, the void fraction's past with them.
  void make_void_fraction_fields() {
    const ExecSpace exec;
    eps_n_ = Vector("amphora::ins_fem::eps_n", n_);
    eps_nm1_ = Vector("amphora::ins_fem::eps_nm1", n_);
    eps_nm2_ = Vector("amphora::ins_fem::eps_nm2", n_);
    kernels::blas1::fill(exec, void_fraction(), 1.0);
    kernels::blas1::fill(exec, eps_n_, 1.0);
    kernels::blas1::fill(exec, eps_nm1_, 1.0);
    kernels::blas1::fill(exec, eps_nm2_, 1.0);
  }

  void make_diagnostic_operators() {
    typename Operator::Options o;
    o.geometry = options_.geometry;
    o.components = dim;
    o.constrained_components = 0;  // integrals over every node, boundary included
    o.kind = solvers::matrix_free::OperatorKind::mass;
    mass_ = std::make_unique<Operator>(space_, o);
    o.kind = solvers::matrix_free::OperatorKind::laplace;
    laplace_ = std::make_unique<Operator>(space_, o);
    o.kind = solvers::matrix_free::OperatorKind::elasticity;  // lambda div div, mu = 0
    o.lambda = 1.0, o.mu = 0.0;
    div_ = std::make_unique<Operator>(space_, o);
    o = typename Operator::Options();
    o.kind = solvers::matrix_free::OperatorKind::mass;
    o.geometry = options_.geometry;
    o.constrained_components = 0;
    scalar_mass_ = std::make_unique<Operator>(space_, o);
    work_ = Vector("amphora::ins_fem::work", (dim + 1) * n_);
    const ExecSpace exec;
    const Vector one = Kokkos::subview(work_, Kokkos::make_pair(0L, n_));
    const Vector m1 = Kokkos::subview(work_, Kokkos::make_pair(n_, 2 * n_));
    kernels::blas1::fill(exec, one, 1.0);
    scalar_mass_->apply(exec, one, m1);
    volume_ = kernels::blas1::sum(exec, m1);
  }

  Space space_;
  InsOptions options_;
  long n_;
  bool pressure_null_space_ = true;
  Vector x_, u_old_, field_, history_, rhs_, delta_, diagonal_, force_, work_;
  Vector advecting_;  // the field's first dim blocks
  Vector eps_n_, eps_nm1_, eps_nm2_, particle_load_, load_density_, basis_integrals_;  // VANS
  bool void_fraction_set_ = false;
  std::unique_ptr<Operator> mass_, laplace_, div_, scalar_mass_;
  std::unique_ptr<Operator> a_, h_, s_;         // the step's operator, history and load terms
  solvers::GmresWorkspace<Vector> gmres_work_;  // kept: no allocation inside a step
  double volume_ = 0.0, dt_old_ = 0.0, dt_older_ = 0.0;
  long steps_ = 0;
  PhaseTimes* times_ = nullptr;
  LinearSolver linear_solver_;
  std::unique_ptr<Multigrid> multigrid_;
  std::unique_ptr<Backflow> backflow_;
};

}  // namespace amphora::physics::ins_fem
