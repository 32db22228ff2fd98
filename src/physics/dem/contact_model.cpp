#include "physics/dem/contact_model.hpp"

#include <cmath>
#include <stdexcept>

namespace amphora::physics::dem {

namespace {

void check(const Material& m) {
  if (!(m.density > 0)) throw std::invalid_argument("material density must be > 0");
  if (!(m.youngs_modulus > 0)) throw std::invalid_argument("Young's modulus must be > 0");
  if (!(m.poisson_ratio > -1 && m.poisson_ratio < 0.5))
    throw std::invalid_argument("Poisson's ratio must lie in (-1, 0.5)");
  if (!(m.restitution > 0 && m.restitution <= 1))
    throw std::invalid_argument("restitution must lie in (0, 1]");
  if (!(m.friction >= 0) || !(m.rolling_friction >= 0) || !(m.cohesion_energy_density >= 0))
    throw std::invalid_argument("friction, rolling friction and cohesion must be >= 0");
}

/// Integrates the scaled contact to separation; returns (restitution, duration).
std::pair<double, double> scaled_impact(double eta) {
  const double c = eta * std::sqrt(1.5);
  auto acc = [c](double s, double v) {
    const double sp = s > 0 ? s : 0.0;
    const double f = sp * std::sqrt(sp) + c * std::sqrt(std::sqrt(sp)) * v;
    return f > 0 ? -f : 0.0;  // a contact pushes, never pulls
  };
  const double h = 2e-4;
  double s = 0, v = 1, t = 0;
  for (int it = 0; it < 100000000; ++it) {
    const double k1s = v, k1v = acc(s, v);
    const double k2s = v + 0.5 * h * k1v, k2v = acc(s + 0.5 * h * k1s, v + 0.5 * h * k1v);
    const double k3s = v + 0.5 * h * k2v, k3v = acc(s + 0.5 * h * k2s, v + 0.5 * h * k2v);
    const double k4s = v + h * k3v, k4v = acc(s + h * k3s, v + h * k3v);
    const double s1 = s + h / 6 * (k1s + 2 * k2s + 2 * k3s + k4s);
    const double v1 = v + h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
    if (t > 0 && s1 <= 0) {
      const double frac = s / (s - s1);  // linear interpolation to s = 0
      return {-(v + frac * (v1 - v)), t + frac * h};
    }
    s = s1;
    v = v1;
    t += h;
  }
  throw std::runtime_error("scaled Hertz impact did not separate (damping too large)");
}

}  // namespace

double restitution_of_damping(double eta) { return scaled_impact(eta).first; }
double scaled_contact_duration(double eta) { return scaled_impact(eta).second; }

double damping_for_restitution(double e) {
  if (!(e > 0 && e <= 1)) throw std::invalid_argument("restitution must lie in (0, 1]");
  if (e == 1.0) return 0.0;
  // Restitution falls monotonically with damping: bracket, then bisect.
  double lo = 0.0, hi = 0.5;
  while (restitution_of_damping(hi) > e) {
    lo = hi;
    hi *= 2;
    if (hi > 64) throw std::invalid_argument("restitution too small to reach by damping");
  }
  for (int it = 0; it < 60 && hi - lo > 1e-10; ++it) {
    const double mid = 0.5 * (lo + hi);
    (restitution_of_damping(mid) > e ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

PairCoefficients pair_coefficients(const Material& a, const Material& b) {
  check(a);
  check(b);
  PairCoefficients c;
  c.e_star = 1.0 / ((1 - a.poisson_ratio * a.poisson_ratio) / a.youngs_modulus +
                    (1 - b.poisson_ratio * b.poisson_ratio) / b.youngs_modulus);
  c.g_star = 1.0 / (2 * (2 - a.poisson_ratio) * (1 + a.poisson_ratio) / a.youngs_modulus +
                    2 * (2 - b.poisson_ratio) * (1 + b.poisson_ratio) / b.youngs_modulus);
  c.damping = damping_for_restitution(0.5 * (a.restitution + b.restitution));
  c.friction = 0.5 * (a.friction + b.friction);
  c.rolling_friction = 0.5 * (a.rolling_friction + b.rolling_friction);
  c.cohesion = 0.5 * (a.cohesion_energy_density + b.cohesion_energy_density);
  c.kn = 4.0 / 3.0 * c.e_star;
  c.kt = 8.0 * c.g_star;
  c.gamma_n = c.damping * std::sqrt(2.0 * c.e_star);
  c.gamma_t = c.damping * std::sqrt(8.0 * c.g_star);
  return c;
}

double hertz_contact_time(double m_eff, double r_eff, double e_star, double v, double eta) {
  return scaled_contact_duration(eta) *
         std::pow(9.0 * m_eff * m_eff / (16.0 * e_star * e_star * r_eff * v), 0.2);
}

double rayleigh_time(const Material& m, double radius) {
  const double g = m.youngs_modulus / (2 * (1 + m.poisson_ratio));
  return M_PI * radius * std::sqrt(m.density / g) / (0.1631 * m.poisson_ratio + 0.8766);
}

}  // namespace amphora::physics::dem
