#pragma once
// Incompressible Navier-Stokes on equal-order continuous Q_k velocity and pressure, stabilised
// by SUPG/PSPG and grad-div (docs/ins.md): variable-step BDF2 (BDF1 for the first step), one
// linear Oseen problem per step with the advecting velocity extrapolated from the last two
// steps, or Picard iterations to a steady state. Each linear problem is solved by GMRES,
// preconditioned by a geometric multigrid V-cycle on the coupled operator (OseenMultigrid) or
// by the coupled point Jacobi; every operator is a matrix-free point functor on the device. State:
// (dim + 1) n_dofs blocked, velocity components then pressure. On several ranks each holds the
// slab of a DistributedQkSpace: vectors are its local entries (owned, then the ghost layer,
// which the state keeps equal to the owners' values) and every reduction is over the ranks.
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
#include "base/communicator.hpp"
#include "mesh/hex/distributed_qk_space.hpp"
#include "mesh/hex/qk_space.hpp"
#include "physics/ins_fem/backflow_stabilisation.hpp"
#include "physics/ins_fem/ins_options.hpp"
#include "physics/ins_fem/step_operators.hpp"
#include "physics/phase_times.hpp"
#include "solvers/gmres.hpp"
#include "solvers/matrix_free/distributed_operator.hpp"
#include "solvers/matrix_free/matrix_free_operator.hpp"
#include "solvers/matrix_free/oseen_multigrid.hpp"

namespace amphora::physics::ins_fem {

template <int dim, class ExecSpace>
class InsSolver {
 public:
  using Space = mesh::hex::QkSpace<dim, ExecSpace>;
  using DistributedSpace = mesh::hex::DistributedQkSpace<dim, ExecSpace>;
  using Operator = solvers::matrix_free::MatrixFreeOperator<dim, ExecSpace>;
  using DistributedOperator = solvers::matrix_free::DistributedOperator<dim, ExecSpace>;
  using Vector = typename Operator::Vector;
  using Multigrid = solvers::matrix_free::OseenMultigrid<dim, ExecSpace>;
  using Backflow = BackflowStabilisation<dim, ExecSpace>;
  static constexpr int dimension = dim;

  /// The pressure is fixed up to a constant where no face is Neumann (periodic or walls all
  /// round): its mean is then kept zero and each step's right-hand side made consistent.
  /// `comm`: the ranks the box is split over (slabs along the last direction).
  InsSolver(const mesh::hex::StructuredHexMesh<dim>& mesh, int degree, const InsOptions& options,
            const Communicator& comm = Communicator(MPI_COMM_SELF))
      : distributed_(mesh, degree, comm),
        space_(distributed_.local()),
        options_(options),
        n_(space_.n_dofs()),
        n_owned_(distributed_.n_owned()),
        n_global_(distributed_.n_global()) {
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
      multigrid_ = std::make_unique<Multigrid>(distributed_, mo);
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
    distributed_.update_ghosts(exec, void_fraction());
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
    distributed_.update_ghosts(ExecSpace(), drag());
  }
  /// VANS: a load vector (dim n_dofs, already integrated against the basis: the particles'
  /// spread forces per unit fluid mass; on several ranks its owned entries summed over them)
  /// added to every step's right-hand side until changed.
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
      apply_on_slabs(exec, *scalar_mass_, one, basis_integrals_);
      distributed_.update_ghosts(exec, basis_integrals_);
    }
    kernels::blas1::copy(exec, load, particle_load_);
    const Vector f = load_density_, m = basis_integrals_;
    const long n = n_;
    Kokkos::parallel_for(
        "amphora::ins_fem::load_density", kernels::RangePolicy<ExecSpace>(exec, 0, int(dim * n_)),
        KOKKOS_LAMBDA(int i) { f(i) = load(i) / m(i % n); });
    distributed_.update_ghosts(exec, load_density_, dim + 1);
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

  /// This rank's slab (the whole box on one rank).
  const Space& space() const { return space_; }
  const DistributedSpace& distributed_space() const { return distributed_; }
  const InsOptions& options() const { return options_; }
  /// DoFs per component of this rank's slab (owned and ghost layer).
  long n_dofs() const { return n_; }
  /// DoFs per component of the whole box.
  long n_global_dofs() const { return n_global_; }
  /// The state (velocity, pressure), blocked; Dirichlet values are those it holds on
  /// constrained velocity DoFs, kept from set_state on.
  const Vector& state() const { return x_; }
  Vector velocity() const { return Kokkos::subview(x_, Kokkos::make_pair(0L, dim * n_)); }
  Vector pressure() const {
    return Kokkos::subview(x_, Kokkos::make_pair(dim * n_, (dim + 1) * n_));
  }
  long steps() const { return steps_; }

