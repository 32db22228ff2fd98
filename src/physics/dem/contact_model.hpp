#pragma once
// Material pairs for the Hertz–Mindlin contact law (as in LIGGGHTS' `hertz tangential history`
// and Lethe-DEM): effective moduli, a damping factor calibrated to the restitution
// coefficient, Coulomb and rolling friction, and SJKR cohesion.
#include <string>
#include <vector>

namespace amphora::physics::dem {

struct Material {
  double density = 2500.0;      ///< kg/m^3
  double youngs_modulus = 1e7;  ///< Pa
  double poisson_ratio = 0.3;
  double restitution = 0.9;              ///< in (0, 1]
  double friction = 0.5;                 ///< Coulomb sliding friction
  double rolling_friction = 0.0;         ///< constant-torque rolling resistance coefficient
  double cohesion_energy_density = 0.0;  ///< SJKR, J/m^3 (0: off)
};

/// Everything the point-wise force needs for one material pair, precomputed on the host.
struct PairCoefficients {
  double e_star = 0;   ///< effective Young's modulus E* [Pa]
  double g_star = 0;   ///< effective shear modulus G* [Pa]
  double damping = 0;  ///< eta: gamma = eta sqrt(S m*) for S = S_n = 2 E* a, S_t = 8 G* a
  double friction = 0;
  double rolling_friction = 0;
  double cohesion = 0;  ///< SJKR energy density [J/m^3]
  // Folded constants of the hot loop (a = sqrt(R* delta) is the contact radius):
  double kn = 0;       ///< (4/3) E*: k_n = kn a
  double kt = 0;       ///< 8 G*: k_t = kt a
  double gamma_n = 0;  ///< eta sqrt(2 E*): gamma_n = gamma_n sqrt(m* a)
  double gamma_t = 0;  ///< eta sqrt(8 G*): gamma_t = gamma_t sqrt(m* a)
};

/// Coefficients of a pair of materials; restitution, friction and cohesion are the mean of
/// the two materials' values, the moduli combine as Hertz and Mindlin prescribe. Throws
/// std::invalid_argument for non-physical input.
PairCoefficients pair_coefficients(const Material& a, const Material& b);

/// Restitution coefficient of the damped Hertz contact with damping factor eta. With
/// F_n = max(0, (4/3) E* sqrt(R*) d^{3/2} + eta sqrt(2 E* sqrt(R* d) m*) d'), the scaled
/// equation s'' = -max(0, s^{3/2} + c s^{1/4} s'), c = eta sqrt(3/2), s(0) = 0, s'(0) = 1, shows
/// the restitution depends on eta alone (Antypov & Elliott, EPL 94 (2011) 50004); it is
/// integrated by RK4.
double restitution_of_damping(double eta);
/// The damping factor giving restitution e (bisection on restitution_of_damping). LIGGGHTS'
/// closed form eta = 2 sqrt(5/6) |ln e| / sqrt(ln^2 e + pi^2) comes from the linear spring and is
/// not exact for the Hertz law; this one meets e to 1e-6.
double damping_for_restitution(double e);
/// Scaled contact duration tau (t_c = tau (9 m*^2 / (16 E*^2 R* v))^{1/5}) for damping eta;
/// tau(0) = 3.2181 gives Hertz's t_c = 2.8686 (m*^2 / (R* E*^2 v))^{1/5}.
double scaled_contact_duration(double eta);

/// Hertz contact duration for an impact at speed v.
double hertz_contact_time(double m_eff, double r_eff, double e_star, double v, double eta = 0.0);
/// Rayleigh time step of a sphere: pi r sqrt(rho / G) / (0.1631 nu + 0.8766).
double rayleigh_time(const Material& m, double radius);

}  // namespace amphora::physics::dem
