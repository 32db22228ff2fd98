#include "physics/ins_fem/ins_module.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

#include "physics/ins_fem/flow_checkpoint.hpp"
#include "physics/ins_fem/flow_failure.hpp"
#include "physics/ins_fem/flow_output.hpp"
#include "physics/ins_fem/flow_error_norms.hpp"
#include "physics/ins_fem/flow_solutions.hpp"
#include "physics/ins_fem/ins_solver.hpp"
#include "solvers/matrix_free/degree_dispatch.hpp"
#include "solvers/matrix_free/error_norms.hpp"

namespace amphora::physics::ins_fem {
// A named namespace, not an anonymous one: CUDA does not support extended lambdas in
// anonymous namespaces (Kokkos issue #1547).
namespace ins_module_detail {

constexpr double pi = kernels::math::pi;

/// The box, its faces and whether the flow is steady, for each case.
template <int dim>
mesh::hex::StructuredHexMesh<dim> case_mesh(const std::string& flow, int cells, double amplitude) {
  mesh::hex::StructuredHexMesh<dim> m;
  for (int d = 0; d < dim; ++d) m.cells[d] = cells;
  if (flow == "taylor_green_2d" || flow == "taylor_green_3d") {
    const double lo = flow == "taylor_green_2d" ? 0.0 : -pi;
    for (int d = 0; d < dim; ++d) m.lower[d] = lo, m.upper[d] = lo + 2.0 * pi;
    for (int f = 0; f < 2 * dim; ++f) m.faces[f] = mesh::hex::FaceCondition::periodic;
  } else if (flow == "kovasznay") {
    m.lower = {-0.5, 0.0, 0.0};
    m.upper = {1.5, 2.0, 0.0};
  } else if (flow == "channel") {  // [0, 2] x [0, 1]: inflow at x = 0, outflow at x = 2
    m.cells[0] = 2 * cells;
    m.upper = {2.0, 1.0, 0.0};
    m.faces[1] = mesh::hex::FaceCondition::neumann;
  }  // lid_cavity: the unit square, walls (the default faces)
  if (amplitude > 0.0)
    m.deformation = mesh::hex::sinusoidal_deformation(dim, amplitude, m.lower, m.upper);
  return m;
}

template <int dim>
class InsModule final : public Module {
 public:
  using Exec = kernels::DefaultExecSpace;
  using Solver = InsSolver<dim, Exec>;
  using Vector = typename Solver::Vector;

  /// On several ranks the box is split into slabs along its last direction (InsSolver).
  InsModule(const Parameters& p, const Communicator& comm) : flow_(p.string("flow")), comm_(comm) {
    InsOptions o;
    o.nu = p.real("nu");
    o.grad_div = p.real("grad_div");
    o.transient_tau = p.string("tau") == "transient";
    o.backflow = p.real("backflow");
    o.tolerance = p.real("tolerance");
    o.max_iterations = static_cast<int>(p.integer("max_iterations"));
    o.restart = static_cast<int>(p.integer("restart"));
    o.multigrid.smoother.degree = static_cast<int>(p.integer("smoothing_degree"));
    o.multigrid.refresh_every = static_cast<int>(p.integer("multigrid_refresh"));
    o.multigrid.viscous_residual = p.boolean("multigrid_viscous_residual");
    o.preconditioner = p.string("preconditioner") == "jacobi" ? InsPreconditioner::jacobi
                                                              : InsPreconditioner::multigrid;
    o.geometry = p.string("geometry") == "on_the_fly"
                     ? solvers::matrix_free::GeometryMode::on_the_fly
                     : solvers::matrix_free::GeometryMode::stored;
    max_cfl_ = p.real("max_cfl");
    steady_ = flow_ == "kovasznay" || flow_ == "channel";
    solver_ = std::make_unique<Solver>(
        case_mesh<dim>(flow_, static_cast<int>(p.integer("cells")), p.real("deformation")),
        static_cast<int>(p.integer("degree")), o, comm);
    solver_->set_state(initial_state());
    solver_->set_phase_times(&times_);
    energy_ = solver_->kinetic_energy();
  }