  /// Sets the state from a host vector of (dim + 1) n_dofs entries (this rank's; the ghost
  /// layer is taken from the owners); restarts the BDF history.
  void set_state(const std::vector<double>& state) {
    if (static_cast<long>(state.size()) != (dim + 1) * n_)
      throw std::invalid_argument("ins_fem: state needs (dim + 1) x n_dofs entries");
    Kokkos::deep_copy(x_, kernels::to_view<typename ExecSpace::memory_space>(state));
    distributed_.update_ghosts(ExecSpace(), x_, dim + 1);
    steps_ = 0;
  }
  /// Restores the two-step history (checkpoints): state, previous velocity and step.
  void set_history(const std::vector<double>& u_old, double dt_old, long steps) {
    Kokkos::deep_copy(u_old_, kernels::to_view<typename ExecSpace::memory_space>(u_old));
    distributed_.update_ghosts(ExecSpace(), u_old_, dim);
    dt_old_ = dt_old, dt_older_ = dt_old, steps_ = steps;
  }
  const Vector& previous_velocity() const { return u_old_; }
  double previous_dt() const { return dt_old_; }

  /// VANS checkpoints: eps^n, eps^(n-1), eps^(n-2) (the whole box's n_global_dofs each, in
  /// global DoF order) and the step before the previous one, which the filtered rate's test
  /// for a uniform step reads. Collective.
  std::vector<double> void_fraction_history() const {
    std::vector<double> h;
    for (const Vector& e : {eps_n_, eps_nm1_, eps_nm2_}) {
      const std::vector<double> g = distributed_.gather(e);
      h.insert(h.end(), g.begin(), g.end());
    }
    h.push_back(dt_older_);
    return h;
  }
  /// Restores void_fraction_history() after set_history; eps^n is also the void fraction now.
  void set_void_fraction_history(const std::vector<double>& h) {
    require_vans("set_void_fraction_history");
    const long ng = n_global_;
    if (h.size() != static_cast<size_t>(3 * ng + 1))
      throw std::invalid_argument(
          "ins_fem: the void fraction's history needs 3 n_dofs + 1 entries");
    const Vector e[3] = {eps_n_, eps_nm1_, eps_nm2_};
    for (int l = 0; l < 3; ++l)
      distributed_.scatter(std::vector<double>(h.begin() + l * ng, h.begin() + (l + 1) * ng), e[l]);
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
    apply_on_slabs(exec, H, history_, rhs_);
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
      apply_on_slabs(exec, H, history_, rhs_);
      add_particle_load(exec, o);
      const InsStepReport r = solve(exec, A);
      total.linear_iterations += r.linear_iterations;
      total.residual = r.residual;
      kernels::blas1::axpy(exec, -1.0, u, advecting_);  // advecting <- u_old - u_new
      const double change = norm(exec, advecting_, dim);
      const double size = norm(exec, u, dim);
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
        kernels::RangePolicy<ExecSpace>(ExecSpace(), 0, static_cast<int>(n_owned_)),
        KOKKOS_LAMBDA(int i, double& acc) {
          double s = 0.0;
          for (int d = 0; d < dim; ++d) s += x(d * n + i) * x(d * n + i);
          if (s > acc) acc = s;
        },
        Kokkos::Max<double>(m));
    return std::sqrt(distributed_.communicator().max(m));
  }
  /// Convective CFL number of step dt: dt max|u| k / h_min (h_min: the smallest cell width of
  /// the undeformed box).
  double cfl(double dt) const {
    const auto& m = distributed_.global_mesh();
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
    apply_on_slabs(exec, S, load_density_, work_);
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
  /// The same for the step's Oseen operator, which the multigrid takes as a distributed one
  /// (and keeps for its finest level); returns its slab operator.
  const Operator& renew(std::unique_ptr<DistributedOperator>& slot,
                        const typename Operator::Options& o) {
    slot = slot ? std::make_unique<DistributedOperator>(distributed_, o, std::move(*slot))
                : std::make_unique<DistributedOperator>(distributed_, o);
    return slot->local();
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
    distributed_.compress_add(exec, delta_, dim + 1, 0);
    const double floor = 1e-12 * std::max(norm(exec, rhs_, dim + 1), norm(exec, delta_, dim + 1));
    kernels::blas1::axpby(exec, 1.0, rhs_, -1.0, delta_);  // delta = rhs - A x
    zero_constrained(exec, delta_);
    if (pressure_null_space_) remove_pressure_mean(exec, delta_, false);
    kernels::blas1::copy(exec, delta_, rhs_);
    if (linear_solver_) {
      if (distributed_.communicator().size() > 1)
        throw std::invalid_argument("ins_fem: an external linear solver runs on one rank only");
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
    using Full = WithBackflow<DistributedSpace, Operator, Backflow>;
    const Full full{&distributed_, &A, backflow_.get()};
    const TimedApply<Full> timed_a{&full, times_, ins_operator};
    const auto inner = distributed_.inner_product(dim + 1);
    solvers::SolverResult r;
    bool fell_back = false;
    if (multigrid_) {
      multigrid_->update(exec, *a_);  // A is a_'s slab operator
      if (times_) times_->lap(ins_setup);
      // Point-Jacobi smoothing fails where viscosity dominates the cells (docs/ins.md): one
      // restart cycle without convergence hands this step and the rest of the run to Jacobi.
      solvers::SolverControl first = control;
      first.max_iterations = std::min(control.max_iterations, options_.restart);
      const TimedApply<Multigrid> timed_m{multigrid_.get(), times_, ins_smoother};
      r = solvers::gmres(exec, timed_a, rhs_, delta_, first, options_.restart, timed_m, inner,
                         gmres_work_);
      if (!r.converged) {
        multigrid_.reset();
        kernels::blas1::fill(exec, delta_, 0.0);
        fell_back = true;
      }
    }
    if (!multigrid_) {
      A.compute_diagonal(exec, diagonal_);
      if (backflow_) backflow_->add_diagonal(exec, diagonal_);
      distributed_.compress_add(exec, diagonal_, dim + 1, dim);
      distributed_.update_ghosts(exec, diagonal_, dim + 1);
      kernels::blas1::reciprocal(exec, diagonal_);
      const solvers::JacobiPreconditioner<Vector> jacobi{diagonal_};
      if (times_) times_->lap(ins_setup);
      const TimedApply<solvers::JacobiPreconditioner<Vector>> timed_m{&jacobi, times_,
                                                                      ins_smoother};
      const int spent = r.iterations;
      r = solvers::gmres(exec, timed_a, rhs_, delta_, control, options_.restart, timed_m, inner,
                         gmres_work_);
      r.iterations += spent;
    }
    kernels::blas1::axpy(exec, 1.0, delta_, x_);
    distributed_.update_ghosts(exec, x_, dim + 1);  // delta's ghost layer is not meaningful
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
      apply_on_slabs(exec, *scalar_mass_, p, pm);
      mean = owned_sum(exec, pm) / volume_;
    } else {
      mean = owned_sum(exec, p) / static_cast<double>(n_global_);
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
    apply_on_slabs(exec, B, u, bu);
    return distributed_.dot(exec, u, bu, dim);
  }

  /// y = B x over the ranks (the step operator without a backflow term).
  void apply_on_slabs(const ExecSpace& exec, const Operator& B, const Vector& x,
                      const Vector& y) const {
    WithBackflow<DistributedSpace, Operator, Backflow>{&distributed_, &B, nullptr}.apply(exec, x,
                                                                                         y);
  }
  /// The sum over the ranks of v's owned entries (one component).
  double owned_sum(const ExecSpace& exec, const Vector& v) const {
    const Vector owned = Kokkos::subview(v, Kokkos::make_pair(0L, n_owned_));
    return distributed_.communicator().sum(kernels::blas1::sum(exec, owned));
  }
  /// |v| over the ranks' owned entries of `components` blocks.
  double norm(const ExecSpace& exec, const Vector& v, int components) const {
    return std::sqrt(distributed_.dot(exec, v, v, components));
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
    apply_on_slabs(exec, *scalar_mass_, one, m1);
    volume_ = owned_sum(exec, m1);
  }

  DistributedSpace distributed_;
  const Space& space_;
  InsOptions options_;
  long n_, n_owned_, n_global_;  // DoFs per component: local, owned, of the whole box
  bool pressure_null_space_ = true;
  Vector x_, u_old_, field_, history_, rhs_, delta_, diagonal_, force_, work_;
  Vector advecting_;  // the field's first dim blocks
  Vector eps_n_, eps_nm1_, eps_nm2_, particle_load_, load_density_, basis_integrals_;  // VANS
  bool void_fraction_set_ = false;
  std::unique_ptr<Operator> mass_, laplace_, div_, scalar_mass_;
  std::unique_ptr<DistributedOperator> a_;      // the step's operator
  std::unique_ptr<Operator> h_, s_;             // its history and load terms
  solvers::GmresWorkspace<Vector> gmres_work_;  // kept: no allocation inside a step
  double volume_ = 0.0, dt_old_ = 0.0, dt_older_ = 0.0;
  long steps_ = 0;
  PhaseTimes* times_ = nullptr;
  LinearSolver linear_solver_;
  std::unique_ptr<Multigrid> multigrid_;
  std::unique_ptr<Backflow> backflow_;
};

}  // namespace amphora::physics::ins_fem
