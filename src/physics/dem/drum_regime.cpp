#include "physics/dem/drum_regime.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include <Eigen/Dense>

namespace amphora::physics::dem {

const char* to_string(DrumRegime r) {
  switch (r) {
    case DrumRegime::kRolling: return "rolling";
    case DrumRegime::kCascading: return "cascading";
    case DrumRegime::kCataracting: return "cataracting";
    case DrumRegime::kCentrifuging: return "centrifuging";
  }
  return "?";
}

DrumClassification classify_drum(const DrumState& drum, const std::vector<double>& x,
                                 const std::vector<double>& v, const std::vector<int>& contacts) {
  DrumClassification c;
  const size_t n = contacts.size();
  if (n == 0) return c;
  size_t upper = 0;
  for (size_t i = 0; i < n; ++i) {
    const double px = x[3 * i], py = x[3 * i + 1];
    const double r = std::sqrt(px * px + py * py);
    // Angular velocity about the axis: (x v_y - y v_x) / r^2.
    const double w = r > 0 ? (px * v[3 * i + 1] - py * v[3 * i]) / (r * r) : 0.0;
    const bool with_wall = drum.angular_velocity != 0 && std::abs(w - drum.angular_velocity) <
                                                             0.3 * std::abs(drum.angular_velocity);
    if (py > 0 && with_wall) ++upper;
  }
  c.upper_fraction = double(upper) / n;

  // Free surface: the highest touching particle in each diameter-wide column across the drum.
  std::map<long, double> top;
  for (size_t i = 0; i < n; ++i) {
    if (contacts[i] == 0) continue;
    const long col = std::lround(std::floor(x[3 * i] / drum.diameter));
    auto it = top.find(col);
    if (it == top.end() || x[3 * i + 1] > it->second) top[col] = x[3 * i + 1];
  }
  std::vector<std::pair<double, double>> surface;
  for (const auto& [col, y] : top) surface.emplace_back((col + 0.5) * drum.diameter, y);
  // Drop the columns at the ends, where the surface meets the wall.
  const size_t cut = surface.size() / 6;
  if (surface.size() >= 6) surface = {surface.begin() + cut, surface.end() - cut};
  if (surface.size() >= 5) {
    // Least-squares line and cubic through the surface (Eigen's QR): the line gives the
    // inclination; the rms gap between the two fits is the systematic S/kidney bending of a
    // cascading bed, free of the particle-scale roughness both fits smooth out.
    const Eigen::Index m = static_cast<Eigen::Index>(surface.size());
    Eigen::MatrixXd a(m, 4);
    Eigen::VectorXd y(m);
    for (Eigen::Index k = 0; k < m; ++k) {
      const double px = surface[k].first / drum.radius;
      a(k, 0) = 1;
      a(k, 1) = px;
      a(k, 2) = px * px;
      a(k, 3) = px * px * px;
      y(k) = surface[k].second;
    }
    const Eigen::VectorXd line = a.leftCols(2).colPivHouseholderQr().solve(y);
    const Eigen::VectorXd cubic = a.colPivHouseholderQr().solve(y);
    const Eigen::VectorXd gap = a.leftCols(2) * line - a * cubic;
    c.surface_angle = std::atan(std::abs(line(1) / drum.radius)) * 180.0 / M_PI;
    c.surface_deviation = std::sqrt(gap.squaredNorm() / double(m)) / drum.diameter;
    // In flight: touching nothing and more than two diameters above the surface line (rattlers
    // and the flowing layer's brief separations stay within it).
    size_t airborne = 0;
    for (size_t i = 0; i < n; ++i) {
      const double px = x[3 * i] / drum.radius;
      if (contacts[i] == 0 && x[3 * i + 1] - (line(0) + line(1) * px) > 2 * drum.diameter)
        ++airborne;
    }
    c.airborne_fraction = double(airborne) / n;
  }

  c.regime = regime_of(c.upper_fraction, c.airborne_fraction, c.surface_deviation);
  return c;
}

DrumRegime regime_of(double upper_fraction, double airborne_fraction, double surface_deviation) {
  if (upper_fraction > 0.25) return DrumRegime::kCentrifuging;
  if (airborne_fraction > 0.05) return DrumRegime::kCataracting;
  if (surface_deviation > 0.4) return DrumRegime::kCascading;
  return DrumRegime::kRolling;
}

}  // namespace amphora::physics::dem
