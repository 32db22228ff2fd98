#include "coupling/fsi/beam_channel_module.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "coupling/fsi/beam_channel_fsi.hpp"
#include "coupling/fsi/beam_channel_wave.hpp"
#include "mesh/box_decomposition.hpp"

namespace amphora::coupling::fsi {

ParamTable beam_channel_parameter_table() {
  return {
      "beam_channel",
      "a periodic Euler-Bernoulli beam over a channel of inviscid fluid, partitioned (tp | amp), "
      "from the exact traveling wave",
      {
          string_param("scheme", std::string("amp"), "coupling scheme", {"amp", "tp", "tp_aitken"}),
          real_param("rho_h", 1.0, "kg/m^2", above(0.0),
                     "beam mass per unit length (density x thickness)"),
          real_param("spring", 0.5, "N/m^3", at_least(0.0), "K: restoring spring"),
          real_param("tension", 1.0, "N/m", at_least(0.0), "T: tension"),
          real_param("stiffness", 0.01, "N m", at_least(0.0), "B = E I: bending stiffness"),
          real_param("length", 1.0, "m", above(0.0), "period in x"),
          real_param("depth", 0.5, "m", above(0.0), "channel depth H"),
          real_param("density", 1.0, "kg/m^3", above(0.0), "fluid density rho"),
          int_param("points", 80, at_least(8) & at_most(1 << 14),
                    "beam points = fluid columns (h = length / points)"),
          int_param("fluid_rows", 40, at_least(2) & at_most(1 << 14),
                    "fluid cells across the channel"),
          int_param("mode", 1, at_least(1), "wave number k = 2 pi mode / length"),
          real_param("blowup_factor", 10.0, "1", above(1.0),
                     "stop as unstable when max |eta| exceeds this multiple of the amplitude"),
          real_param("subiteration_tolerance", 1e-10, "1", above(0.0),
                     "tp_aitken: relative change of the interface acceleration that ends a step"),
          int_param("max_subiterations", 500, at_least(1),
                    "tp_aitken: sub-iterations allowed per step"),
          real_param("initial_relaxation", 0.1, "1", above(0.0) & at_most(1.0),
                     "tp_aitken: first relaxation factor"),
      }};
}

namespace {

class BeamChannelModule final : public physics::Module {
 public:
  BeamChannelModule(const Parameters& p, const Communicator& comm) {
    if (comm.size() > 1)
      throw mesh::DecompositionError(
          "more ranks (" + std::to_string(comm.size()) +
          ") than blocks (1): the beam-channel problem runs on one rank");
    s_.scheme = parse_beam_scheme(p.string("scheme"));
    s_.beam.rho_h = p.real("rho_h");
    s_.beam.spring = p.real("spring");
    s_.beam.tension = p.real("tension");
    s_.beam.stiffness = p.real("stiffness");
    s_.beam.length = p.real("length");
    s_.beam.points = static_cast<int>(p.integer("points"));
    s_.depth = p.real("depth");
    s_.rho = p.real("density");
    s_.fluid_rows = static_cast<int>(p.integer("fluid_rows"));
    s_.mode = static_cast<int>(p.integer("mode"));
    s_.blowup_factor = p.real("blowup_factor");
    s_.subiteration_tolerance = p.real("subiteration_tolerance");
    s_.max_subiterations = static_cast<int>(p.integer("max_subiterations"));
    s_.initial_relaxation = p.real("initial_relaxation");
    if (2 * s_.mode >= s_.beam.points)
      throw std::invalid_argument("beam_channel.mode = " + std::to_string(s_.mode) +
                                  " is not resolved by points = " + std::to_string(s_.beam.points) +
                                  " (allowed: mode < points / 2)");
    // The coupled system (its factorisations depend on dt) is built by set_time_step, which
    // the run driver calls before anything else: building it here too doubled the start-up.
  }

  std::string name() const override { return "beam_channel"; }
  /// Both schemes are implicit in the beam: the step is set by accuracy, one grid cell of
  /// wave travel (dt = h / phase speed), so dt and h shrink together.
  double stable_dt() const override {
    const double k = 2 * 3.141592653589793 * s_.mode / s_.beam.length;
    const double w = beam_channel_frequency(s_.beam, k, s_.depth, s_.rho);
    return (s_.beam.length / s_.beam.points) * k / w;
  }
  void set_time_step(double dt) override {
    if (!(dt > 0)) throw std::invalid_argument("beam_channel: dt must be > 0");
    s_.dt = dt;
    fsi_ = std::make_unique<BeamChannelFsi>(s_);  // the AMP condition depends on dt
  }
  void advance(double, double) override { fsi_->step(); }
  long long work_per_step() const override {
    return static_cast<long long>(s_.beam.points) * (s_.fluid_rows + 2);
  }
  std::string work_unit() const override { return "point-steps"; }

