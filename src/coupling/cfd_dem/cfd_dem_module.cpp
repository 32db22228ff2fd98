#include "coupling/cfd_dem/cfd_dem_module.hpp"

#include <array>
#include <cmath>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "coupling/cfd_dem/cfd_dem_coupling.hpp"
#include "coupling/cfd_dem/richardson_zaki.hpp"
#include "kernels/reductions.hpp"
#include "physics/dem/dem_module.hpp"
#include "physics/ins_fem/flow_checkpoint.hpp"
#include "physics/ins_fem/flow_failure.hpp"
#include "physics/ins_fem/flow_output.hpp"
#include "solvers/matrix_free/degree_dispatch.hpp"

namespace amphora::coupling::cfd_dem {

ParamTable cfd_dem_parameter_table() {
  return {
      "cfd_dem",
      "unresolved CFD-DEM (VANS model A or B, matrix-free Q_k, coupled to the DEM): a square "
      "column "
      "with inflow at the bottom, a fluidised or a fixed packed bed, or a slot with a jet: a "
      "pseudo-2D spouted bed",
      {
          string_param("bed", std::string("fluidised"),
                       "fluidised (the particles move), packed (held fixed), or single: one "
                       "sphere released from rest on the column's axis at release_height, "
                       "settling to its terminal velocity (particle_count is ignored)",
                       {"fluidised", "packed", "single"}),
          real_param("release_height", 0.15, "m", above(0.0),
                     "bed = single: the sphere's centre at release, above the distributor"),
          real_param("column_width", 0.03, "m", above(0.0), "side of the square column (x)"),
          real_param("column_depth", 0.0, "m", at_least(0.0),
                     "the column's depth (y); 0: the width (a square section)"),
          real_param("column_height", 0.2, "m", above(0.0),
                     "column height (particles leaving the top are removed)"),
          real_param("distributor_height", 0.02, "m", at_least(0.0),
                     "the particles' floor, a distributor the fluid passes: clear fluid below "
                     "it, so the inflow meets eps = 1"),
          string_param("fluid_sides", std::string("periodic"),
                       "the column's sides for the fluid: periodic (a slice of a wide bed), "
                       "no-slip walls (on a column a few cells wide these raise the pressure "
                       "drop: docs/cfd_dem.md), or slot: walls at x = 0 and the width, "
                       "periodic across the thin depth (pseudo-2D)",
                       {"walls", "periodic", "slot"}),
          string_param("particle_sides", std::string("fluid"),
                       "the column's sides for the particles: as the fluid's (periodic where "
                       "fluid_sides is, walls elsewhere), or walls everywhere (a particle-free "
                       "gap along periodic fluid sides: docs/cfd_dem.md)",
                       {"fluid", "walls"}),
          int_param("cells", 8, at_least(2) & at_most(256),
                    "cells across the column (about as many per length along it: the "
                    "nearest multiple of the largest power of two dividing cells, so that the "
                    "multigrid halves the column as often as its width)"),
          int_param("degree", 1,
                    at_least(1) & at_most(solvers::matrix_free::max_compiled_degree_vans),
                    "polynomial degree of the flow (Q1: CFD-DEM's usual element)"),
          int_param("particle_count", 2000, at_least(1),
                    "particles, on a lattice from the bottom up"),
          real_param("particle_diameter", 3.087e-3, "m", above(0.0), "alumina (Ferreira 2023)"),
          real_param("particle_density", 3585.9, "kg/m^3", above(0.0), "alumina"),
          real_param("youngs_modulus", 1e7, "Pa", above(0.0),
                     "particle and wall Young's modulus (softened, as CFD-DEM does)"),
          real_param("poisson_ratio", 0.3, "1", above(-1.0) & below(0.5), "Poisson's ratio"),
          real_param("restitution", 0.9, "1", above(0.0) & at_most(1.0),
                     "restitution, particles and walls"),
          real_param("friction", 0.1, "1", at_least(0.0), "sliding friction, particles and walls"),
          real_param("rolling_friction", 0.1, "1", at_least(0.0), "rolling friction"),
          real_param("fluid_density", 997.0, "kg/m^3", above(0.0), "water"),
          real_param("viscosity", 8.379e-7, "m^2/s", above(0.0), "kinematic viscosity (water)"),
          real_param("inlet_velocity", 0.157, "m/s", at_least(0.0),
                     "superficial velocity of the inflow at the bottom (outside the jet)"),
          real_param("jet_width", 0.0, "m", at_least(0.0),
                     "width of a central slot jet in the inflow, across the depth (0: none)"),
          real_param("jet_velocity", 0.0, "m/s", at_least(0.0), "the jet's inflow velocity"),
          real_param("gravity", 9.81, "m/s^2", at_least(0.0), "gravity, along -z"),
          string_param("drag", std::string("rong"), "drag closure",
                       {"di_felice", "rong", "beetstra", "gidaspow"}),
          bool_param("saffman_lift", false,
                     "add the Saffman-Mei shear lift to the particles (and its reaction to the "
                     "fluid)"),
          string_param("void_fraction", std::string("qcm"),
                       "particle-centred (smoothed) or quadrature-centred", {"pcm", "qcm"}),
          real_param("smoothing_length", 1.0, "diameters", at_least(0.0),
                     "L of the void fraction's L2-projection smoothing, in particle diameters"),
          bool_param("bound_void_fraction", false,
                     "keep eps within [void_fraction_lower_bound, void_fraction_upper_bound] "
                     "(MPRGP; the particles' volume is then not held exactly where one binds)"),
          real_param("void_fraction_lower_bound", 0.36, "1", above(0.0) & below(1.0),
                     "the least eps where bound_void_fraction"),
          real_param("void_fraction_upper_bound", 1.0, "1", above(0.0) & at_most(1.0),
                     "the largest eps where bound_void_fraction"),
          string_param("vans_model", std::string("A"),
                       "A: the pressure shared by the phases, -eps grad p in the fluid; B: the "
                       "fluid's alone, -grad p, and the particles' pressure and viscous forces "
                       "returned to the fluid (Zhou et al. 2010)",
                       {"A", "B"}),
          bool_param("viscous_force", true,
                     "the viscous-stress force V_p mu lap u on each particle (zero with degree "
                     "1)"),
          bool_param("self_induced_correction", false,
                     "give the drag closure the undisturbed velocity: the fluid's less what the "
                     "particle's own force induces (lone particles in small cells; degree 1)"),
          string_param("drag_coupling", std::string("semi_implicit"),
                       "how the fluid takes the drag", {"semi_implicit", "explicit"}),
          int_param("dem_substeps", 200, at_least(1),
                    "DEM steps per fluid step (run.dt is the fluid step)"),
          real_param("max_cfl", 2.0, "1", above(0.0), "a fluid step over this CFL stops the run"),
          real_param("grad_div", 0.0, "1", at_least(0.0), "grad-div stabilisation weight"),
          bool_param("void_fraction_time_derivative", true,
                     "keep -d eps / dt in the fluid's continuity (false: drop it, for a bed "
                     "that barely moves: docs/cfd_dem.md)"),
          string_param("void_fraction_rate", std::string("filtered"),
                       "how d eps / dt is taken: filtered (second order, blind to the "
                       "period-two-step alternation of a settled bed) or the flow's BDF2 "
                       "(docs/cfd_dem.md)",
                       {"filtered", "bdf"}),
          real_param("backflow", 1.0, "1", at_least(0.0),
                     "beta of the backflow stabilisation at the open top (0: plain do-nothing)"),
          real_param("tolerance", 1e-8, "1", above(0.0) & below(1.0),
                     "relative residual reduction of each fluid step's GMRES solve"),
          real_param("verlet_skin", 0.25, "1", above(0.0) & at_most(2.0),
                     "Verlet skin in diameters"),
          int_param("seed", 1, at_least(0), "seed of the lattice's jitter"),
      }};
}

// A named namespace, not an anonymous one: CUDA does not support extended lambdas in
// anonymous namespaces.
namespace cfd_dem_module_detail {

using Exec = kernels::DefaultExecSpace;
using Flow = physics::ins_fem::InsSolver<3, Exec>;

/// The column's depth (y): column_depth, or the width where that is 0.
double column_depth(const Parameters& p) {
  const double d = p.real("column_depth");
  return d > 0.0 ? d : p.real("column_width");
}

/// The `[dem]` table of the column's particles: a box of the column's size, lattice insertion.
Parameters dem_parameters(const Parameters& p) {
  Parameters d(physics::dem::parameter_table());
  d.set("geometry", std::string("box"));
  d.set("box_x", p.real("column_width"));
  d.set("box_y", column_depth(p));
  d.set("box_z", p.real("column_height"));
  d.set("floor_height", p.real("distributor_height"));
  const std::string sides = p.string("fluid_sides");
  if (p.string("particle_sides") == "fluid" && sides != "walls")
    d.set("box_sides", std::string(sides == "periodic" ? "periodic" : "periodic_y"));
  d.set("particle_radius", 0.5 * p.real("particle_diameter"));
  d.set("density", p.real("particle_density"));
  for (const char* key : {"youngs_modulus", "poisson_ratio", "restitution", "friction",
                          "rolling_friction", "gravity", "verlet_skin"})
    d.set(key, p.real(key));
  d.set("wall_youngs_modulus", p.real("youngs_modulus"));
  d.set("wall_restitution", p.real("restitution"));
  d.set("wall_friction", p.real("friction"));
  d.set("insertion", std::string("lattice"));
  d.set("particle_count",
        p.string("bed") == "single" ? std::int64_t{0} : p.integer("particle_count"));
  d.set("seed", p.integer("seed"));
  return d;
}

/// The column: sides as fluid_sides says, inflow at z = 0, open top. Along y and z the cells
/// are as near cubic as a count that is a multiple of q, the largest power of two dividing the
/// cells across, allows (a side shorter than q cells keeps its count), so that the multigrid's
/// levels are nested as often as the width allows (odd counts coarsen without nesting).
mesh::hex::StructuredHexMesh<3> column_mesh(const Parameters& p) {
  mesh::hex::StructuredHexMesh<3> m;
  const int n = static_cast<int>(p.integer("cells")), q = n & -n;
  const double w = p.real("column_width"), depth = column_depth(p), h = p.real("column_height");
  const auto along = [&](double l) {  // a thin side (a slot's depth) keeps its count
    const double cubic = n * l / w;
    return cubic < q ? std::max(1, static_cast<int>(std::lround(cubic)))
                     : q * static_cast<int>(std::lround(cubic / q));
  };
  m.cells = {n, along(depth), along(h)};
  m.upper = {w, depth, h};
  m.faces[5] = mesh::hex::FaceCondition::neumann;
  const std::string sides = p.string("fluid_sides");
  for (int f = sides == "slot" ? 2 : 0; f < 4 && sides != "walls"; ++f)
    m.faces[f] = mesh::hex::FaceCondition::periodic;
  return m;
}

physics::ins_fem::InsOptions flow_options(const Parameters& p) {
  physics::ins_fem::InsOptions o;
  o.model = p.string("vans_model") == "B" ? physics::ins_fem::FlowModel::vans_b
                                          : physics::ins_fem::FlowModel::vans_a;
  o.transient_tau = true;
  o.nu = p.real("viscosity");
  o.grad_div = p.real("grad_div");
  o.backflow = p.real("backflow");
  o.void_fraction_time_derivative = p.boolean("void_fraction_time_derivative");
  o.void_fraction_rate = p.string("void_fraction_rate") == "filtered"
                             ? physics::ins_fem::VoidFractionRate::filtered
                             : physics::ins_fem::VoidFractionRate::bdf;
  o.tolerance = p.real("tolerance");
  return o;
}

CfdDemOptions coupling_options(const Parameters& p) {
  CfdDemOptions o;
  o.fluid.density = p.real("fluid_density");
  o.fluid.viscosity = p.real("viscosity") * o.fluid.density;
  o.fluid.drag = *drag_model_from_name(p.string("drag"));  // the table allows only these
  o.fluid.saffman_lift = p.boolean("saffman_lift");
  o.void_fraction.method =
      p.string("void_fraction") == "qcm" ? VoidFractionMethod::qcm : VoidFractionMethod::pcm;
  o.void_fraction.smoothing_length = p.real("smoothing_length") * p.real("particle_diameter");
  o.void_fraction.bounded = p.boolean("bound_void_fraction");
  o.void_fraction.lower_bound = p.real("void_fraction_lower_bound");
  o.void_fraction.upper_bound = p.real("void_fraction_upper_bound");
  if (o.void_fraction.bounded && !(o.void_fraction.lower_bound < o.void_fraction.upper_bound))
    throw std::invalid_argument(
        "cfd_dem: void_fraction_lower_bound " + std::to_string(o.void_fraction.lower_bound) +
        " must lie below void_fraction_upper_bound " + std::to_string(o.void_fraction.upper_bound));
  o.drag_coupling = p.string("drag_coupling") == "explicit" ? DragCoupling::explicit_load
                                                            : DragCoupling::semi_implicit;
  o.dem_substeps = static_cast<int>(p.integer("dem_substeps"));
  o.move_particles = p.string("bed") != "packed";
  o.max_cfl = p.real("max_cfl");
  o.viscous_force = p.boolean("viscous_force");
  o.self_induced_correction = p.boolean("self_induced_correction");
  return o;
}

/// Sum over the owned particles of their heights and of their volumes.
template <class Set>
std::pair<double, double> height_and_volume_sums(const Exec& exec, const Set& p) {
  const auto x = p.x;
  const auto r = p.radius;
  double z = 0.0, volume = 0.0;
  Kokkos::parallel_reduce(
      "amphora::cfd_dem::height_sum", kernels::RangePolicy<Exec>(exec, 0, p.n_owned),
      KOKKOS_LAMBDA(int i, double& s) { s += x(i, 2); }, z);
  Kokkos::parallel_reduce(
      "amphora::cfd_dem::volume_sum", kernels::RangePolicy<Exec>(exec, 0, p.n_owned),
      KOKKOS_LAMBDA(int i, double& s) { s += 4.0 / 3.0 * M_PI * r(i) * r(i) * r(i); }, volume);
  return {z, volume};
}

/// Over the owned particles: the sum of the vertical velocities within `half` of the mid-plane
/// x = c (the spout) and their count, the sum of all vertical velocities, and the highest
/// particle's centre.
template <class Set>
std::array<double, 4> spout_sums(const Exec& exec, const Set& p, double c, double half) {
  const auto x = p.x;
  const auto v = p.v;
  double w_in = 0.0, n_in = 0.0, w_all = 0.0, top = 0.0;
  const kernels::RangePolicy<Exec> all(exec, 0, p.n_owned);
  Kokkos::parallel_reduce(
      "amphora::cfd_dem::spout_w", all,
      KOKKOS_LAMBDA(int i, double& s) {
        s += kernels::math::fabs(x(i, 0) - c) < half ? v(i, 2) : 0.0;
      },
      w_in);
  Kokkos::parallel_reduce(
      "amphora::cfd_dem::spout_n", all,
      KOKKOS_LAMBDA(int i, double& s) { s += kernels::math::fabs(x(i, 0) - c) < half ? 1.0 : 0.0; },
      n_in);
  Kokkos::parallel_reduce(
      "amphora::cfd_dem::all_w", all, KOKKOS_LAMBDA(int i, double& s) { s += v(i, 2); }, w_all);
  Kokkos::parallel_reduce(
      "amphora::cfd_dem::top", all,
      KOKKOS_LAMBDA(int i, double& m) { m = x(i, 2) > m ? x(i, 2) : m; }, Kokkos::Max<double>(top));
  return {w_in, n_in, w_all, p.n_owned > 0 ? top : -1e300};
}

/// Sum of column c of an n x 3 particle field (forces, velocities) over its first n rows.
template <class Field>
double column_sum(const Exec& exec, const Field& f, int n, int c) {
  double s = 0.0;
  Kokkos::parallel_reduce(
      "amphora::cfd_dem::column_sum", kernels::RangePolicy<Exec>(exec, 0, n),
      KOKKOS_LAMBDA(int i, double& a) { a += f(i, c); }, s);
  return s;
}

class CfdDemModule final : public physics::Module {
 public:
  CfdDemModule(const Parameters& p, const Communicator& comm)
      : comm_(comm),
        width_(p.real("column_width")),
        depth_(column_depth(p)),
        height_(p.real("column_height")),
        rho_(p.real("fluid_density")),
        rho_p_(p.real("particle_density")),
        g_(p.real("gravity")),
        u_in_(p.real("inlet_velocity")),
        floor_(p.real("distributor_height")),
        jet_width_(p.real("jet_width")),
        jet_velocity_(p.real("jet_velocity")),
        sides_(p.string("fluid_sides")),
        single_(p.string("bed") == "single"),
        bounded_(p.boolean("bound_void_fraction")) {
    if (jet_width_ > width_ || (jet_velocity_ > 0.0 && !(jet_width_ > 0.0)))
      throw std::invalid_argument("cfd_dem: jet_width " + std::to_string(jet_width_) +
                                  " m must lie in (0, column_width " + std::to_string(width_) +
                                  " m] where jet_velocity is set");
    const auto mesh = column_mesh(p);
    const CfdDemOptions o = coupling_options(p);
    dem_ = std::make_unique<physics::dem::DemModule>(dem_parameters(p), comm,
                                                     dem_split(mesh, o, p, comm));
    if (single_) release_sphere(p);
    flow_ =
        std::make_unique<Flow>(mesh, static_cast<int>(p.integer("degree")), flow_options(p), comm);
    flow_->set_state(initial_state());
    substeps_ = o.dem_substeps;
    coupling_ = std::make_unique<CfdDemCoupling<Exec>>(*flow_, dem_->system(), o);
    coupling_->set_phase_times(&times_);
    const double d = p.real("particle_diameter"), mu = o.fluid.viscosity;
    terminal_ = terminal_velocity(o.fluid.drag, rho_, mu, d, rho_p_, g_);
    rz_exponent_ = richardson_zaki_exponent(rho_ * terminal_ * d / mu, d / width_);
    if (o.self_induced_correction) warn_if_dense(d);
  }