  /// The initial state: the exact flow (Taylor-Green), its boundary values and rest
  /// (Kovasznay; the channel's inflow), rest with the lid's velocity on the top wall (cavity).
  /// This rank's entries.
  std::vector<double> initial_state() const {
    const auto& s = solver_->space();
    const auto& box = solver_->distributed_space().global_mesh();
    const double re = 1.0 / solver_->options().nu;
    return s.interpolate(
        [&](const mesh::hex::Point3& x, int c) {
          if (flow_ == "taylor_green_2d") return TaylorGreen2D{c, 1.0}.value(x.data());
          if (flow_ == "taylor_green_3d") return TaylorGreen3D{c}.value(x.data());
          const bool boundary = x[0] <= box.lower[0] + 1e-12 || x[0] >= box.upper[0] - 1e-12 ||
                                x[1] <= box.lower[1] + 1e-12 || x[1] >= box.upper[1] - 1e-12;
          if (!boundary || c == dim) return 0.0;
          if (flow_ == "kovasznay") return Kovasznay{c, re}.value(x.data());
          if (flow_ == "channel") return Poiseuille{c, 1.0 / re, 2.0}.value(x.data());
          // the regularised lid: u = 16 x^2 (1 - x)^2 on y = 1 (no corner singularity)
          const bool lid = x[1] >= box.upper[1] - 1e-12;
          return lid && c == 0 ? 16.0 * x[0] * x[0] * (1.0 - x[0]) * (1.0 - x[0]) : 0.0;
        },
        dim + 1);
  }

  std::string name() const override { return "ins_fem"; }
  /// The step of convective CFL 1 (the scene's cfl scales it); steady flows: one step.
  double stable_dt() const override {
    const double cfl = solver_->cfl(1.0);
    return steady_ || !(cfl > 0.0) ? 1.0 : 1.0 / cfl;
  }
  void set_time_step(double dt) override {
    if (steady_) return;
    const double cfl = solver_->cfl(dt);
    if (cfl > max_cfl_)
      throw std::invalid_argument("ins_fem: time step " + std::to_string(dt) +
                                  " gives a CFL number of " + std::to_string(cfl) +
                                  ", above max_cfl = " + std::to_string(max_cfl_) +
                                  " (lower [run] dt or cfl, or raise [ins_fem] max_cfl)");
  }
  void advance(double, double dt) override {
    if (steady_) {
      if (solved_) return;
      int picard = 0;
      last_ = solver_->solve_steady(1e-10, 100, &picard);
      picard_ = picard;
      solved_ = last_.converged;
      if (!solved_) record_failure("Picard/GMRES did not converge");
      return;
    }
    last_ = solver_->step(dt);
    if (!last_.converged) record_failure("GMRES did not reach its relative tolerance");
    const double e = solver_->kinetic_energy();
    decay_rate_ = (energy_ - e) / dt;
    energy_ = e;
  }
  /// A failed solve stops the run like a divergence (the runner names the step and time and
  /// keeps the last good output): find_nonfinite() reports it.
  void record_failure(const std::string& what) {
    std::ostringstream m;
    m << "the flow solve failed: " << what << " (residual " << last_.residual << " after "
      << last_.linear_iterations << " iterations)";
    failure_ = m.str();
  }
  long long work_per_step() const override { return (dim + 1) * solver_->n_global_dofs(); }
  std::string work_unit() const override { return "DoF-steps"; }

  std::vector<OutputBlock> output(double) const override;
  Diagnostics diagnostics(double t) const override;
  std::string error_diagnostic() const override {
    return has_exact() ? "velocity_l2_error" : "kinetic_energy";
  }
  std::optional<NonFiniteReport> find_nonfinite() const override {
    return find_flow_failure<dim>(*solver_, failure_);
  }
  std::vector<StateBlock> state() const override;
  void restore(const std::vector<StateBlock>& blocks) override;
  std::vector<std::string> owned_blocks() const override { return {"flow"}; }
  Diagnostics phase_seconds() const override { return times_.seconds(); }

