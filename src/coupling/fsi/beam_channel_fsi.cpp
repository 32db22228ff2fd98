#include "coupling/fsi/beam_channel_fsi.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "coupling/fsi/beam_channel_wave.hpp"

namespace amphora::coupling::fsi {

BeamScheme parse_beam_scheme(const std::string& name) {
  if (name == "tp") return BeamScheme::traditional;
  if (name == "tp_aitken") return BeamScheme::traditional_aitken;
  if (name == "amp") return BeamScheme::amp;
  throw std::invalid_argument("unknown beam coupling scheme '" + name +
                              "' (allowed: tp, tp_aitken, amp)");
}

const char* to_string(BeamScheme s) {
  return s == BeamScheme::amp ? "amp" : s == BeamScheme::traditional ? "tp" : "tp_aitken";
}

namespace {

physics::channel_flow::ChannelGrid fluid_grid_of(const BeamChannelSetup& s) {
  physics::channel_flow::ChannelGrid g;
  g.nx = s.beam.points;
  g.ny = s.fluid_rows;
  g.length = s.beam.length;
  g.depth = s.depth;
  return g;
}

/// TP: Neumann data p_y = -rho a^n (B = identity). AMP: the beam's own update,
/// (rho_h + dt^2/4 A) a^{n+1} = p - A eta*, with a^{n+1} = -p_y / rho from the fluid, is the
/// Robin condition p + (rho_h I + dt^2/4 A) p_y / rho = A eta* (Newmark predictor eta* = eta +
/// dt v + dt^2/4 a). Its leading weight is rho_h / rho; the dt^2 A part is the implicit beam's.
physics::channel_flow::ChannelPressure fluid_of(const BeamChannelSetup& s,
                                                const physics::beam::EulerBernoulliBeam& b) {
  std::array<double, 5> top{0, 0, 1, 0, 0};
  const bool amp = s.scheme == BeamScheme::amp;
  if (amp) {
    const auto c = b.stencil();
    for (int o = 0; o < 5; ++o)
      top[o] = (0.25 * s.dt * s.dt * c[o] + (o == 2 ? s.beam.rho_h : 0.0)) / s.rho;
  }
  return physics::channel_flow::ChannelPressure(fluid_grid_of(s), amp ? 1.0 : 0.0, top);
}

}  // namespace

BeamChannelFsi::BeamChannelFsi(const BeamChannelSetup& s)
    : s_(s),
      grid_(fluid_grid_of(s)),
      k_(2 * 3.141592653589793 * s.mode / s.beam.length),
      omega_(beam_channel_frequency(s.beam, k_, s.depth, s.rho)),
      beam_(s.beam, s.dt),
      fluid_(fluid_of(s, beam_)) {
  const int nx = s.beam.points;
  const double hx = grid_.hx();
  std::vector<double> eta(nx), v(nx), p_top(nx);
  for (int i = 0; i < nx; ++i) {
    eta[i] = exact_eta(i * hx, 0.0);
    v[i] = omega_ * std::sin(k_ * i * hx);
    p_top[i] = exact_pressure(i * hx, 0.0, 0.0);
  }
  beam_.set_state(0.0, eta, v, p_top);
  p_.assign(size_t(grid_.ny + 1) * nx, 0.0);
  for (int j = 0; j <= grid_.ny; ++j)
    for (int i = 0; i < nx; ++i)
      p_[size_t(j) * nx + i] = exact_pressure(i * hx, -s.depth + j * grid_.hy(), 0.0);
}

double BeamChannelFsi::exact_eta(double x, double t) const { return std::cos(k_ * x - omega_ * t); }

double BeamChannelFsi::exact_pressure(double x, double y, double t) const {
  return s_.rho * omega_ * omega_ * std::cosh(k_ * (y + s_.depth)) /
         (k_ * std::sinh(k_ * s_.depth)) * std::cos(k_ * x - omega_ * t);
}

void BeamChannelFsi::step() {
  const int nx = grid_.nx;
  const size_t top = size_t(grid_.ny) * nx;
  double mean_eta = 0;
  for (int i = 0; i < nx; ++i) mean_eta += beam_.displacement()[i] / nx;
  // TP's fluid: p_y = -rho a on the interface; volume conservation fixes the constant (the
  // mean of eta_tt vanishes, so the interface mean of p balances the spring's K mean(eta)).
  auto tp_pressure = [&](const std::vector<double>& a) {
    std::vector<double> g(nx);
    for (int i = 0; i < nx; ++i) g[i] = -s_.rho * a[i];
    return fluid_.solve(g, s_.beam.spring * mean_eta);
  };
  auto interface = [&](const std::vector<double>& p) {
    return std::vector<double>(p.begin() + top, p.begin() + top + nx);
  };
  std::vector<double> p;
  subiterations_ = 1;
  if (s_.scheme == BeamScheme::amp) {
    p = fluid_.solve(beam_.restoring_force(beam_.predictor()));
    beam_.step(interface(p));
  } else if (s_.scheme == BeamScheme::traditional) {
    p = tp_pressure(beam_.acceleration());
    beam_.step(interface(p));
  } else {
    // Fixed point a -> beam(fluid(a)) with Aitken's relaxation, from the last acceleration.
    std::vector<double> a = beam_.acceleration(), r_old;
    double omega = s_.initial_relaxation;
    for (subiterations_ = 1;; ++subiterations_) {
      p = tp_pressure(a);
      const std::vector<double> trial = beam_.acceleration_after(interface(p));
      std::vector<double> r(nx);
      double rr = 0, aa = 0;
      for (int i = 0; i < nx; ++i) {
        r[i] = trial[i] - a[i];
        rr += r[i] * r[i];
        aa += trial[i] * trial[i];
      }
      if (rr <= s_.subiteration_tolerance * s_.subiteration_tolerance * aa) {
        a = trial;
        break;
      }
      if (subiterations_ >= s_.max_subiterations || !std::isfinite(rr)) {
        std::ostringstream m;
        m << "tp_aitken: the sub-iterations did not converge in " << subiterations_
          << " at t = " << time() << " (relative update " << std::sqrt(rr / aa) << ")";
        throw std::runtime_error(m.str());
      }
      if (!r_old.empty()) {  // omega <- -omega (r_old . (r - r_old)) / |r - r_old|^2
        double num = 0, den = 0;
        for (int i = 0; i < nx; ++i) {
          const double d = r[i] - r_old[i];
          num += r_old[i] * d;
          den += d * d;
        }
        omega = -omega * num / den;
      }
      for (int i = 0; i < nx; ++i) a[i] += omega * r[i];
      r_old = std::move(r);
    }
    beam_.advance_with(a);
  }
  p.resize(top + nx);  // drop the ghost line
  p_ = std::move(p);
}

void BeamChannelFsi::refresh_pressure() {
  // The pressure that balances the current acceleration: p_y = -rho a on the interface.
  const int nx = grid_.nx;
  std::vector<double> g(nx);
  double mean_eta = 0;
  for (int i = 0; i < nx; ++i) {
    g[i] = -s_.rho * beam_.acceleration()[i];
    mean_eta += beam_.displacement()[i] / nx;
  }
  std::array<double, 5> neumann{0, 0, 1, 0, 0};
  const physics::channel_flow::ChannelPressure neumann_fluid(grid_, 0.0, neumann);
  p_ = neumann_fluid.solve(g, s_.beam.spring * mean_eta);
  p_.resize(size_t(grid_.ny + 1) * nx);
}

double BeamChannelFsi::max_abs_eta() const {
  double m = 0;
  for (double x : beam_.displacement()) m = std::isfinite(x) ? std::max(m, std::abs(x)) : INFINITY;
  return m;
}

bool BeamChannelFsi::blown_up() const { return !(max_abs_eta() <= s_.blowup_factor); }

double BeamChannelFsi::eta_error() const {
  double e = 0;
  for (int i = 0; i < grid_.nx; ++i)
    e = std::max(e, std::abs(beam_.displacement()[i] - exact_eta(i * grid_.hx(), time())));
  return e;
}

double BeamChannelFsi::pressure_error() const {
  double e = 0;
  for (int j = 0; j <= grid_.ny; ++j)
    for (int i = 0; i < grid_.nx; ++i)
      e = std::max(e, std::abs(p_[size_t(j) * grid_.nx + i] -
                               exact_pressure(i * grid_.hx(), -s_.depth + j * grid_.hy(), time())));
  return e;
}

BeamChannelResult run_beam_channel(const BeamChannelSetup& s) {
  BeamChannelFsi fsi(s);
  BeamChannelResult r;
  r.omega = fsi.omega();
  const int steps = static_cast<int>(std::lround(s.end_time / s.dt));
  long long subiterations = 0;
  for (int n = 0; n < steps; ++n) {
    fsi.step();
    subiterations += fsi.last_subiterations();
    r.mean_subiterations = double(subiterations) / (n + 1);
    r.steps = n + 1;
    r.time = fsi.time();
    const double m = fsi.max_abs_eta();
    r.max_eta = std::max(r.max_eta, m);
    if (fsi.blown_up()) {
      r.stable = false;
      std::ostringstream msg;
      msg << to_string(s.scheme) << " beam coupling unstable: max |eta| = " << m << " > "
          << s.blowup_factor << " x the wave amplitude at step " << r.steps << ", t = " << r.time
          << " (rho_h / rho = " << s.beam.rho_h / s.rho << ")";
      r.message = msg.str();
      return r;
    }
  }
  r.eta_error = fsi.eta_error();
  r.pressure_error = fsi.pressure_error();
  return r;
}

BeamChannelSetup beam_channel_wave_case(double rho_h, int points, BeamScheme scheme) {
  BeamChannelSetup s;
  s.beam.length = 1.0;
  s.beam.rho_h = rho_h;
  s.beam.spring = 0.5;
  s.beam.tension = 1.0;
  s.beam.stiffness = 0.01;
  s.beam.points = points;
  s.depth = 0.5;
  s.rho = 1.0;
  s.fluid_rows = points / 2;
  s.scheme = scheme;
  s.end_time = 0.5;
  const double w = beam_channel_frequency(s.beam, 2 * M_PI, s.depth, s.rho);
  const int m = std::max(1, static_cast<int>(std::ceil(s.end_time * w / M_PI)));
  s.dt = s.end_time / (m * points);
  return s;
}

}  // namespace amphora::coupling::fsi