  /// On several ranks the particles are split as the flow is, in slabs of its cells along z,
  /// and with QCM their ghosts reach over a reference sphere (CfdDemCoupling::check_split).
  static physics::dem::DemSplit dem_split(const mesh::hex::StructuredHexMesh<3>& mesh,
                                          const CfdDemOptions& o, const Parameters& p,
                                          const Communicator& comm) {
    physics::dem::DemSplit s;
    if (comm.size() == 1) return s;
    s.layout.cells = mesh.cells;
    s.layout.split = {false, false, true};
    if (o.void_fraction.method == VoidFractionMethod::qcm)
      s.min_halo_width =
          CfdDemCoupling<Exec>::qcm_reach(mesh, o.void_fraction, 0.5 * p.real("particle_diameter"));
    return s;
  }

  /// The self-induced correction is for lone or dilute particles (docs/cfd_dem.md): one line
  /// when the particles fill more than 5 % of the column above the distributor.
  void warn_if_dense(double d) const {
    const double volume =
        comm_.sum(height_and_volume_sums(Exec(), dem_->system().particles()).second);
    const double solids = volume / (width_ * depth_ * (height_ - floor_));
    if (solids <= 0.05 || !comm_.is_root()) return;
    std::ostringstream line;
    line.precision(3);
    line << "cfd_dem: warning: self_induced_correction is meant for lone or dilute particles, "
            "but the particles fill "
         << 100.0 * solids << " % of the column (over 5 %; " << dem_->system().global_count()
         << " of diameter " << d << " m): a bed's drag closure is fitted to the flow as it is";
    std::cerr << line.str() << "\n";
  }

