#pragma once
// A thin Euler–Bernoulli beam with tension and a restoring spring, periodic in x, as the solid
// of the beam FSI model problem (Banks, Henshaw & Schwendeman, "An added-mass partition
// algorithm for fluid-structure interactions of compressible fluids and nonlinear solids" and
// the incompressible beam AMP scheme, J. Comput. Phys. 2016, section 2):
//   rho_h eta_tt = -K eta + T eta_xx - B eta_xxxx + f(x, t),   x in [0, L) periodic,
// with rho_h = (solid density) x (thickness). Space: centred differences (D+D- and its square,
// second order); time: Newmark's average-acceleration rule (beta = 1/4, gamma = 1/2), second
// order, unconditionally stable and free of numerical damping (the discrete energy
// E = h/2 (rho_h v.v + eta.A eta) is conserved exactly when f = 0), so a growing interface
// energy in a coupled run is the coupling's doing. The implicit matrix rho_h I + dt^2/4 A is
// factored once (Eigen sparse LDL^T); a beam holds at most a few thousand points, so it lives
// on the host.
#include <array>
#include <memory>
#include <vector>

namespace amphora::physics::beam {

struct BeamParameters {
  double length = 1.0;
  double rho_h = 1.0;      ///< mass per unit length (density x thickness)
  double spring = 0.0;     ///< K >= 0: restoring force per unit length and displacement
  double tension = 0.0;    ///< T >= 0
  double stiffness = 0.0;  ///< B = E I >= 0
  int points = 64;         ///< grid points x_i = i L / points, i = 0 .. points-1
};

/// Frequency of the free traveling wave eta = cos(k x - omega t) of the continuous beam:
/// omega^2 = (K + T k^2 + B k^4) / rho_h.
double beam_frequency(const BeamParameters& p, double k);

class EulerBernoulliBeam {
 public:
  /// Throws std::invalid_argument (naming the parameter) for rho_h <= 0, negative K, T or B,
  /// fewer than 5 points or dt <= 0.
  EulerBernoulliBeam(const BeamParameters& p, double dt);
  ~EulerBernoulliBeam();
  EulerBernoulliBeam(EulerBernoulliBeam&&) noexcept;

  /// State at time t; the acceleration follows from the equation with load f.
  void set_state(double t, const std::vector<double>& eta, const std::vector<double>& v,
                 const std::vector<double>& f);
  /// Restores a saved state (acceleration included) exactly, for a bit-for-bit restart.
  void restore_state(double t, const std::vector<double>& eta, const std::vector<double>& v,
                     const std::vector<double>& a);
  /// One Newmark step to t + dt with the load at the new time.
  void step(const std::vector<double>& f_next);
  /// The acceleration that step(f_next) would give, without stepping (sub-iterations).
  std::vector<double> acceleration_after(const std::vector<double>& f_next) const;
  /// The Newmark update to t + dt with a given new acceleration.
  void advance_with(const std::vector<double>& a_new);
  /// eta* = eta + dt v + dt^2/4 a: the displacement the step starts from.
  std::vector<double> predictor() const;

  /// (A eta)_i = K eta_i - T (D+D- eta)_i + B (D+D-)^2 eta)_i: minus the elastic force.
  std::vector<double> restoring_force(const std::vector<double>& eta) const;
  /// A's periodic stencil: (A eta)_i = sum_{o=-2..2} c[o+2] eta_{i+o}.
  std::array<double, 5> stencil() const;
  /// h/2 (rho_h |v|^2 + eta . A eta).
  double energy() const;

  const std::vector<double>& displacement() const { return eta_; }
  const std::vector<double>& velocity() const { return v_; }
  const std::vector<double>& acceleration() const { return a_; }
  double time() const { return t_; }
  double dt() const { return dt_; }
  double spacing() const { return h_; }
  int points() const { return p_.points; }
  const BeamParameters& parameters() const { return p_; }

 private:
  struct Factor;
  BeamParameters p_;
  double dt_, h_, t_ = 0;
  std::vector<double> eta_, v_, a_;
  std::unique_ptr<Factor> factor_;  // rho_h I + dt^2/4 A
};

}  // namespace amphora::physics::beam
