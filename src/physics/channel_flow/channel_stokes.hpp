#pragma once
// Viscous incompressible flow (linearised: unsteady Stokes) in a channel periodic in x,
// -H < y < 0, with the velocity given on both walls:
//   rho v_t + grad p = mu lap v + f,  div v = 0.
// Staggered (MAC) grid: p at cell centres, u on x-faces, v on y-faces (the wall faces carry the
// data), so the discrete divergence of the projected velocity vanishes to round-off.
// Fractional step, second order (Brown, Cortez & Minion, J. Comput. Phys. 168, 2001, the
// rotational incremental pressure-correction scheme): Crank–Nicolson velocity predictor with
// the old pressure gradient, pressure increment phi from lap phi = rho/dt div v*, projection,
// p^{n+1/2} = p^{n-1/2} + phi - (mu/2) div v*. The pressure lives at half steps. The implicit
// matrices are fixed, so they are factored once (Eigen SparseLU).
// The top wall is either a velocity wall (data u_top, v_top) or an impedance interface, the
// fluid side of the AMP coupling with an elastic solid above (Banks, Henshaw & Schwendeman,
// J. Comput. Phys. 269, 2014, sec. 3): the solid's outgoing characteristics at t_{n+1},
// g_y = sigma_yy + z_p v and g_x = sigma_xy + z_s u, are matched by the fluid's traction and
// velocity. The shear one is a Robin condition on u in the velocity predictor (through the
// ghost row, v_x from the guessed interface velocity v_g),
//   mu (u_y + v_x) + z_s u = g_x;
// the normal one, with sigma_yy = -p + 2 mu v_y, p^{n+1} = (3 p^{n+1/2} - p^{n-1/2}) / 2 and the
// projected v = v_g - dt/rho phi_y, is a Robin condition on the pressure increment with weight
// z_p dt / rho (the coupling's weight; the 3/2 puts it at t_{n+1}),
//   -(3/2) phi - (z_p dt / rho) phi_y + (2 mu dt / rho) phi_xx
//       = g_y + p^{n-1/2} - (3 mu / 4) div v* - 2 mu v*_y - z_p v_g,
// which moves the interface's normal velocity: heavy solids (z_p large) fix v, light ones
// (z_p small) fix p. v_y = -u_x is taken from the two rows below the wall (the wall's own u,
// through the ghost, carries the guessed v_x), and at t_{n+1}: u^{n+1} = u* - dt/rho phi_x
// puts the phi_xx term in the condition. Explicit, that normal viscous stress fed the wall
// pressure back through the predictor's pressure gradient with a gain of about
// 1/3 - (16/3) mu dt / (rho h^2): light solids blew up once mu dt / (rho h^2) passed ~1/4;
// implicit, they run at 12 (tests/physics/test_channel_stokes.cpp). Cf. the "added damping"
// of Serino, Banks, Henshaw & Schwendeman (J. Comput. Phys. 399, 2019).
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "physics/channel_flow/channel_pressure.hpp"

namespace amphora::physics::channel_flow {

/// The problem data: body force and wall velocities as functions of position and time.
struct StokesData {
  std::function<double(double x, double y, double t)> fx, fy;
  std::function<double(double x, double t)> u_bottom, v_bottom, u_top, v_top;
  /// Impedance top only: the solid's characteristics g_x (at u's x) and g_y (at v's x) at t;
  /// v_top(x, t_{n+1}) is then a guess of the interface's normal velocity (the projection
  /// corrects it) and u_top is unused.
  std::function<double(double x, double t)> g_top_x, g_top_y;
};

/// The solid impedances of an impedance top wall: z_normal = rho_bar cp_bar, z_shear = rho_bar
/// cs_bar.
struct TopImpedance {
  double z_normal = 0, z_shear = 0;
};

class ChannelStokes {
 public:
  /// A velocity top wall, or an impedance one if `top` is given. Throws std::invalid_argument
  /// for rho, mu, dt <= 0, negative impedances or a grid below 3 x 2 cells.
  ChannelStokes(const ChannelGrid& g, double rho, double mu, double dt,
                std::optional<TopImpedance> top = std::nullopt);
  ~ChannelStokes();
  ChannelStokes(ChannelStokes&&) noexcept;

  // Coordinates of the unknowns (cell (i, j): x in [i hx, (i+1) hx], y in -H + [j hy, (j+1) hy]).
  double u_x(int i) const { return i * g_.hx(); }
  double u_y(int j) const { return -g_.depth + (j + 0.5) * g_.hy(); }
  double v_x(int i) const { return (i + 0.5) * g_.hx(); }
  double v_y(int j) const { return -g_.depth + j * g_.hy(); }  ///< j = 0 .. ny (walls at 0, ny)

  /// u: ny x nx, v: (ny+1) x nx, p at t - dt/2: ny x nx, all row-major (row = j); with an
  /// impedance top also the interface's state (3 nx values): u on the wall at t (at u's x),
  /// the ghost v_{ny+1} at t, and p on the wall at t - 3dt/2 (both at v's x).
  void set_state(double t, std::vector<double> u, std::vector<double> v, std::vector<double> p,
                 std::vector<double> top_state = {});
  void step(const StokesData& data);

  const std::vector<double>& u() const { return u_; }
  const std::vector<double>& v() const { return v_; }
  /// The pressure at time() - dt/2.
  const std::vector<double>& p() const { return p_; }
  /// Impedance top: the interface's state (see set_state); its first nx values are the
  /// fluid's tangential velocity on the wall at time().
  const std::vector<double>& top_state() const { return top_state_; }
  /// max over cells of |div v| (the projection's leftover: round-off).
  double max_divergence() const;
  double time() const { return t_; }
  double dt() const { return dt_; }
  const ChannelGrid& grid() const { return g_; }

 private:
  struct Factors;
  ChannelGrid g_;
  double rho_, mu_, dt_, t_ = 0;
  std::optional<TopImpedance> top_;
  // Impedance top: phi ghost = phi_ghost x the row below + phi_viscous x L_x phi + data.
  double phi_ghost(double hy) const;
  double phi_viscous(double hy) const;
  std::vector<double> viscous_part(const Eigen::VectorXd& phi) const;
  std::vector<double> u_, v_, p_, top_state_;
  std::unique_ptr<Factors> f_;
};

}  // namespace amphora::physics::channel_flow