  /// bed = single: one sphere at rest on the column's axis, release_height above the floor.
  void release_sphere(const Parameters& p) {
    physics::dem::ParticleSpec s;
    s.radius = 0.5 * p.real("particle_diameter");
    s.x[0] = 0.5 * width_, s.x[1] = 0.5 * depth_, s.x[2] = floor_ + p.real("release_height");
    if (s.x[2] + s.radius > height_)
      throw std::invalid_argument(
          "cfd_dem: release_height " + std::to_string(p.real("release_height")) +
          " m puts the sphere above the column's top (column_height " + std::to_string(height_) +
          " m, distributor_height " + std::to_string(floor_) + " m)");
    dem_->system().add_particles({s});
  }

  /// At rest but for the inflow: w = u_in at every node of the bottom face (its edges too, so
  /// the inflow's flux is u_in times the column's section), the jet's velocity at the bottom's
  /// nodes within jet_width / 2 of the mid-plane x = width / 2 (bounds included), and zero on
  /// the side walls.
  std::vector<double> initial_state() const {
    const auto& s = flow_->space();
    const double w = width_, tiny = 1e-12 * width_;
    return s.interpolate(
        [&](const mesh::hex::Point3& x, int c) {
          if (c != 2) return 0.0;
          const bool wall_x = sides_ != "periodic" && (x[0] < tiny || x[0] > w - tiny);
          const bool wall_y = sides_ == "walls" && (x[1] < tiny || x[1] > depth_ - tiny);
          const bool jet =
              jet_width_ > 0.0 && std::abs(x[0] - 0.5 * w) <= 0.5 * jet_width_ + 1e-9 * w;
          if (x[2] < tiny) return jet ? jet_velocity_ : u_in_;
          return wall_x || wall_y ? 0.0 : u_in_;
        },
        4);
  }

