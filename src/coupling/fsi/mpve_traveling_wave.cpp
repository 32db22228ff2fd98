#include "coupling/fsi/mpve_traveling_wave.hpp"

#include <Eigen/Dense>
#include <cmath>

namespace amphora::fsi {

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
  const Complex chk = std::cosh(-k * H), shk = std::sinh(-k * H), chq = std::cosh(-q * H), shq = std::sinh(-q * H);
  const Complex cha = std::cosh(a * Hb), sha = std::sinh(a * Hb), chb = std::cosh(b * Hb), shb = std::sinh(b * Hb);
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

DispersionRoot solve_mpve_dispersion(const MpveParameters& p, Complex omega0, double tolerance, int max_iterations) {
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

DispersionRoot continue_mpve_dispersion(const MpveParameters& from, Complex omega_from, const MpveParameters& to,
                                        int steps) {
  auto at = [&](double t) {
    auto lerp = [t](double a, double b) { return a + t * (b - a); };
    return MpveParameters{lerp(from.k, to.k),     lerp(from.H, to.H),           lerp(from.Hbar, to.Hbar),
                          lerp(from.rho, to.rho), lerp(from.mu, to.mu),         lerp(from.rho_bar, to.rho_bar),
                          lerp(from.lambda_bar, to.lambda_bar), lerp(from.mu_bar, to.mu_bar)};
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
    const bool near = std::abs(next.omega - guess) <= 0.05 * std::abs(root.omega) + 0.5 * std::abs(slope * step);
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

MpveFluidFields mpve_fluid(const MpveParameters& p, Complex w, const std::array<Complex, 8>& c,
                           double x, double y, double t) {
  const double k = p.k;
  const Complex q = std::sqrt(k * k - I * p.rho * w / p.mu), ik = I * k;
  const Complex e = std::exp(I * (k * x - w * t));
  // phi = A cosh ky + B sinh ky (harmonic), psi = C cosh qy + D sinh qy (psi'' = q^2 psi).
  const Complex phi = c[0] * std::cosh(k * y) + c[1] * std::sinh(k * y);
  const Complex dphi = k * (c[0] * std::sinh(k * y) + c[1] * std::cosh(k * y));
  const Complex psi = c[2] * std::cosh(q * y) + c[3] * std::sinh(q * y);
  const Complex dpsi = q * (c[2] * std::sinh(q * y) + c[3] * std::cosh(q * y));
  const Complex u = ik * phi + dpsi, v = dphi - ik * psi;
  const Complex u_y = ik * dphi + q * q * psi, v_y = k * k * phi - ik * dpsi;
  const Complex pressure = I * w * p.rho * phi;
  MpveFluidFields f;
  f.u = (u * e).real();
  f.v = (v * e).real();
  f.p = (pressure * e).real();
  f.sxy = (p.mu * (u_y + ik * v) * e).real();
  f.syy = ((-pressure + 2 * p.mu * v_y) * e).real();
  return f;
}

MpveSolidFields mpve_solid(const MpveParameters& p, Complex w, const std::array<Complex, 8>& c,
                           double x, double y, double t) {
  const double k = p.k;
  const double cp2 = (p.lambda_bar + 2 * p.mu_bar) / p.rho_bar, cs2 = p.mu_bar / p.rho_bar;
  const Complex a = std::sqrt(k * k - w * w / cp2), b = std::sqrt(k * k - w * w / cs2), ik = I * k;
  const Complex e = std::exp(I * (k * x - w * t));
  // Phi = E cosh ay + F sinh ay, Psi = G cosh by + H sinh by; ubar = ik Phi + Psi', vbar = Phi' - ik Psi.
  const Complex Phi = c[4] * std::cosh(a * y) + c[5] * std::sinh(a * y);
  const Complex dPhi = a * (c[4] * std::sinh(a * y) + c[5] * std::cosh(a * y));
  const Complex Psi = c[6] * std::cosh(b * y) + c[7] * std::sinh(b * y);
  const Complex dPsi = b * (c[6] * std::sinh(b * y) + c[7] * std::cosh(b * y));
  const Complex ub = ik * Phi + dPsi, vb = dPhi - ik * Psi;
  const Complex ub_y = ik * dPhi + b * b * Psi, vb_y = a * a * Phi - ik * dPsi;
  const Complex div = ik * ub + vb_y;
  MpveSolidFields s;
  s.ubar = (ub * e).real();
  s.vbar = (vb * e).real();
  s.ubar_t = (-I * w * ub * e).real();
  s.vbar_t = (-I * w * vb * e).real();
  s.sxx = ((p.lambda_bar * div + 2 * p.mu_bar * ik * ub) * e).real();
  s.sxy = (p.mu_bar * (ub_y + ik * vb) * e).real();
  s.syy = ((p.lambda_bar * div + 2 * p.mu_bar * vb_y) * e).real();
  return s;
}

}  // namespace amphora::fsi
