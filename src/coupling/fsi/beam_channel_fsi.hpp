#pragma once
// Partitioned schemes for the beam model problem with an inviscid fluid: a periodic
// Euler–Bernoulli beam (physics/beam) on top of a channel of linearised incompressible
// inviscid fluid (physics/channel_flow), coupled at y = 0 by eta_tt = -p_y / rho (fluid
// momentum at the interface) and rho_h eta_tt = -L eta + p (beam, L = K - T d_xx + B d_xxxx).
//
// - TP (traditional partitioned): the fluid sees the beam's last acceleration,
//   p_y = -rho a^n, then the beam is advanced with the new pressure. The fluid's added mass
//   rho / (k tanh kH) enters explicitly, so the scheme fails once it outweighs rho_h.
// - TP-Aitken: TP iterated to convergence within each step (fluid with p_y = -rho a^(k), beam
//   trial acceleration, Aitken's dynamic relaxation; Kuettler & Wall, Comput. Mech. 2008).
//   Stable where it converges, at the price of the sub-iterations.
// - AMP (added-mass partitioned; Li, Henshaw, Banks, Schwendeman & Main, J. Comput. Phys.
//   2016): eliminating eta_tt between the two interface equations gives the Robin condition
//   p + (rho_h / rho) p_y = L eta. With the beam advanced by Newmark's implicit rule,
//   eta^{n+1} = eta* + dt^2/4 eta_tt^{n+1}, the same elimination at the new time level gives
//   p + (rho_h + dt^2/4 L) p_y / rho = L eta*, which the fluid solves; the beam is then
//   advanced with that pressure and its acceleration equals the fluid's -p_y / rho. The added
//   mass is inside the pressure solve, so no density ratio breaks it, with no sub-iterations
//   and nothing to tune.
// The exact traveling wave (coupling/fsi/beam_channel_wave.hpp) starts every run and is the
// reference for the errors.
#include <string>

#include "physics/beam/euler_bernoulli_beam.hpp"
#include "physics/channel_flow/channel_pressure.hpp"

namespace amphora::coupling::fsi {

enum class BeamScheme { traditional, traditional_aitken, amp };
BeamScheme parse_beam_scheme(const std::string& name);  ///< "tp" | "tp_aitken" | "amp"
const char* to_string(BeamScheme s);

struct BeamChannelSetup {
  physics::beam::BeamParameters beam;  ///< length and points shared with the channel's x grid
  double depth = 0.5;                  ///< H
  double rho = 1.0;                    ///< fluid density
  int fluid_rows = 16;                 ///< channel cells in y
  int mode = 1;                        ///< k = 2 pi mode / length
  double dt = 1e-3, end_time = 0.5;
  BeamScheme scheme = BeamScheme::amp;
  /// Declared unstable when max |eta| exceeds this multiple of the wave's amplitude (1).
  double blowup_factor = 10.0;
  /// TP-Aitken: relative tolerance on the acceleration update, iteration cap, first relaxation.
  double subiteration_tolerance = 1e-10;
  int max_subiterations = 500;
  double initial_relaxation = 0.1;
};

struct BeamChannelResult {
  bool stable = true;
  int steps = 0;         ///< steps taken (up to the blow-up)
  double time = 0;       ///< time reached
  double omega = 0;      ///< the exact wave's frequency
  double eta_error = 0;  ///< max-norm errors at `time` (if stable)
  double pressure_error = 0;
  double max_eta = 0;   ///< largest |eta| seen
  std::string message;  ///< where and when it blew up, if it did
  double mean_subiterations = 0;
};

/// The verification case: a beam of length 1 (K = 0.5, T = 1, B = 0.01, `points` nodes) over a
/// channel of depth 0.5 (rho = 1, points / 2 rows), the k = 2 pi wave to t = 0.5, dt
/// proportional to h (at least `points` steps per half period).
BeamChannelSetup beam_channel_wave_case(double rho_h, int points, BeamScheme scheme);

/// The coupled system, stepped by one of the schemes, starting from the exact traveling wave.
class BeamChannelFsi {
 public:
  explicit BeamChannelFsi(const BeamChannelSetup& s);
  void step();
  /// max |eta| over the beam exceeds blowup_factor (or is not finite).
  bool blown_up() const;
  double max_abs_eta() const;
  double time() const { return beam_.time(); }
  double omega() const { return omega_; }
  const BeamChannelSetup& setup() const { return s_; }
  const physics::channel_flow::ChannelGrid& fluid_grid() const { return grid_; }
  const physics::beam::EulerBernoulliBeam& beam() const { return beam_; }
  physics::beam::EulerBernoulliBeam& beam() { return beam_; }
  /// The pressure of the last step's solve (at time()), rows 0..ny of the fluid grid.
  const std::vector<double>& pressure() const { return p_; }
  /// The exact wave at (x, y, t).
  double exact_eta(double x, double t) const;
  double exact_pressure(double x, double y, double t) const;
  /// Max-norm errors of eta and p at time().
  double eta_error() const;
  double pressure_error() const;
  /// Sub-iterations of the last step (1 for TP and AMP).
  int last_subiterations() const { return subiterations_; }
  /// Recomputes the pressure for the current state (after a restore).
  void refresh_pressure();

 private:
  BeamChannelSetup s_;
  physics::channel_flow::ChannelGrid grid_;
  double k_, omega_;
  physics::beam::EulerBernoulliBeam beam_;
  physics::channel_flow::ChannelPressure fluid_;
  std::vector<double> p_;
  int subiterations_ = 0;
};

/// Runs the scheme from the exact traveling wave to end_time (or to a detected blow-up).
BeamChannelResult run_beam_channel(const BeamChannelSetup& s);

}  // namespace amphora::coupling::fsi