  std::vector<OutputBlock> output(double t) const override {
    const int nx = s_.beam.points, ny = s_.fluid_rows;
    const auto& g = fsi_->fluid_grid();
    OutputBlock beam;
    beam.name = "beam";
    beam.y = {0.0};
    beam.z = {0.0};
    std::vector<double> exact(nx);
    for (int i = 0; i < nx; ++i) {
      beam.x.push_back(i * g.hx());
      exact[i] = fsi_->exact_eta(i * g.hx(), t);
    }
    beam.fields = {{"eta", fsi_->beam().displacement()},
                   {"eta_t", fsi_->beam().velocity()},
                   {"eta_exact", exact}};
    OutputBlock fluid;
    fluid.name = "fluid";
    fluid.x = beam.x;
    fluid.z = {0.0};
    std::vector<double> p_exact(size_t(ny + 1) * nx);
    for (int j = 0; j <= ny; ++j) {
      fluid.y.push_back(-s_.depth + j * g.hy());
      for (int i = 0; i < nx; ++i)
        p_exact[size_t(j) * nx + i] = fsi_->exact_pressure(i * g.hx(), fluid.y.back(), t);
    }
    fluid.fields = {{"pressure", fsi_->pressure()}, {"pressure_exact", p_exact}};
    return {beam, fluid};
  }

  Diagnostics diagnostics(double) const override {
    return {
        {"max_eta", fsi_->max_abs_eta()}, {"beam_energy", fsi_->beam().energy()},
        {"eta_error", fsi_->eta_error()}, {"pressure_error", fsi_->pressure_error()},
        {"omega", fsi_->omega()},         {"subiterations", double(fsi_->last_subiterations())}};
  }
  std::string error_diagnostic() const override { return "eta_error"; }

  std::optional<physics::NonFiniteReport> find_nonfinite() const override {
    if (!fsi_->blown_up()) return std::nullopt;
    // Unbounded growth is the failure this problem exists to show: stop like a divergence.
    physics::NonFiniteReport r;
    std::ostringstream f;
    f << "the " << to_string(s_.scheme)
      << " coupling is unstable at rho_h / rho = " << s_.beam.rho_h / s_.rho
      << " (max |eta| = " << fsi_->max_abs_eta() << " > " << s_.blowup_factor
      << " x the wave amplitude)";
    r.reason = f.str();
    r.field = "eta";
    r.block = "beam";
    const auto& eta = fsi_->beam().displacement();
    for (size_t i = 0; i < eta.size(); ++i)
      if (!(std::abs(eta[i]) <= s_.blowup_factor)) {
        r.index = static_cast<long long>(i);
        r.x = i * fsi_->fluid_grid().hx();
        break;
      }
    return r;
  }

  std::vector<StateBlock> state() const override {
    const auto& b = fsi_->beam();
    return {{"beam",
             {{"time", {b.time()}},
              {"eta", b.displacement()},
              {"eta_t", b.velocity()},
              {"eta_tt", b.acceleration()}}}};
  }
  void restore(const std::vector<StateBlock>& blocks) override {
    for (const auto& blk : blocks) {
      if (blk.name != "beam") continue;
      std::vector<double> t, eta, v, a;
      for (const auto& [key, values] : blk.arrays) {
        if (key == "time") t = values;
        if (key == "eta") eta = values;
        if (key == "eta_t") v = values;
        if (key == "eta_tt") a = values;
      }
      if (t.size() != 1)
        throw std::runtime_error("beam_channel: checkpoint without the beam's time");
      fsi_->beam().restore_state(t[0], eta, v, a);
      fsi_->refresh_pressure();
    }
  }
  std::vector<std::string> owned_blocks() const override { return {"beam"}; }

 private:
  BeamChannelSetup s_;
  std::unique_ptr<BeamChannelFsi> fsi_;
};

}  // namespace

std::unique_ptr<physics::Module> create_beam_channel(const Parameters& p,
                                                     const Communicator& comm) {
  return std::make_unique<BeamChannelModule>(p, comm);
}

}  // namespace amphora::coupling::fsi
