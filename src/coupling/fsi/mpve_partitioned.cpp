#include "coupling/fsi/mpve_partitioned.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <stdexcept>
#include <type_traits>
#include <sstream>

#include "physics/channel_flow/channel_stokes.hpp"
#include "physics/elastic_solid/linear_elastic_solid.hpp"

namespace amphora::coupling::fsi {

namespace {

using Host = Kokkos::DefaultHostExecutionSpace;
using Solid = physics::elastic_solid::LinearElasticSolid<Host>;

/// The exact solid displacement, as the solid's initial-value functor.
struct ExactDisplacement {
  MpveParameters p;
  Complex w;
  std::array<Complex, 8> c;
  double operator()(double x, double y, double t, int comp) const {
    const MpveSolidFields s = mpve_solid(p, w, c, x, y, t);
    return comp == 0 ? s.ubar : s.vbar;
  }
};

/// Node values of a traction (component c at column i = x / hx).
struct NodeTraction {
  Kokkos::View<double* [2], Kokkos::HostSpace> values;
  double hx;
  double operator()(double x, double, int c) const {
    return values(std::lround(x / hx) % values.extent(0), c);
  }
};

struct Fixed {
  double operator()(double, double, double, int) const { return 0.0; }
};

std::optional<physics::channel_flow::TopImpedance> fluid_top(const MpveSetup& s) {
  if (s.scheme != MpveScheme::amp) return std::nullopt;
  const auto& P = s.physics;
  return physics::channel_flow::TopImpedance{std::sqrt(P.rho_bar * (P.lambda_bar + 2 * P.mu_bar)),
                                             std::sqrt(P.rho_bar * P.mu_bar)};
}

}  // namespace

const char* to_string(MpveScheme s) {
  return s == MpveScheme::amp ? "amp" : s == MpveScheme::tp_aitken ? "tp_aitken" : "tp";
}

MpveScheme parse_mpve_scheme(const std::string& name) {
  if (name == "amp") return MpveScheme::amp;
  if (name == "tp") return MpveScheme::tp;
  if (name == "tp_aitken") return MpveScheme::tp_aitken;
  throw std::invalid_argument("mpve: scheme '" + name + "' is not one of amp, tp, tp_aitken");
}

struct MpvePartitioned::State {
  MpveSetup s;
  std::array<Complex, 8> mode;
  physics::channel_flow::ChannelGrid fg;
  physics::elastic_solid::ElasticGrid sg;
  physics::channel_flow::ChannelStokes fluid;
  Solid solid;
  std::vector<double> p_prev;             // fluid pressure at t - 3 dt / 2
  std::vector<double> row_prev, row_now;  // solid interface displacement (u, v) at t - dt, t
  std::vector<double> gu_now, gv_now;  // the fluid's wall velocity at t (u at x_i, v at x_{i+1/2})
  std::vector<double> gv_prev;         // AMP: the fluid's wall v at t - dt
  std::vector<double> g_now;           // AMP: the characteristics sent at t (x, y per node)
  std::vector<double> traction_prev;   // TP-Aitken: the traction at t - dt (x, y per node)
  physics::channel_flow::TopImpedance z;  // AMP: the solid's impedances (z_p, z_s)
  double z_fluid = 0;                     // AMP: the discrete fluid's impedance (fluid_traction)
  int subiterations = 1;                  // of the last step
  double v_scale = 0;
  Kokkos::View<double* [2], Kokkos::HostSpace>
      traction;  // the fluid's, on the solid's interface nodes

  static physics::channel_flow::ChannelGrid fluid_grid(const MpveSetup& s) {
    const double L = 2 * M_PI / s.physics.k, h = L / s.nx;
    return {s.nx, std::max(2, int(std::lround(s.physics.H / h))), L, s.physics.H};
  }
  static physics::elastic_solid::ElasticGrid solid_grid(const MpveSetup& s) {
    const double L = 2 * M_PI / s.physics.k, h = L / s.nx;
    const int ny = std::max(2, int(std::lround(s.physics.Hbar / h)));
    return {s.nx, ny, h, s.physics.Hbar / ny};
  }

