#pragma once
// The MP-VE model problem (viscous fluid -H < y < 0 on an elastic solid 0 < y < Hbar, periodic
// in x) by a partitioned scheme. Each step the solid (leapfrog, physics/elastic_solid) takes
// a traction at t_n (the fluid's; AMP: the impedance-weighted one between the fluid's and the one
// consistent with the characteristics it sent and the interface velocity, g_n - z v_I); then
//  - TP (traditional): the fluid (Stokes, physics/channel_flow) takes the solid's interface
//    velocity at t_n and t_{n+1} as wall data;
//  - AMP (added-mass partitioned; Banks, Henshaw & Schwendeman, J. Comput. Phys. 269, 2014):
//    the solid's step is a predictor; its outgoing characteristics at the interface,
//    sigma_yy + z_p v and sigma_xy + z_s u (z_p = rho_bar cp_bar, z_s = rho_bar cs_bar), are the
//    fluid's impedance top (a Robin condition on the pressure with weight z_p dt / rho, one on
//    the tangential velocity); then the solid's interface row is corrected to move with the
//    fluid's interface velocity (trapezoidal rule in time). No sub-iterations, no parameters.
//  - TP-Aitken: TP made implicit in the traction at t_{n+1} and iterated to convergence each
//    step with Aitken relaxation (see aitken_step in the source).
// Starts from the exact traveling wave (mpve_traveling_wave.hpp), which is also the reference.
// Second-order interface transfers: the fluid traction from one-sided differences and the
// pressure extrapolated in time from its half steps; the solid velocity from its displacement
// levels (centred at t_n, one-sided at t_{n+1}).
#include <memory>
#include <utility>
#include <string>
#include <vector>

#include "coupling/fsi/mpve_traveling_wave.hpp"

namespace amphora::coupling::fsi {

enum class MpveScheme { tp, tp_aitken, amp };
const char* to_string(MpveScheme s);
MpveScheme parse_mpve_scheme(const std::string& name);  ///< tp | tp_aitken | amp

struct MpveSetup {
  MpveScheme scheme = MpveScheme::tp;
  MpveParameters physics;  ///< k, H, Hbar, rho, mu, rho_bar, lambda_bar, mu_bar
  Complex omega;           ///< a root of the dispersion relation for `physics`
  int nx = 32;             ///< cells per wavelength in x (the period is 2 pi / k)
  double dt = 1e-3, end_time = 0.5;
  double blowup_factor = 10.0;  ///< unstable once max |v| exceeds this multiple of its start
  /// TP-Aitken: relative tolerance on the traction update, iteration cap, first relaxation.
  double subiteration_tolerance = 1e-8;
  int max_subiterations = 500;
  double initial_relaxation = 0.1;
};

struct MpveErrors {
  double u = 0, v = 0, p = 0;  ///< fluid
  double ubar = 0, vbar = 0;   ///< solid displacement
  double sigma = 0;  ///< solid stress (max over xx, xy, yy; centred differences, interior rows)
};

class MpvePartitioned {
 public:
  explicit MpvePartitioned(const MpveSetup& s);
  ~MpvePartitioned();
  void step();
  double time() const;
  bool blown_up() const;
  /// Max-norm errors against the exact wave at time() (pressure at time() - dt/2).
  MpveErrors errors() const;

  /// Output: the fluid at cell centres (u, v averaged from the faces; p at time() - dt/2) and
  /// the solid at its nodes, each with the exact values beside.
  struct Snapshot {
    std::vector<double> fluid_x, fluid_y, u, v, p, u_exact, v_exact, p_exact;
    std::vector<double> solid_x, solid_y, ubar, vbar, ubar_exact, vbar_exact;
  };
  Snapshot snapshot() const;
  /// Every array needed to continue bit for bit, and its restoration.
  std::vector<std::pair<std::string, std::vector<double>>> save() const;
  void restore(const std::vector<std::pair<std::string, std::vector<double>>>& arrays);
  /// Sub-iterations of the last step (1 for TP and AMP).
  int last_subiterations() const;
  /// Interface kinetic energy proxy: max |v| over the fluid (the blow-up measure).
  double max_fluid_speed() const;

 private:
  struct State;
  std::unique_ptr<State> s_;
};

struct MpveRun {
  bool stable = true;
  int steps = 0;
  double time = 0;
  MpveErrors errors;
  std::string message;
  double mean_subiterations = 1;
};
MpveRun run_mpve(const MpveSetup& s);

}  // namespace amphora::coupling::fsi