  std::string name() const override { return "cfd_dem"; }
  /// N DEM stable steps, and no more than the fluid's CFL limit.
  double stable_dt() const override {
    const double cfl = flow_->cfl(1.0);
    const double dem = substeps_ * dem_->stable_dt();
    return cfl > 0.0 ? std::min(dem, 1.0 / cfl) : dem;
  }
  void set_time_step(double dt) override {
    try {
      dem_->set_time_step(dt / substeps_);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("cfd_dem: the DEM step run.dt / cfd_dem.dem_substeps: " +
                                  std::string(e.what()));
    }
  }
  void advance(double, double) override {
    try {
      last_ = coupling_->step();
      if (!last_.converged) failure_ = "the fluid's GMRES did not reach its tolerance";
    } catch (const StepFailure& e) {  // eps out of (0, 1], CFL over the limit
      failure_ = e.what();
      failure_field_ = e.field;
      failure_node_ = e.node;
    } catch (const std::runtime_error& e) {
      failure_ = e.what();
    }
  }
  long long work_per_step() const override {
    return std::max(1LL, dem_->system().global_count()) * substeps_;
  }
  std::string work_unit() const override { return "particle-steps"; }

  std::vector<OutputBlock> output(double t) const override {
    OutputBlock f = physics::ins_fem::flow_output_block<3>(*flow_, "flow", rho_);
    f.fields.push_back(
        {"eps", physics::ins_fem::node_values<3>(flow_->space(), coupling_->void_fraction())});
    std::vector<OutputBlock> out = {f};
    for (auto& b : dem_->output(t)) out.push_back(std::move(b));
    return out;
  }