  explicit State(const MpveSetup& setup)
      : s(setup),
        mode(mpve_mode(setup.physics, setup.omega)),
        fg(fluid_grid(setup)),
        sg(solid_grid(setup)),
        fluid(fg, setup.physics.rho, setup.physics.mu, setup.dt, fluid_top(setup)),
        solid(sg, {setup.physics.rho_bar, setup.physics.lambda_bar, setup.physics.mu_bar},
              setup.dt) {
    const int nx = fg.nx, ny = fg.ny;
    const auto& P = s.physics;
    auto F = [&](double x, double y, double t) { return mpve_fluid(P, s.omega, mode, x, y, t); };
    std::vector<double> u(size_t(nx) * ny), v(size_t(nx) * (ny + 1)), p(size_t(nx) * ny);
    p_prev.resize(p.size());
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i < nx; ++i) {
        v[size_t(j) * nx + i] = F(fluid.v_x(i), fluid.v_y(j), 0.0).v;
        v_scale = std::max(v_scale, std::abs(v[size_t(j) * nx + i]));
        if (j == ny) continue;
        u[size_t(j) * nx + i] = F(fluid.u_x(i), fluid.u_y(j), 0.0).u;
        p[size_t(j) * nx + i] = F(fluid.v_x(i), fluid.u_y(j), -0.5 * s.dt).p;
        p_prev[size_t(j) * nx + i] = F(fluid.v_x(i), fluid.u_y(j), -1.5 * s.dt).p;
      }
    gu_now.resize(nx);
    gv_now.resize(nx);
    gv_prev.resize(nx);
    for (int i = 0; i < nx; ++i) {
      gu_now[i] = F(fluid.u_x(i), 0.0, 0.0).u;
      gv_now[i] = F(fluid.v_x(i), 0.0, 0.0).v;
      gv_prev[i] = F(fluid.v_x(i), 0.0, -s.dt).v;
    }
    fluid.set_state(0.0, u, v, p, s.scheme == MpveScheme::amp ? gu_now : std::vector<double>{});
    solid.set_state(0.0, ExactDisplacement{P, s.omega, mode});
    row_now = interface_row(solid.displacement());
    row_prev = interface_row(solid.previous());
    traction = Kokkos::View<double* [2], Kokkos::HostSpace>("amphora::mpve::traction", nx);
    for (int i = 0; i < nx; ++i) {  // the exact interface traction at t - dt
      const MpveSolidFields e = mpve_solid(P, s.omega, mode, i * sg.hx, 0.0, -s.dt);
      traction_prev.push_back(e.sxy);
      traction_prev.push_back(e.syy);
    }
    if (s.scheme == MpveScheme::amp) {
      z = *fluid_top(s);
      z_fluid = P.rho * fg.hy() / s.dt + 2 * P.mu / fg.hy();
      for (int i = 0; i < nx; ++i) {
        const MpveSolidFields e = mpve_solid(P, s.omega, mode, i * sg.hx, 0.0, 0.0);
        g_now.push_back(e.sxy + z.z_shear * e.ubar_t);
        g_now.push_back(e.syy + z.z_normal * e.vbar_t);
      }
    }
  }

  /// The coupling's own state arrays (beside the fluid's and the solid's fields), by checkpoint
  /// name: save() and restore() both go through this one list.
  template <class Self>
  static auto coupling_arrays(Self& st) {
    using Array =
        std::conditional_t<std::is_const_v<Self>, const std::vector<double>, std::vector<double>>;
    return std::vector<std::pair<const char*, Array*>>{
        {"p_prev", &st.p_prev},   {"row_prev", &st.row_prev},
        {"row_now", &st.row_now}, {"gu_now", &st.gu_now},
        {"gv_now", &st.gv_now},   {"gv_prev", &st.gv_prev},
        {"g_now", &st.g_now},     {"traction_prev", &st.traction_prev}};
  }

