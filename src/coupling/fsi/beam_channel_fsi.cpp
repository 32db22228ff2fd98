#include "coupling/fsi/beam_channel_fsi.hpp"

#include <array>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "coupling/fsi/beam_channel_wave.hpp"

namespace amphora::fsi {

BeamScheme parse_beam_scheme(const std::string& name) {
  if (name == "tp") return BeamScheme::traditional;
  if (name == "amp") return BeamScheme::amp;
  throw std::invalid_argument("unknown beam coupling scheme '" + name + "' (allowed: tp, amp)");
}

const char* to_string(BeamScheme s) { return s == BeamScheme::amp ? "amp" : "tp"; }

namespace {

/// The exact wave: eta = cos(k x - w t), p = rho w^2 cosh(k (y + H)) / (k sinh kH) cos(k x - w t).
struct ExactWave {
  double k, w, H, rho;
  double eta(double x, double t) const { return std::cos(k * x - w * t); }
  double velocity(double x, double t) const { return w * std::sin(k * x - w * t); }
  double pressure(double x, double y, double t) const {
    return rho * w * w * std::cosh(k * (y + H)) / (k * std::sinh(k * H)) * std::cos(k * x - w * t);
  }
};

}  // namespace

BeamChannelResult run_beam_channel(const BeamChannelSetup& s) {
  const int nx = s.beam.points;
  const double pi = 3.141592653589793;
  channel::ChannelGrid grid;
  grid.nx = nx;
  grid.ny = s.fluid_rows;
  grid.length = s.beam.length;
  grid.depth = s.depth;
  const double k = 2 * pi * s.mode / s.beam.length;
  const ExactWave exact{k, beam_channel_frequency(s.beam, k, s.depth, s.rho), s.depth, s.rho};
  const bool amp = s.scheme == BeamScheme::amp;
  beam::EulerBernoulliBeam solid(s.beam, s.dt);
  // TP: Neumann data p_y = -rho a^n. AMP: the beam's own update, (rho_h + dt^2/4 A) a^{n+1} =
  // p - A eta*, with a^{n+1} = -p_y / rho from the fluid, is the Robin condition
  // p + (rho_h I + dt^2/4 A) p_y / rho = A eta* (the Newmark predictor eta* = eta + dt v +
  // dt^2/4 a). Its leading weight is rho_h / rho; the dt^2 A part is the implicit beam's.
  std::array<double, 5> top{0, 0, 1, 0, 0};
  if (amp) {
    const auto c = solid.stencil();
    for (int o = 0; o < 5; ++o) top[o] = (0.25 * s.dt * s.dt * c[o] + (o == 2 ? s.beam.rho_h : 0.0)) / s.rho;
  }
  const channel::ChannelPressure fluid(grid, amp ? 1.0 : 0.0, top);

  const double hx = grid.hx();
  std::vector<double> eta(nx), v(nx), p_top(nx), g(nx);
  for (int i = 0; i < nx; ++i) {
    eta[i] = exact.eta(i * hx, 0.0);
    v[i] = exact.velocity(i * hx, 0.0);
    p_top[i] = exact.pressure(i * hx, 0.0, 0.0);
  }
  solid.set_state(0.0, eta, v, p_top);

  BeamChannelResult r;
  r.omega = exact.w;
  const int steps = static_cast<int>(std::lround(s.end_time / s.dt));
  std::vector<double> p;
  for (int n = 0; n < steps; ++n) {
    const auto& e = solid.displacement();
    const auto& vel = solid.velocity();
    const auto& a = solid.acceleration();
    double mean_eta = 0;
    for (int i = 0; i < nx; ++i) mean_eta += e[i] / nx;
    if (amp) {
      std::vector<double> predicted(nx);
      for (int i = 0; i < nx; ++i) predicted[i] = e[i] + s.dt * vel[i] + 0.25 * s.dt * s.dt * a[i];
      g = solid.restoring_force(predicted);
      p = fluid.solve(g);
    } else {
      // Volume conservation fixes the constant: the mean of eta_tt vanishes, so the mean of
      // p on the interface balances the spring's K mean(eta).
      for (int i = 0; i < nx; ++i) g[i] = -s.rho * a[i];
      p = fluid.solve(g, s.beam.spring * mean_eta);
    }
    for (int i = 0; i < nx; ++i) p_top[i] = p[size_t(grid.ny) * nx + i];
    solid.step(p_top);
    r.steps = n + 1;
    r.time = solid.time();
    double m = 0;
    bool finite = true;
    for (double x : solid.displacement()) {
      m = std::max(m, std::abs(x));
      finite = finite && std::isfinite(x);
    }
    r.max_eta = std::max(r.max_eta, m);
    if (!finite || m > s.blowup_factor) {
      r.stable = false;
      std::ostringstream msg;
      msg << to_string(s.scheme) << " beam coupling unstable: max |eta| = " << m << " > "
          << s.blowup_factor << " x the wave amplitude at step " << r.steps << ", t = " << r.time
          << " (rho_h / rho = " << s.beam.rho_h / s.rho << ")";
      r.message = msg.str();
      return r;
    }
  }
  for (int i = 0; i < nx; ++i)
    r.eta_error = std::max(r.eta_error, std::abs(solid.displacement()[i] - exact.eta(i * hx, r.time)));
  // The pressure of the last solve belongs to the time of the last step.
  for (int j = 0; j <= grid.ny; ++j)
    for (int i = 0; i < nx; ++i)
      r.pressure_error =
          std::max(r.pressure_error, std::abs(p[size_t(j) * nx + i] -
                                              exact.pressure(i * hx, -s.depth + j * grid.hy(), r.time)));
  return r;
}

}  // namespace amphora::fsi