  Diagnostics diagnostics(double t) const override;
  std::string error_diagnostic() const override {
    return single_ ? "settling_velocity_ratio" : "pressure_drop_ratio";
  }

  std::optional<physics::NonFiniteReport> find_nonfinite() const override {
    if (auto bad = dem_->find_nonfinite()) return bad;
    // eps out of range names its node (on the rank that found it); a step over the CFL limit
    // or a failed solve, the place the flow is fastest. Collective.
    auto r = physics::ins_fem::find_flow_failure<3>(*flow_, failure_);
    if (!r || failure_field_ != "eps" || !r->reason.size()) return r;
    const int owner = static_cast<int>(comm_.min(failure_node_ >= 0 ? comm_.rank() : comm_.size()));
    physics::NonFiniteReport e =
        physics::ins_fem::flow_report_at<3>(*flow_, std::max(0L, failure_node_), failure_);
    e.field = failure_field_;
    return physics::ins_fem::flow_report_from<3>(*flow_, e, owner);
  }

  std::vector<StateBlock> state() const override {
    const StateBlock flow = physics::ins_fem::flow_state_block(
        *flow_,
        {static_cast<double>(coupling_->steps()), static_cast<double>(last_.linear_iterations)});
    // the flow gathered on every rank, the particles on rank 0 (collective); rank 0 writes
    std::vector<StateBlock> blocks = {flow};
    for (auto& b : dem_->state()) blocks.push_back(std::move(b));
    if (!comm_.is_root()) return {};
    return blocks;
  }
  /// The flow (with its void fraction's history and multigrid), the coupling's step count and
  /// the particles: a continuation is the uninterrupted run bit for bit.
  void restore(const std::vector<StateBlock>& blocks) override {
    std::vector<StateBlock> dem;
    for (const auto& b : blocks) {
      if (b.name != "flow") {
        dem.push_back(b);
        continue;
      }
      const std::vector<double> h =
          physics::ins_fem::restore_flow_block<3>(*flow_, b, "cfd_dem", 2);
      coupling_->resume(static_cast<long>(h[0]));
      last_.linear_iterations = static_cast<int>(h[1]);
    }
    dem_->restore(dem);
  }
  std::vector<std::string> owned_blocks() const override {
    std::vector<std::string> names = {"flow"};
    for (const auto& n : dem_->owned_blocks()) names.push_back(n);
    return names;
  }
  Diagnostics phase_seconds() const override { return times_.seconds(); }

