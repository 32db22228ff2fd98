#include "coupling/fsi/mpve_module.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "coupling/fsi/mpve_partitioned.hpp"
#include "mesh/box_decomposition.hpp"

namespace amphora::coupling::fsi {

ParamTable mpve_parameter_table() {
  return {
      "mpve",
      "MP-VE: viscous fluid (-H < y < 0) on an elastic solid (0 < y < Hbar), periodic in x, "
      "partitioned coupling (traditional, traditional with Aitken sub-iterations, or added-mass "
      "partitioned), from the exact traveling wave",
      {
          string_param("scheme", std::string("amp"), "coupling scheme", {"amp", "tp", "tp_aitken"}),
          real_param("rho_bar", 1000.0, "kg/m^3", above(0.0),
                     "solid density (mu_bar = rho_bar: cs = 1)"),
          real_param(
              "poisson_ratio", 0.25, "1", above(-1.0) & below(0.5),
              "solid Poisson ratio nu (lambda_bar = 2 mu_bar nu / (1 - 2 nu); 0.25: cp = sqrt 3)"),
          real_param("viscosity", 0.02, "Pa s", above(0.0), "fluid viscosity mu (fluid density 1)"),
          int_param("cells", 32, at_least(8) & at_most(4096),
                    "cells per wavelength in x (h = 1 / cells; the wavelength is 1)"),
          real_param("blowup_factor", 10.0, "1", above(1.0),
                     "unstable once max |v| exceeds this multiple of its start"),
      }};
}

namespace {

class MpveModule final : public physics::Module {
 public:
  MpveModule(const Parameters& p, const Communicator& comm) {
    if (comm.size() > 1)
      throw mesh::DecompositionError("more ranks (" + std::to_string(comm.size()) +
                                     ") than blocks (1): MP-VE runs on one rank");
    // The MP-VE check case (Banks et al. 2014), its root followed to the scene's solid and
    // viscosity.
    s_.physics = mpve_check_case();
    s_.physics.mu = p.real("viscosity");
    const double nu = p.real("poisson_ratio");
    s_.physics.rho_bar = s_.physics.mu_bar = p.real("rho_bar");
    s_.physics.lambda_bar = 2 * s_.physics.mu_bar * nu / (1 - 2 * nu);
    const DispersionRoot root = mpve_root_from_check_case(s_.physics);
    if (!root.converged)
      throw std::invalid_argument("mpve: the dispersion root could not be followed to rho_bar = " +
                                  std::to_string(p.real("rho_bar")) +
                                  ", viscosity = " + std::to_string(p.real("viscosity")));
    s_.omega = root.omega;
    s_.scheme = parse_mpve_scheme(p.string("scheme"));
    s_.nx = static_cast<int>(p.integer("cells"));
    s_.blowup_factor = p.real("blowup_factor");
    // The coupled system (its factorisations depend on dt) is built by set_time_step, which
    // the run driver calls before anything else.
  }

  std::string name() const override { return "mpve"; }
  /// The solid's leapfrog limit 1 / (cp sqrt(1/hx^2 + 1/hy^2)) with hx = hy = h.
  double stable_dt() const override {
    const auto& P = s_.physics;
    return (1.0 / s_.nx) / (std::sqrt((P.lambda_bar + 2 * P.mu_bar) / P.rho_bar) * std::sqrt(2.0));
  }
  void set_time_step(double dt) override {
    if (!(dt > 0) || dt > stable_dt() * (1 + 1e-12)) {
      std::ostringstream m;
      m << "mpve: dt = " << dt << " outside (0, " << stable_dt() << "], the solid's leapfrog limit";
      throw std::invalid_argument(m.str());
    }
    s_.dt = dt;
    run_ = std::make_unique<MpvePartitioned>(s_);
  }
  void advance(double, double) override { run_->step(); }
  long long work_per_step() const override { return 3LL * s_.nx * s_.nx; }
  std::string work_unit() const override { return "cell-steps"; }

  std::vector<OutputBlock> output(double) const override {
    const auto o = run_->snapshot();
    OutputBlock f;
    f.name = "fluid";
    f.x = o.fluid_x;
    f.y = o.fluid_y;
    f.z = {0.0};
    f.fields = {{"u", o.u},
                {"v", o.v},
                {"p", o.p},
                {"u_exact", o.u_exact},
                {"v_exact", o.v_exact},
                {"p_exact", o.p_exact}};
    OutputBlock s;
    s.name = "solid";
    s.x = o.solid_x;
    s.y = o.solid_y;
    s.z = {0.0};
    s.fields = {{"ubar", o.ubar},
                {"vbar", o.vbar},
                {"ubar_exact", o.ubar_exact},
                {"vbar_exact", o.vbar_exact}};
    return {f, s};
  }
  Diagnostics diagnostics(double) const override {
    const MpveErrors e = run_->errors();
    return {{"max_v", run_->max_fluid_speed()},
            {"subiterations", double(run_->last_subiterations())},
            {"u_error", e.u},
            {"v_error", e.v},
            {"p_error", e.p},
            {"ubar_error", e.ubar},
            {"vbar_error", e.vbar},
            {"sigma_bar_error", e.sigma},
            {"omega_re", s_.omega.real()},
            {"omega_im", s_.omega.imag()}};
  }
  std::string error_diagnostic() const override { return "vbar_error"; }
  std::optional<physics::NonFiniteReport> find_nonfinite() const override {
    if (!run_->blown_up()) return std::nullopt;
    physics::NonFiniteReport r;
    std::ostringstream m;
    m << "the " << to_string(s_.scheme)
      << " coupling is unstable at rho_bar / rho = " << s_.physics.rho_bar / s_.physics.rho
      << " (max |v| = " << run_->max_fluid_speed() << " > " << s_.blowup_factor << " x its start)";
    r.reason = m.str();
    r.field = "v";
    r.block = "fluid";
    return r;
  }
  std::vector<StateBlock> state() const override { return {{"mpve", run_->save()}}; }
  void restore(const std::vector<StateBlock>& blocks) override {
    for (const auto& b : blocks)
      if (b.name == "mpve") run_->restore(b.arrays);
  }
  std::vector<std::string> owned_blocks() const override { return {"mpve"}; }

 private:
  MpveSetup s_;
  std::unique_ptr<MpvePartitioned> run_;
};

}  // namespace

std::unique_ptr<physics::Module> create_mpve(const Parameters& p, const Communicator& comm) {
  return std::make_unique<MpveModule>(p, comm);
}

}  // namespace amphora::coupling::fsi