  std::vector<double> interface_row(const Solid::Field& f) const {
    std::vector<double> r(2 * size_t(sg.nx));
    for (int i = 0; i < sg.nx; ++i) {
      r[2 * i] = f(1, i, 0);  // storage row 1 = grid row 0, the interface
      r[2 * i + 1] = f(1, i, 1);
    }
    return r;
  }

  void step() {
    // 1. The fluid's traction at t on the solid's interface nodes x_i.
    fluid_traction(traction);
    if (s.scheme == MpveScheme::tp_aitken) return aitken_step();
    // 2. The solid to t + dt (AMP: its predictor).
    solid.step_with_bottom_traction(NodeTraction{traction, sg.hx}, Fixed{});
    Kokkos::fence();
    if (s.scheme == MpveScheme::amp) return amp_fluid_and_corrector();
    tp_fluid();
  }

  /// The traction the solid takes at t (x, y per node): the fluid's, one-sided differences of
  /// its velocity and its pressure extrapolated from t - dt/2, t - 3dt/2 (AMP: see below).
  void fluid_traction(const Kokkos::View<double* [2], Kokkos::HostSpace>& tr) const {
    const int nx = fg.nx, ny = fg.ny;
    const double mu = s.physics.mu, hx = fg.hx(), hy = fg.hy();
    auto wrap = [nx](int i) { return (i % nx + nx) % nx; };
    const auto& u = fluid.u();
    const auto& p = fluid.p();
    for (int i = 0; i < nx; ++i) {
      const double g = gu_now[i];
      const double u_y =
          (8 * g - 9 * u[size_t(ny - 1) * nx + i] + u[size_t(ny - 2) * nx + i]) / (3 * hy);
      const double v_x = (gv_now[i] - gv_now[wrap(i - 1)]) / hx;
      const double v_y =
          -(gu_now[wrap(i + 1)] - gu_now[wrap(i - 1)]) / (2 * hx);  // div v = 0 on the wall
      auto wall_p = [&](const std::vector<double>& q, int col) {    // to y = 0, second order
        return 0.5 * (3 * q[size_t(ny - 1) * nx + col] - q[size_t(ny - 2) * nx + col]);
      };
      auto at_xi = [&](const std::vector<double>& q) {
        return 0.5 * (wall_p(q, wrap(i - 1)) + wall_p(q, i));
      };
      const double p0 = 0.5 * (3 * at_xi(p) - at_xi(p_prev));  // t - dt/2, t - 3dt/2 -> t
      tr(i, 0) = mu * (u_y + v_x);
      tr(i, 1) = -p0 + 2 * mu * v_y;
      if (s.scheme == MpveScheme::amp) {
        // AMP: the impedance-weighted interface traction, between the fluid's own and the one
        // consistent with the characteristics sent at t and the interface velocity (g - z v),
        // weighted by the solid's impedance and the discrete fluid's, z_f = rho h / dt + 2 mu / h
        // (the first cell's pressure and normal viscous stress per unit change of the interface
        // velocity in one step). A light solid must not see the fluid's traction (its errors
        // enter the predictor divided by rho_bar: blow-up at rho_bar/rho = 1e-3, h = 1/160); a
        // heavy one must not see g - z v (errors in v enter multiplied by z: rho_bar/rho = 1e3,
        // h = 1/80 blew up at t = 2.1); without the viscous part rho_bar/rho = 10 and 1 blew up
        // at h = 1/320, mu = 0.02.
        const double zf = z_fluid;
        const double v_i = 0.5 * (gv_now[wrap(i - 1)] + gv_now[i]);
        auto weigh = [zf](double own, double solid_side, double zs) {
          return (zs * own + zf * solid_side) / (zs + zf);
        };
        tr(i, 0) = weigh(tr(i, 0), g_now[2 * i] - z.z_shear * gu_now[i], z.z_shear);
        tr(i, 1) = weigh(tr(i, 1), g_now[2 * i + 1] - z.z_normal * v_i, z.z_normal);
      }
    }
  }