  /// The mean of the flow's pressure [Pa] over the plane at height z (midpoint probes, two per
  /// cell and direction: exact for Q1), from the rank whose slab holds the plane. Collective.
  double plane_mean_pressure(double z) const {
    const auto& slab = flow_->space().mesh();
    const bool top =
        flow_->distributed_space().end_cell() == flow_->distributed_space().global_mesh().cells[2];
    if (!(z >= slab.lower[2] && (z < slab.upper[2] || (top && z <= slab.upper[2]))))
      return comm_.sum(0.0);
    const auto& cells = flow_->space().mesh().cells;
    const int k = flow_->space().degree(), mx = 2 * cells[0] * k, my = 2 * cells[1] * k;
    using Points = Kokkos::View<double* [3], Kokkos::LayoutRight, Exec::memory_space>;
    Points x("amphora::cfd_dem::probes", mx * my), out("amphora::cfd_dem::probe_values", mx * my);
    auto h = Kokkos::create_mirror_view(x);
    for (int j = 0; j < my; ++j)
      for (int i = 0; i < mx; ++i) {
        h(j * mx + i, 0) = (i + 0.5) * width_ / mx;
        h(j * mx + i, 1) = (j + 0.5) * depth_ / my;
        h(j * mx + i, 2) = z;
      }
    Kokkos::deep_copy(x, h);
    interpolate(Exec(), coupling_->void_fraction_solver().basis(), flow_->pressure(), 1, x, mx * my,
                out);
    const auto o = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), out);
    double s = 0.0;
    for (int i = 0; i < mx * my; ++i) s += o(i, 0);
    return comm_.sum(rho_ * s / (mx * my));
  }