  bool periodic() const { return flow_ == "taylor_green_2d" || flow_ == "taylor_green_3d"; }
  bool has_exact() const {
    return flow_ == "taylor_green_2d" || flow_ == "kovasznay" || flow_ == "channel";
  }
  /// Velocity and pressure (mean-free) L2 errors against the exact flow at time t: each rank's
  /// cells' integrals, summed over the ranks.
  template <class Exact>
  std::pair<double, double> errors(Exact exact) const {
    const Exec exec;
    const long n = solver_->n_dofs();
    double eu = 0.0;
    for (int c = 0; c < dim; ++c) {
      exact.component = c;
      const Vector uc = Kokkos::subview(solver_->state(), Kokkos::make_pair(c * n, (c + 1) * n));
      const double e = solvers::matrix_free::error_norms(exec, solver_->space(), uc, exact).l2;
      eu += e * e;
    }
    exact.component = dim;
    auto ep = solvers::matrix_free::error_norms(exec, solver_->space(), solver_->pressure(), exact);
    ep.l2 = std::sqrt(comm_.sum(ep.l2 * ep.l2));
    ep.integral = comm_.sum(ep.integral);
    ep.volume = comm_.sum(ep.volume);
    return {std::sqrt(comm_.sum(eu)), ep.l2_mean_free()};
  }