  /// TP after the solid's step: the solid's interface velocity at t and t + dt as the fluid's
  /// wall data, the fluid to t + dt.
  void tp_fluid() {
    const int nx = fg.nx;
    const double hx = fg.hx(), dt = s.dt;
    auto wrap = [nx](int i) { return (i % nx + nx) % nx; };
    const std::vector<double> row_next = interface_row(solid.displacement());
    // 3. The solid's interface velocity at t (centred) and t + dt (one-sided), as wall data.
    std::vector<double> gu0(nx), gv0(nx), gu1(nx), gv1(nx), vel0(2 * nx), vel1(2 * nx);
    for (int k = 0; k < 2 * nx; ++k) {
      vel0[k] = (row_next[k] - row_prev[k]) / (2 * dt);
      vel1[k] = (3 * row_next[k] - 4 * row_now[k] + row_prev[k]) / (2 * dt);
    }
    for (int i = 0; i < nx; ++i) {
      gu0[i] = vel0[2 * i];
      gu1[i] = vel1[2 * i];
      gv0[i] = 0.5 * (vel0[2 * i + 1] + vel0[2 * wrap(i + 1) + 1]);
      gv1[i] = 0.5 * (vel1[2 * i + 1] + vel1[2 * wrap(i + 1) + 1]);
    }
    // 4. The fluid to t + dt.
    const double t0 = fluid.time();
    auto pick = [t0, dt](const std::vector<double>& a, const std::vector<double>& b,
                         double t) -> const std::vector<double>& {
      return std::abs(t - t0) < 0.25 * dt ? a : b;
    };
    physics::channel_flow::StokesData d;
    d.fx = d.fy = [](double, double, double) { return 0.0; };
    d.u_bottom = d.v_bottom = [](double, double) { return 0.0; };
    d.u_top = [&](double x, double t) { return pick(gu0, gu1, t)[wrap(int(std::lround(x / hx)))]; };
    d.v_top = [&](double x, double t) { return pick(gv0, gv1, t)[wrap(int(std::floor(x / hx)))]; };
    p_prev = fluid.p();
    fluid.step(d);
    row_prev = row_now;
    row_now = row_next;
    gu_now = gu1;
    gv_now = gv1;
  }

  /// TP with sub-iterations (Kuettler & Wall 2008, Aitken's dynamic relaxation) on the traction
  /// at t + dt: the solid's interface row takes (s_{n+1} + 2 s_n + s_{n-1}) / 4 (second order,
  /// and implicit in s_{n+1} like Newmark's average acceleration, so the converged iteration
  /// is stable for any density ratio); each sub-iteration redoes the solid's and the fluid's
  /// step from the saved state until the fluid's traction at t + dt matches the guess.
  void aitken_step() {
    const int nx = fg.nx;
    auto field = [](const Solid::Field& f) {
      return std::vector<double>(f.data(), f.data() + f.size());
    };
    const double t0 = fluid.time();
    const std::vector<double> su = field(solid.displacement()), so = field(solid.previous());
    const std::vector<double> fu = fluid.u(), fv = fluid.v(), fp = fluid.p(), pp = p_prev;
    const std::vector<double> rp = row_prev, rn = row_now, gu = gu_now, gv = gv_now;
    std::vector<double> s_now(2 * nx), guess(2 * nx), r(2 * nx), r_old(2 * nx);
    for (int i = 0; i < nx; ++i)
      for (int c = 0; c < 2; ++c) {
        s_now[2 * i + c] = traction(i, c);
        guess[2 * i + c] = 2 * s_now[2 * i + c] - traction_prev[2 * i + c];
      }
    double omega = s.initial_relaxation;
    int k = 0;
    for (;; ++k) {
      if (k > 0) {
        solid.restore(t0, su, so);
        fluid.set_state(t0, fu, fv, fp);
        p_prev = pp;
        row_prev = rp;
        row_now = rn;
        gu_now = gu;
        gv_now = gv;
      }
      for (int i = 0; i < nx; ++i)
        for (int c = 0; c < 2; ++c)
          traction(i, c) =
              0.25 * (guess[2 * i + c] + 2 * s_now[2 * i + c] + traction_prev[2 * i + c]);
      solid.step_with_bottom_traction(NodeTraction{traction, sg.hx}, Fixed{});
      Kokkos::fence();
      tp_fluid();
      fluid_traction(traction);  // the fluid's at t + dt
      double rr = 0, ss = 0, dr_r = 0, dr_dr = 0;
      for (int j = 0; j < 2 * nx; ++j) {
        r[j] = traction(j / 2, j % 2) - guess[j];
        rr += r[j] * r[j];
        ss += traction(j / 2, j % 2) * traction(j / 2, j % 2);
        dr_r += r_old[j] * (r[j] - r_old[j]);
        dr_dr += (r[j] - r_old[j]) * (r[j] - r_old[j]);
      }
      if (!std::isfinite(rr) ||
          rr <= s.subiteration_tolerance * s.subiteration_tolerance * std::max(ss, 1e-300) ||
          k + 1 >= s.max_subiterations)
        break;
      if (k > 0 && dr_dr > 0) omega = -omega * dr_r / dr_dr;
      for (int j = 0; j < 2 * nx; ++j) guess[j] += omega * r[j];
      r_old = r;
    }
    traction_prev = s_now;
    subiterations = k + 1;
  }