 private:
  Communicator comm_;
  double width_, depth_, height_, rho_, rho_p_, g_, u_in_, floor_, jet_width_, jet_velocity_;
  std::string sides_;
  bool single_ = false;
  bool bounded_ = false;  // bound_void_fraction
  double terminal_ = 0.0, rz_exponent_ = 0.0;
  int substeps_ = 1;
  std::unique_ptr<physics::dem::DemModule> dem_;
  std::unique_ptr<Flow> flow_;
  std::unique_ptr<CfdDemCoupling<Exec>> coupling_;
  physics::ins_fem::InsStepReport last_;
  std::string failure_, failure_field_ = "velocity";
  long failure_node_ = -1;
  physics::PhaseTimes times_{cfd_dem_phase_names()};
};

/// The pressure drop from below the bed to the top against the bed's buoyant weight per section,
/// M g (1 - rho / rho_p) / A; the bed's height (twice its particles' mean height: exact for a
/// uniform bed, above the distributor) and void fraction against Richardson-Zaki's; the void
/// fraction's volume balance.
Diagnostics CfdDemModule::diagnostics(double t) const {
  const Exec exec;
  const auto& particles = dem_->system().particles();
  const auto [z_local, volume_local] = height_and_volume_sums(exec, particles);
  const double z_sum = comm_.sum(z_local), volume = comm_.sum(volume_local);
  const long long n = dem_->system().global_count();
  const double area = width_ * depth_;
  const double weight = volume * (rho_p_ - rho_) * g_ / area;
  // below the bed at half the distributor's height: clear of the inflow's edges, where the
  // prescribed inflow meets the no-slip walls and the pressure is singular
  const double tap = std::max(0.5 * floor_, 1e-9 * height_);
  const double drop = plane_mean_pressure(tap) - plane_mean_pressure(height_ * (1 - 1e-9));
  const double bed = n > 0 ? 2.0 * (z_sum / n - floor_) : 0.0;
  const double solid = volume > 0.0 ? area * height_ - coupling_->void_fraction_solver().integral(
                                                           exec, coupling_->void_fraction())
                                    : 0.0;
  Diagnostics d = {
      {"pressure_drop", drop},
      {"weight_pressure", weight},
      {"pressure_drop_ratio", weight > 0.0 ? drop / weight : 0.0},
      {"fluid_force_ratio",
       weight > 0.0 ? comm_.sum(column_sum(exec, coupling_->held_forces(), particles.n_owned, 2)) /
                          (weight * area)
                    : 0.0},
      {"bed_height", bed},
      {"bed_void_fraction", bed > 0.0 ? 1.0 - volume / (area * bed) : 1.0},
      {"richardson_zaki_void_fraction",
       richardson_zaki_void_fraction(u_in_, terminal_, rz_exponent_)},
      {"void_fraction_volume_error",
       volume > 0.0 && coupling_->steps() > 0 ? std::abs(solid - volume) / volume : 0.0},
      {"particles", static_cast<double>(n)},
      {"cfl", flow_->cfl(flow_->previous_dt())},
      {"linear_iterations", static_cast<double>(last_.linear_iterations)}};
  if (bounded_) {  // the nodes the last void fraction held at each bound
    const auto& b = coupling_->void_fraction_solver().bounds();
    d.push_back({"void_fraction_at_lower_bound", static_cast<double>(b.at_lower)});
    d.push_back({"void_fraction_at_upper_bound", static_cast<double>(b.at_upper)});
  }
  if (jet_width_ > 0.0) {
    const auto s = spout_sums(exec, particles, 0.5 * width_, 0.5 * jet_width_);
    const double w_in = comm_.sum(s[0]), n_in = comm_.sum(s[1]), w_all = comm_.sum(s[2]);
    const double n_out = static_cast<double>(n) - n_in;
    d.push_back({"spout_particle_velocity", n_in > 0 ? w_in / n_in : 0.0});
    d.push_back({"annulus_particle_velocity", n_out > 0 ? (w_all - w_in) / n_out : 0.0});
    d.push_back({"fountain_height", comm_.max(s[3]) - floor_});
  }
  if (single_ && n > 0) {
    const double w = comm_.sum(column_sum(exec, particles.v, particles.n_owned, 2)) / n;
    const CfdDemCoupling<Exec>::Vec water("amphora::cfd_dem::u_at_sphere", particles.n_owned);
    coupling_->velocity_at_particles(exec, water);  // the water at the sphere now
    const double u = comm_.sum(column_sum(exec, water, particles.n_owned, 2)) / n;
    d.push_back({"particle_velocity", w});
    d.push_back({"terminal_velocity", terminal_});
    d.push_back({"settling_velocity_ratio", -w / terminal_});
    d.push_back({"slip_velocity_ratio", (u - w) / terminal_});
  }
  for (const auto& [key, value] : dem_->diagnostics(t))
    if (key == "kinetic_energy" || key == "contacts" || key == "max_overlap")
      d.push_back({"particle_" + key, value});
  return d;
}

}  // namespace cfd_dem_module_detail

std::unique_ptr<physics::Module> create_cfd_dem(const Parameters& p, const Communicator& comm) {
  return std::make_unique<cfd_dem_module_detail::CfdDemModule>(p, comm);
}

}  // namespace amphora::coupling::cfd_dem