 private:
  std::string flow_;
  Communicator comm_;
  std::unique_ptr<Solver> solver_;
  double max_cfl_ = 1.0, energy_ = 0.0, decay_rate_ = 0.0;
  bool steady_ = false, solved_ = false;
  int picard_ = 0;
  InsStepReport last_;
  std::string failure_;  ///< why the last solve failed; empty: it did not
  PhaseTimes times_{ins_phase_names()};
};

template <int dim>
Diagnostics InsModule<dim>::diagnostics(double t) const {
  const double viscous = solver_->viscous_dissipation();
  Diagnostics d = {{"kinetic_energy", solver_->kinetic_energy()},
                   {"dissipation_rate", decay_rate_},
                   {"viscous_dissipation", viscous}};
  // The energy balance -dE_k/dt = nu |grad u|^2 holds for periodic flows (no work by walls):
  // the gap is what the discretisation dissipates.
  if (periodic()) d.push_back({"numerical_dissipation", decay_rate_ - viscous});
  d.push_back({"divergence_rms", solver_->divergence_rms()});
  d.push_back({"cfl", steady_ ? 0.0 : solver_->cfl(solver_->previous_dt())});
  d.push_back({"linear_iterations", static_cast<double>(last_.linear_iterations)});
  d.push_back({"multigrid", solver_->multigrid_active() ? 1.0 : 0.0});
  if (steady_) d.push_back({"picard_iterations", static_cast<double>(picard_)});
  if constexpr (dim == 2) {  // the flows with an exact solution are 2D: no 3D error kernels
    if (!has_exact()) return d;
    const double nu = solver_->options().nu;
    const auto e = flow_ == "kovasznay" ? errors(Kovasznay{0, 1.0 / nu})
                   : flow_ == "channel" ? errors(Poiseuille{0, nu, 2.0})
                                        : errors(TaylorGreen2D{0, std::exp(-2.0 * nu * t)});
    d.push_back({"velocity_l2_error", e.first});
    d.push_back({"pressure_l2_error", e.second});
  }
  return d;
}

template <int dim>
std::vector<OutputBlock> InsModule<dim>::output(double) const {
  return {flow_output_block<dim>(*solver_, "flow")};
}

template <int dim>
std::vector<StateBlock> InsModule<dim>::state() const {
  // gathered on every rank (collective), written from rank 0 (the whole box's DoF order)
  StateBlock b = flow_state_block(*solver_, {energy_, decay_rate_, solved_ ? 1.0 : 0.0,
                                             static_cast<double>(last_.linear_iterations),
                                             solver_->multigrid_active() ? 1.0 : 0.0});
  if (!comm_.is_root()) return {};
  return {std::move(b)};
}

template <int dim>
void InsModule<dim>::restore(const std::vector<StateBlock>& blocks) {
  const StateBlock* flow = nullptr;
  for (const auto& b : blocks)
    if (b.name == "flow") flow = &b;
  const std::vector<double> h =
      restore_flow_block<dim>(*solver_, flow ? *flow : StateBlock{"flow", {}}, "ins_fem", 4);
  energy_ = h[0], decay_rate_ = h[1], solved_ = h[2] != 0.0;
  last_.linear_iterations = static_cast<int>(h[3]);
  if (h.size() > 4 && h[4] == 0.0) solver_->disable_multigrid();
}

}  // namespace ins_module_detail
using namespace ins_module_detail;

ParamTable parameter_table() {
  const solvers::matrix_free::OseenMultigridOptions multigrid;  // the keys' defaults
  return {"ins_fem",
          "incompressible Navier-Stokes, equal-order Q_k with SUPG/PSPG and grad-div, BDF2, "
          "matrix-free",
          {
              string_param(
                  "flow", std::string("taylor_green_2d"), "the case",
                  {"taylor_green_2d", "taylor_green_3d", "kovasznay", "lid_cavity", "channel"}),
              int_param("degree", 2,
                        at_least(1) & at_most(solvers::matrix_free::max_compiled_degree_flow),
                        "polynomial degree k of velocity and pressure (Q_k; the compiled range)"),
              int_param("cells", 16, at_least(1) & at_most(512),
                        "cells per direction (the channel: twice as many along its length)"),
              real_param("deformation", 0.0, "1", at_least(0.0) & at_most(0.1),
                         "amplitude of the sinusoidal deformation that curves the cells, "
                         "faces kept in place (0: Cartesian cells)"),
              real_param("nu", 0.01, "m^2/s", above(0.0), "kinematic viscosity"),
              real_param("grad_div", 0.0, "1", at_least(0.0), "grad-div stabilisation weight"),
              string_param("tau", std::string("steady"),
                           "the SUPG/PSPG parameter: steady leaves (2 / dt)^2 out of tau, "
                           "transient keeps it (tau <= dt / 2; Lethe keeps a transient term too)",
                           {"steady", "transient"}),
              real_param("backflow", 1.0, "1", at_least(0.0),
                         "beta of the backflow stabilisation on open faces (the channel's "
                         "outflow; 0: plain do-nothing)"),
              real_param("max_cfl", 2.0, "1", above(0.0),
                         "largest convective CFL number dt max|u| k / h a step may have"),
              string_param("geometry", std::string("stored"),
                           "how geometry reaches the quadrature points", {"stored", "on_the_fly"}),
              real_param("tolerance", 1e-8, "1", above(0.0) & below(1.0),
                         "relative residual reduction of each step's GMRES solve"),
              int_param("max_iterations", 5000, at_least(1), "GMRES iteration limit per step"),
              int_param("restart", 60, at_least(2) & at_most(500), "GMRES restart length"),
              string_param("preconditioner", std::string("multigrid"),
                           "of GMRES: the coupled geometric multigrid (falls back to Jacobi for "
                           "the rest of the run where it fails to converge in one restart "
                           "cycle) or point Jacobi",
                           {"multigrid", "jacobi"}),
              int_param("smoothing_degree", multigrid.smoother.degree, at_least(1) & at_most(12),
                        "Chebyshev degree of the multigrid's smoother (matrix-vector products "
                        "per smoothing on each level)"),
              int_param("multigrid_refresh", multigrid.refresh_every, at_least(1),
                        "steps between recomputations of the multigrid's diagonals and "
                        "eigenvalue bounds (each costs a cell application per cell DoF)"),
              bool_param("multigrid_viscous_residual", multigrid.viscous_residual,
                         "whether the multigrid's operators keep -nu lap u in the SUPG/PSPG "
                         "residual (false: its smoothers skip the second derivatives; GMRES "
                         "still applies the full operator)"),
          }};
}

std::unique_ptr<Module> create(const Parameters& p, const Communicator& comm) {
  if (p.string("flow") == "taylor_green_3d") return std::make_unique<InsModule<3>>(p, comm);
  return std::make_unique<InsModule<2>>(p, comm);
}

}  // namespace amphora::physics::ins_fem