  /// AMP after the solid's predictor: the fluid with the solid's outgoing characteristics at
  /// t + dt as its impedance top, then the solid's interface row moved with the fluid.
  void amp_fluid_and_corrector() {
    const int nx = fg.nx;
    const double dt = s.dt, hy = sg.hy, hx = sg.hx;
    const auto& P = s.physics;
    const double lb = P.lambda_bar, mb = P.mu_bar;
    auto wrap = [nx](int i) { return (i % nx + nx) % nx; };
    const auto d = solid.displacement();  // predicted; storage row 1 = the interface
    const std::vector<double> row_pred = interface_row(d);
    // The outgoing characteristics at the nodes: one-sided y derivatives, centred x ones,
    // velocities by BDF2.
    std::vector<double> gx(nx), gy_node(nx), gy(nx);
    for (int i = 0; i < nx; ++i) {
      const int e = wrap(i + 1), w = wrap(i - 1);
      auto dy = [&](int c) { return (-3 * d(1, i, c) + 4 * d(2, i, c) - d(3, i, c)) / (2 * hy); };
      auto dx = [&](int c) { return (d(1, e, c) - d(1, w, c)) / (2 * hx); };
      auto vel = [&](int c) {
        return (3 * row_pred[2 * i + c] - 4 * row_now[2 * i + c] + row_prev[2 * i + c]) / (2 * dt);
      };
      gx[i] = mb * (dy(0) + dx(1)) + z.z_shear * vel(0);
      gy_node[i] = (lb + 2 * mb) * dy(1) + lb * dx(0) + z.z_normal * vel(1);
    }
    for (int i = 0; i < nx; ++i) {
      gy[i] = 0.5 * (gy_node[i] + gy_node[wrap(i + 1)]);
      g_now[2 * i] = gx[i];
      g_now[2 * i + 1] = gy_node[i];
    }
    std::vector<double> v_guess(nx);  // the interface's normal velocity at t + dt, extrapolated
    for (int i = 0; i < nx; ++i) v_guess[i] = 2 * gv_now[i] - gv_prev[i];
    const double hf = fg.hx();
    physics::channel_flow::StokesData data;
    data.fx = data.fy = [](double, double, double) { return 0.0; };
    data.u_bottom = data.v_bottom = [](double, double) { return 0.0; };
    data.u_top = [](double, double) { return 0.0; };
    data.v_top = [&](double x, double) { return v_guess[wrap(int(std::floor(x / hf)))]; };
    data.g_top_x = [&](double x, double) { return gx[wrap(int(std::lround(x / hf)))]; };
    data.g_top_y = [&](double x, double) { return gy[wrap(int(std::floor(x / hf)))]; };
    p_prev = fluid.p();
    fluid.step(data);
    // The fluid's interface velocity at t + dt; the solid's interface row follows it.
    const std::vector<double>& gu1 = fluid.top_state();
    std::vector<double> gv1(fluid.v().end() - nx, fluid.v().end());
    std::vector<double> row_next(2 * nx);
    for (int i = 0; i < nx; ++i) {
      const double v0 = 0.5 * (gv_now[wrap(i - 1)] + gv_now[i]),
                   v1 = 0.5 * (gv1[wrap(i - 1)] + gv1[i]);
      row_next[2 * i] = row_now[2 * i] + 0.5 * dt * (gu_now[i] + gu1[i]);
      row_next[2 * i + 1] = row_now[2 * i + 1] + 0.5 * dt * (v0 + v1);
      d(1, i, 0) = row_next[2 * i];
      d(1, i, 1) = row_next[2 * i + 1];
    }
    row_prev = row_now;
    row_now = row_next;
    gu_now = gu1;
    gv_prev = gv_now;
    gv_now = gv1;
  }
};

