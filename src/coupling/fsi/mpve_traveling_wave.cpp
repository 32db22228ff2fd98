#include "coupling/fsi/mpve_traveling_wave.hpp"

#include <Eigen/Dense>
#include <cmath>

namespace amphora::coupling::fsi {

namespace {
const Complex I(0.0, 1.0);
}

std::array<Complex, 64> mpve_matrix(const MpveParameters& p, Complex w) {
  const double k = p.k;
  const Complex q = std::sqrt(k * k - I * p.rho * w / p.mu);
  const double cp2 = (p.lambda_bar + 2 * p.mu_bar) / p.rho_bar, cs2 = p.mu_bar / p.rho_bar;
  const Complex a = std::sqrt(k * k - w * w / cp2), b = std::sqrt(k * k - w * w / cs2);
  const Complex ik = I * k;
  std::array<Complex, 64> M{};
  auto row = [&](int r, std::array<Complex, 8> v) {
    for (int c = 0; c < 8; ++c) M[8 * r + c] = v[c];
  };
  const double H = p.H, Hb = p.Hbar;
  const Complex chk = std::cosh(-k * H), shk = std::sinh(-k * H), chq = std::cosh(-q * H),
                shq = std::sinh(-q * H);
  const Complex cha = std::cosh(a * Hb), sha = std::sinh(a * Hb), chb = std::cosh(b * Hb),
                shb = std::sinh(b * Hb);
  // no slip at y = -H: u = ik phi + psi' = 0, v = phi' - ik psi = 0
  row(0, {ik * chk, ik * shk, q * shq, q * chq, 0., 0., 0., 0.});
  row(1, {k * shk, k * chk, -ik * chq, -ik * shq, 0., 0., 0., 0.});
  // fixed solid at y = Hbar: ubar = vbar = 0
  row(2, {0., 0., 0., 0., ik * cha, ik * sha, b * shb, b * chb});
  row(3, {0., 0., 0., 0., a * sha, a * cha, -ik * chb, -ik * shb});
  // interface velocity u = -i omega ubar, v = -i omega vbar
  row(4, {ik, 0., 0., q, I * w * ik, 0., 0., I * w * b});
  row(5, {0., k, -ik, 0., 0., I * w * a, I * w * (-ik), 0.});
  // interface traction: sigma_xy and sigma_yy continuous
  row(6, {0., 2. * ik * k * p.mu, p.mu * (q * q + k * k), 0., 0., -2. * ik * a * p.mu_bar,
          -p.mu_bar * (b * b + k * k), 0.});
  const Complex solid_normal = (p.lambda_bar + 2 * p.mu_bar) * a * a - p.lambda_bar * k * k;
  row(7, {-I * w * p.rho + 2 * p.mu * k * k, 0., 0., -2. * ik * p.mu * q, -solid_normal, 0., 0.,
          2. * ik * p.mu_bar * b});
  return M;
}

Complex mpve_determinant(const MpveParameters& p, Complex omega) {
  const auto m = mpve_matrix(p, omega);
  Eigen::Matrix<Complex, 8, 8> M;
  for (int r = 0; r < 8; ++r)
    for (int c = 0; c < 8; ++c) M(r, c) = m[8 * r + c];
  return M.partialPivLu().determinant();
}

DispersionRoot solve_mpve_dispersion(const MpveParameters& p, Complex omega0, double tolerance,
                                     int max_iterations) {
  DispersionRoot root{omega0, 0, false};
  Complex w = omega0;
  for (int it = 1; it <= max_iterations; ++it) {
    const double h = 1e-6 * (1.0 + std::abs(w));
    const Complex f = mpve_determinant(p, w);
    const Complex df = (mpve_determinant(p, w + h) - mpve_determinant(p, w - h)) / (2.0 * h);
    const Complex step = f / df;
    w -= step;
    root.iterations = it;
    if (!std::isfinite(w.real()) || !std::isfinite(w.imag())) break;
    if (std::abs(step) <= tolerance * (1.0 + std::abs(w))) {
      root.converged = true;
      break;
    }
  }
  root.omega = w;
  return root;
}

DispersionRoot continue_mpve_dispersion(const MpveParameters& from, Complex omega_from,
                                        const MpveParameters& to, int steps) {
  auto at = [&](double t) {
    auto lerp = [t](double a, double b) { return a + t * (b - a); };
    return MpveParameters{lerp(from.k, to.k),
                          lerp(from.H, to.H),
                          lerp(from.Hbar, to.Hbar),
                          lerp(from.rho, to.rho),
                          lerp(from.mu, to.mu),
                          lerp(from.rho_bar, to.rho_bar),
                          lerp(from.lambda_bar, to.lambda_bar),
                          lerp(from.mu_bar, to.mu_bar)};
  };
  // Predictor: the secant through the last two roots; a step is accepted when Newton converges
  // quickly and stays near the prediction (else the step is halved: the root can move fast,
  // and a large step lets Newton jump to another branch).
  DispersionRoot root{omega_from, 0, true};
  double t = 0.0, dt = 1.0 / std::max(steps, 1);
  Complex previous = omega_from, slope = 0.0;  // d omega / d t
  int total = 0;
  while (t < 1.0 && dt > 1e-8) {
    const double step = std::min(dt, 1.0 - t);
    const Complex guess = root.omega + slope * step;
    const DispersionRoot next = solve_mpve_dispersion(at(t + step), guess, 1e-12, 12);
    total += next.iterations;
    const bool near =
        std::abs(next.omega - guess) <= 0.05 * std::abs(root.omega) + 0.5 * std::abs(slope * step);
    if (next.converged && near) {
      previous = root.omega;
      root.omega = next.omega;
      slope = (root.omega - previous) / step;
      t += step;
      dt = std::min(2 * dt, 1.0 / std::max(steps, 1));
    } else {
      dt *= 0.5;
    }
  }
  root.converged = t >= 1.0;
  root.iterations = total;
  return root;
}

std::array<Complex, 8> mpve_mode(const MpveParameters& p, Complex omega) {
  const auto m = mpve_matrix(p, omega);
  Eigen::Matrix<Complex, 8, 8> M;
  for (int r = 0; r < 8; ++r)
    for (int c = 0; c < 8; ++c) M(r, c) = m[8 * r + c];
  Eigen::JacobiSVD<Eigen::Matrix<Complex, 8, 8>> svd(M, Eigen::ComputeFullV);
  const Eigen::Matrix<Complex, 8, 1> c = svd.matrixV().col(7);
  // vbar(0) = alpha F - ik G
  const double cp2 = (p.lambda_bar + 2 * p.mu_bar) / p.rho_bar;
  const Complex a = std::sqrt(p.k * p.k - omega * omega / cp2);
  const Complex vbar0 = a * c(5) - I * p.k * c(6);
  std::array<Complex, 8> out;
  for (int i = 0; i < 8; ++i) out[i] = c(i) / vbar0;
  return out;
}

namespace {

/// A displacement or velocity field grad Phi + curl Psi with Phi = c0 cosh(a y) + c1 sinh(a y),
/// Psi = c2 cosh(b y) + c3 sinh(b y) (so Phi'' = a^2 Phi, Psi'' = b^2 Psi): the shape of both
/// the fluid's (a = k, b = q) and the solid's (a = alpha, b = beta) fields, times e^{i(kx - wt)}.
struct PotentialField {
  Complex phi, u, v, u_y, v_y;
};

PotentialField potential_field(double k, Complex a, Complex b, const Complex* c, double y) {
  const Complex ik = I * k;
  const Complex phi = c[0] * std::cosh(a * y) + c[1] * std::sinh(a * y);
  const Complex dphi = a * (c[0] * std::sinh(a * y) + c[1] * std::cosh(a * y));
  const Complex psi = c[2] * std::cosh(b * y) + c[3] * std::sinh(b * y);
  const Complex dpsi = b * (c[2] * std::sinh(b * y) + c[3] * std::cosh(b * y));
  return {phi, ik * phi + dpsi, dphi - ik * psi, ik * dphi + b * b * psi, a * a * phi - ik * dpsi};
}

}  // namespace

MpveFluidFields mpve_fluid(const MpveParameters& p, Complex w, const std::array<Complex, 8>& c,
                           double x, double y, double t) {
  const double k = p.k;
  const Complex q = std::sqrt(k * k - I * p.rho * w / p.mu), ik = I * k;
  const Complex e = std::exp(I * (k * x - w * t));
  const PotentialField f = potential_field(k, k, q, c.data(), y);  // phi harmonic, psi'' = q^2 psi
  const Complex pressure = I * w * p.rho * f.phi;
  MpveFluidFields out;
  out.u = (f.u * e).real();
  out.v = (f.v * e).real();
  out.p = (pressure * e).real();
  out.sxy = (p.mu * (f.u_y + ik * f.v) * e).real();
  out.syy = ((-pressure + 2 * p.mu * f.v_y) * e).real();
  return out;
}

MpveSolidFields mpve_solid(const MpveParameters& p, Complex w, const std::array<Complex, 8>& c,
                           double x, double y, double t) {
  const double k = p.k;
  const double cp2 = (p.lambda_bar + 2 * p.mu_bar) / p.rho_bar, cs2 = p.mu_bar / p.rho_bar;
  const Complex a = std::sqrt(k * k - w * w / cp2), b = std::sqrt(k * k - w * w / cs2), ik = I * k;
  const Complex e = std::exp(I * (k * x - w * t));
  const PotentialField f = potential_field(k, a, b, c.data() + 4, y);
  const Complex div = ik * f.u + f.v_y;
  MpveSolidFields s;
  s.ubar = (f.u * e).real();
  s.vbar = (f.v * e).real();
  s.ubar_t = (-I * w * f.u * e).real();
  s.vbar_t = (-I * w * f.v * e).real();
  s.sxx = ((p.lambda_bar * div + 2 * p.mu_bar * ik * f.u) * e).real();
  s.sxy = (p.mu_bar * (f.u_y + ik * f.v) * e).real();
  s.syy = ((p.lambda_bar * div + 2 * p.mu_bar * f.v_y) * e).real();
  return s;
}

MpveParameters mpve_check_case() { return {2 * M_PI, 1.0, 0.5, 1.0, 0.01, 0.05, 0.05, 0.05}; }

DispersionRoot mpve_root_from_check_case(const MpveParameters& to, int steps) {
  const MpveParameters check = mpve_check_case();
  const DispersionRoot start = solve_mpve_dispersion(check, Complex(1.4, -0.4));
  if (!start.converged) return start;
  return continue_mpve_dispersion(check, start.omega, to, steps);
}

}  // namespace amphora::coupling::fsi
