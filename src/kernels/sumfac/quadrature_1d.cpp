#include "kernels/sumfac/quadrature_1d.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace amphora::kernels::sumfac {
namespace {

constexpr double pi = 3.14159265358979323846;

/// P_n(x) and P_n'(x) on [-1, 1] by the three-term recurrence.
void legendre(int n, double x, double& p, double& dp) {
  double p0 = 1.0, p1 = x;
  if (n == 0) {
    p = 1.0;
    dp = 0.0;
    return;
  }
  for (int k = 2; k <= n; ++k) {
    const double pk = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
    p0 = p1;
    p1 = pk;
  }
  p = p1;
  dp = n * (x * p1 - p0) / (x * x - 1.0);
}

/// Symmetrise about 1/2 (Newton leaves round-off asymmetry that would break even–odd kernels).
void symmetrise(Quadrature1D& q) {
  const std::size_t n = q.points.size();
  for (std::size_t i = 0; i < n / 2; ++i) {
    const double x = 0.5 * (q.points[i] + 1.0 - q.points[n - 1 - i]);
    const double w = 0.5 * (q.weights[i] + q.weights[n - 1 - i]);
    q.points[i] = x;
    q.points[n - 1 - i] = 1.0 - x;
    q.weights[i] = q.weights[n - 1 - i] = w;
  }
  if (n % 2 == 1) q.points[n / 2] = 0.5;
}

}  // namespace

Quadrature1D gauss(int n) {
  if (n < 1) throw std::invalid_argument("gauss: need at least 1 point, got " + std::to_string(n));
  Quadrature1D q;
  q.points.resize(n);
  q.weights.resize(n);
  for (int i = 0; i < n; ++i) {
    double x = -std::cos(pi * (i + 0.75) / (n + 0.5));
    double p = 0.0, dp = 0.0;
    for (int it = 0; it < 100; ++it) {
      legendre(n, x, p, dp);
      const double dx = p / dp;
      x -= dx;
      if (std::abs(dx) < 1e-17) break;
    }
    legendre(n, x, p, dp);
    q.points[i] = 0.5 * (x + 1.0);
    q.weights[i] = 1.0 / ((1.0 - x * x) * dp * dp);  // 2/((1-x^2)P'^2), halved for [0, 1]
  }
  symmetrise(q);
  return q;
}

Quadrature1D gauss_lobatto(int n) {
  if (n < 2)
    throw std::invalid_argument("gauss_lobatto: need at least 2 points, got " + std::to_string(n));
  Quadrature1D q;
  q.points.resize(n);
  q.weights.resize(n);
  const int m = n - 1;  // interior points: roots of P'_m
  for (int i = 0; i < n; ++i) {
    double x = -std::cos(pi * i / m);
    if (i > 0 && i < m) {
      for (int it = 0; it < 100; ++it) {
        // Newton on P'_m: P''_m = (2x P'_m - m(m+1) P_m) / (1 - x^2).
        double p = 0.0, dp = 0.0;
        legendre(m, x, p, dp);
        const double d2p = (2.0 * x * dp - m * (m + 1.0) * p) / (1.0 - x * x);
        const double dx = dp / d2p;
        x -= dx;
        if (std::abs(dx) < 1e-17) break;
      }
    }
    double p = 0.0, dp = 0.0;
    if (i == 0 || i == m) {
      p = (i == 0 && m % 2 == 1) ? -1.0 : 1.0;
    } else {
      legendre(m, x, p, dp);
    }
    q.points[i] = 0.5 * (x + 1.0);
    q.weights[i] = 1.0 / (m * (m + 1.0) * p * p);  // 2/(m(m+1)P_m^2), halved
  }
  symmetrise(q);
  return q;
}

std::vector<double> lagrange_values(const std::vector<double>& nodes,
                                    const std::vector<double>& x) {
  const std::size_t n = nodes.size();
  std::vector<double> v(x.size() * n);
  for (std::size_t q = 0; q < x.size(); ++q)
    for (std::size_t j = 0; j < n; ++j) {
      double l = 1.0;
      for (std::size_t m = 0; m < n; ++m)
        if (m != j) l *= (x[q] - nodes[m]) / (nodes[j] - nodes[m]);
      v[q * n + j] = l;
    }
  return v;
}

std::vector<double> lagrange_derivatives(const std::vector<double>& nodes,
                                         const std::vector<double>& x) {
  const std::size_t n = nodes.size();
  std::vector<double> d(x.size() * n);
  for (std::size_t q = 0; q < x.size(); ++q)
    for (std::size_t j = 0; j < n; ++j) {
      // l_j' = sum_{m != j} 1/(x_j - x_m) prod_{r != j, m} (x - x_r)/(x_j - x_r)
      double s = 0.0;
      for (std::size_t m = 0; m < n; ++m) {
        if (m == j) continue;
        double l = 1.0 / (nodes[j] - nodes[m]);
        for (std::size_t r = 0; r < n; ++r)
          if (r != j && r != m) l *= (x[q] - nodes[r]) / (nodes[j] - nodes[r]);
        s += l;
      }
      d[q * n + j] = s;
    }
  return d;
}

}  // namespace amphora::kernels::sumfac