MpvePartitioned::MpvePartitioned(const MpveSetup& s) : s_(std::make_unique<State>(s)) {}
MpvePartitioned::~MpvePartitioned() = default;
void MpvePartitioned::step() { s_->step(); }
double MpvePartitioned::time() const { return s_->fluid.time(); }

double MpvePartitioned::max_fluid_speed() const {
  double m = 0;
  for (double x : s_->fluid.v()) m = std::isfinite(x) ? std::max(m, std::abs(x)) : INFINITY;
  return m;
}

bool MpvePartitioned::blown_up() const {
  return !(max_fluid_speed() <= s_->s.blowup_factor * s_->v_scale);
}

MpvePartitioned::Snapshot MpvePartitioned::snapshot() const {
  const State& st = *s_;
  const auto& P = st.s.physics;
  const auto& f = st.fluid;
  const int nx = st.fg.nx, ny = st.fg.ny;
  const double t = time(), tp = t - 0.5 * st.s.dt;
  Snapshot o;
  for (int i = 0; i < nx; ++i) o.fluid_x.push_back(f.v_x(i));
  for (int j = 0; j < ny; ++j) o.fluid_y.push_back(f.u_y(j));
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const size_t r = size_t(j) * nx + i;
      o.u.push_back(0.5 * (f.u()[r] + f.u()[size_t(j) * nx + (i + 1) % nx]));
      o.v.push_back(0.5 * (f.v()[r] + f.v()[r + nx]));
      o.p.push_back(f.p()[r]);
      const MpveFluidFields e = mpve_fluid(P, st.s.omega, st.mode, f.v_x(i), f.u_y(j), t);
      o.u_exact.push_back(e.u);
      o.v_exact.push_back(e.v);
      o.p_exact.push_back(mpve_fluid(P, st.s.omega, st.mode, f.v_x(i), f.u_y(j), tp).p);
    }
  const auto d = st.solid.displacement();
  for (int i = 0; i < nx; ++i) o.solid_x.push_back(i * st.sg.hx);
  for (int j = 0; j <= st.sg.ny; ++j) o.solid_y.push_back(j * st.sg.hy);
  for (int j = 0; j <= st.sg.ny; ++j)
    for (int i = 0; i < nx; ++i) {
      o.ubar.push_back(d(j + 1, i, 0));
      o.vbar.push_back(d(j + 1, i, 1));
      const MpveSolidFields e = mpve_solid(P, st.s.omega, st.mode, i * st.sg.hx, j * st.sg.hy, t);
      o.ubar_exact.push_back(e.ubar);
      o.vbar_exact.push_back(e.vbar);
    }
  return o;
}

std::vector<std::pair<std::string, std::vector<double>>> MpvePartitioned::save() const {
  const State& st = *s_;
  auto field = [](const Solid::Field& f) {
    return std::vector<double>(f.data(), f.data() + f.size());
  };
  std::vector<std::pair<std::string, std::vector<double>>> out = {
      {"time", {time()}},
      {"u", st.fluid.u()},
      {"v", st.fluid.v()},
      {"p", st.fluid.p()},
      {"solid", field(st.solid.displacement())},
      {"solid_prev", field(st.solid.previous())}};
  for (const auto& [name, array] : State::coupling_arrays(st)) out.emplace_back(name, *array);
  return out;
}

