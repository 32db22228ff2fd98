#pragma once
// Exact traveling waves of the model problem MP-VE of Banks, Henshaw & Schwendeman (J. Comput.
// Phys. 2014, "An analysis of a new stable partitioned algorithm for FSI problems. Part I"):
// periodic in x, a viscous incompressible fluid in -H < y < 0 (no slip at y = -H) on a linear
// elastic solid in 0 < y < Hbar (fixed at y = Hbar), coupled at y = 0 (velocity and traction
// continuous, linearised). Every field is Re f(y) exp(i (k x - omega t)).
//
// Derivation: fluid v = grad phi + curl psi with
// lap phi = 0 (so p = i omega rho phi) and psi'' = q^2 psi, q^2 = k^2 - i rho omega / mu; solid
// u = grad Phi + curl Psi with Phi'' = alpha^2 Phi, Psi'' = beta^2 Psi, alpha^2 = k^2 -
// omega^2/cp^2, beta^2 = k^2 - omega^2/cs^2. With phi = A cosh ky + B sinh ky, psi = C cosh qy +
// D sinh qy, Phi = E cosh alpha y + F sinh alpha y, Psi = G cosh beta y + H sinh beta y:
//   u = ik phi + psi',  v = phi' - ik psi,
//   sigma_xy = mu (2ik phi' + (q^2 + k^2) psi),  sigma_yy = (-i omega rho + 2 mu k^2) phi - 2ik mu
//   psi',
// and the same for the solid with (lambda + 2 mu) alpha^2 - lambda k^2 in place of the fluid's
// normal-stress factor. Eight conditions (no slip at -H, fixed at Hbar, velocity u = -i omega
// ubar and traction continuity at 0) give M(omega) c = 0; the dispersion relation is
// det M(omega) = 0 (cosh/sinh pairs make it independent of the square roots' branches).
#include <array>
#include <complex>

namespace amphora::coupling::fsi {

using Complex = std::complex<double>;

struct MpveParameters {
  double k = 2 * 3.141592653589793;                         ///< wave number
  double H = 1.0, Hbar = 0.5;                               ///< fluid and solid depths
  double rho = 1.0, mu = 0.01;                              ///< fluid density and viscosity
  double rho_bar = 0.05, lambda_bar = 0.05, mu_bar = 0.05;  ///< solid density and Lame constants
};

/// M(omega) c = 0: the 8x8 interface system, row major.
std::array<Complex, 64> mpve_matrix(const MpveParameters& p, Complex omega);
Complex mpve_determinant(const MpveParameters& p, Complex omega);

struct DispersionRoot {
  Complex omega;
  int iterations = 0;
  bool converged = false;
};

/// Newton's method on det M(omega) = 0 from omega0 (derivative by central differences).
DispersionRoot solve_mpve_dispersion(const MpveParameters& p, Complex omega0,
                                     double tolerance = 1e-12, int max_iterations = 60);

/// Newton with continuation: follows the root omega_from of parameters `from` to parameters `to`
/// along the straight line between them in `steps` steps (each solve starts from the last root).
DispersionRoot continue_mpve_dispersion(const MpveParameters& from, Complex omega_from,
                                        const MpveParameters& to, int steps);

/// The MP-VE check case: k = 2 pi, H = 1, Hbar = 0.5, rho = 1, mu = 0.01,
/// rho_bar = lambda_bar = mu_bar = 0.05 (omega ~ 1.42227 - 0.37955 i).
MpveParameters mpve_check_case();
/// A root of the dispersion relation for `to`, followed by continuation from the check case's
/// (`converged` false if it is lost on the way).
DispersionRoot mpve_root_from_check_case(const MpveParameters& to, int steps = 40);

/// The mode: coefficients c (A, B, C, D, E, F, G, H above) with M(omega) c = 0, scaled so that
/// the interface displacement vbar(0) = 1.
std::array<Complex, 8> mpve_mode(const MpveParameters& p, Complex omega);

/// The exact fields (real parts) of a mode at (x, y, t): the fluid for -H <= y <= 0 ...
struct MpveFluidFields {
  double u, v, p;   ///< velocity and pressure
  double sxy, syy;  ///< stress mu (u_y + v_x), -p + 2 mu v_y
};
MpveFluidFields mpve_fluid(const MpveParameters& p, Complex omega, const std::array<Complex, 8>& c,
                           double x, double y, double t);

/// ... and the solid for 0 <= y <= Hbar: displacement, velocity, stress.
struct MpveSolidFields {
  double ubar, vbar, ubar_t, vbar_t;
  double sxx, sxy, syy;
};
MpveSolidFields mpve_solid(const MpveParameters& p, Complex omega, const std::array<Complex, 8>& c,
                           double x, double y, double t);

}  // namespace amphora::coupling::fsi