void MpvePartitioned::restore(
    const std::vector<std::pair<std::string, std::vector<double>>>& arrays) {
  State& st = *s_;
  std::map<std::string, std::vector<double>> a(arrays.begin(), arrays.end());
  auto need = [&a](const std::string& key) -> const std::vector<double>& {
    if (!a.count(key)) throw std::runtime_error("mpve: checkpoint lacks '" + key + "'");
    return a[key];
  };
  const double t = need("time").at(0);
  for (const auto& [name, array] : State::coupling_arrays(st)) *array = need(name);
  st.fluid.set_state(t, need("u"), need("v"), need("p"),
                     st.s.scheme == MpveScheme::amp ? st.gu_now : std::vector<double>{});
  st.solid.restore(t, need("solid"), need("solid_prev"));
}

int MpvePartitioned::last_subiterations() const { return s_->subiterations; }

MpveErrors MpvePartitioned::errors() const {
  const State& st = *s_;
  const auto& P = st.s.physics;
  const int nx = st.fg.nx, ny = st.fg.ny;
  const double t = time(), tp = t - 0.5 * st.s.dt;
  MpveErrors e;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const auto& f = st.fluid;
      e.v = std::max(e.v, std::abs(f.v()[size_t(j) * nx + i] -
                                   mpve_fluid(P, st.s.omega, st.mode, f.v_x(i), f.v_y(j), t).v));
      if (j == ny) continue;
      e.u = std::max(e.u, std::abs(f.u()[size_t(j) * nx + i] -
                                   mpve_fluid(P, st.s.omega, st.mode, f.u_x(i), f.u_y(j), t).u));
      e.p = std::max(e.p, std::abs(f.p()[size_t(j) * nx + i] -
                                   mpve_fluid(P, st.s.omega, st.mode, f.v_x(i), f.u_y(j), tp).p));
    }
  const auto d = st.solid.displacement();
  const double hx = st.sg.hx, hy = st.sg.hy, lb = P.lambda_bar, mb = P.mu_bar;
  for (int j = 0; j <= st.sg.ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const MpveSolidFields ex = mpve_solid(P, st.s.omega, st.mode, i * hx, j * hy, t);
      e.ubar = std::max(e.ubar, std::abs(d(j + 1, i, 0) - ex.ubar));
      e.vbar = std::max(e.vbar, std::abs(d(j + 1, i, 1) - ex.vbar));
      if (j == 0 || j == st.sg.ny) continue;
      const int ie = (i + 1) % nx, iw = (i + nx - 1) % nx;
      const double ux = (d(j + 1, ie, 0) - d(j + 1, iw, 0)) / (2 * hx),
                   uy = (d(j + 2, i, 0) - d(j, i, 0)) / (2 * hy);
      const double vx = (d(j + 1, ie, 1) - d(j + 1, iw, 1)) / (2 * hx),
                   vy = (d(j + 2, i, 1) - d(j, i, 1)) / (2 * hy);
      e.sigma = std::max({e.sigma, std::abs(lb * (ux + vy) + 2 * mb * ux - ex.sxx),
                          std::abs(mb * (uy + vx) - ex.sxy),
                          std::abs(lb * (ux + vy) + 2 * mb * vy - ex.syy)});
    }
  return e;
}

MpveRun run_mpve(const MpveSetup& s) {
  MpvePartitioned m(s);
  MpveRun r;
  long long subiterations = 0;
  const int steps = static_cast<int>(std::lround(s.end_time / s.dt));
  for (int n = 0; n < steps; ++n) {
    m.step();
    subiterations += m.last_subiterations();
    r.steps = n + 1;
    r.mean_subiterations = double(subiterations) / r.steps;
    r.time = m.time();
    if (m.blown_up()) {
      r.stable = false;
      std::ostringstream msg;
      msg << to_string(s.scheme) << " (MP-VE) unstable at step " << r.steps << ", t = " << r.time
          << " (rho_bar / rho = " << s.physics.rho_bar / s.physics.rho << ")";
      r.message = msg.str();
      return r;
    }
  }
  r.errors = m.errors();
  return r;
}

}  // namespace amphora::coupling::fsi
