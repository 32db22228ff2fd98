#pragma once
// Exact incompressible flows for verification and initial conditions, one component at a time
// (0 .. dim-1 velocity, dim pressure), device-callable with value(x) and gradient(x, g) as
// solvers::matrix_free::error_norms asks.
#include <Kokkos_Core.hpp>

#include "kernels/kokkos_compat.hpp"

namespace amphora::physics::ins_fem {

/// The 2D Taylor-Green vortex on [0, 2 pi]^2 (periodic), an exact Navier-Stokes solution:
/// u = g (sin x cos y, -cos x sin y), p = g^2 (cos 2x + cos 2y) / 4. Free decay has
/// g = exp(-2 nu t); any other g(t) needs the force f = (g' + 2 nu g) (sin x cos y, -cos x sin y)
/// (the convection is balanced by the pressure whatever g is).
struct TaylorGreen2D {
  int component = 0;
  double g = 1.0;  ///< amplitude g(t)

  KOKKOS_INLINE_FUNCTION double value(const double* x) const {
    using kernels::math::cos;
    using kernels::math::sin;
    if (component == 0) return g * sin(x[0]) * cos(x[1]);
    if (component == 1) return -g * cos(x[0]) * sin(x[1]);
    return 0.25 * g * g * (cos(2.0 * x[0]) + cos(2.0 * x[1]));
  }
  KOKKOS_INLINE_FUNCTION void gradient(const double* x, double* d) const {
    using kernels::math::cos;
    using kernels::math::sin;
    if (component == 0) {
      d[0] = g * cos(x[0]) * cos(x[1]), d[1] = -g * sin(x[0]) * sin(x[1]);
    } else if (component == 1) {
      d[0] = g * sin(x[0]) * sin(x[1]), d[1] = -g * cos(x[0]) * cos(x[1]);
    } else {
      d[0] = -0.5 * g * g * sin(2.0 * x[0]), d[1] = -0.5 * g * g * sin(2.0 * x[1]);
    }
  }
};

/// Kovasznay's flow behind a grid (Kovasznay 1948), steady, Reynolds number re (nu = 1 / re):
/// u = 1 - e^(l x) cos 2 pi y, v = l / (2 pi) e^(l x) sin 2 pi y, p = (1 - e^(2 l x)) / 2,
/// l = re / 2 - sqrt(re^2 / 4 + 4 pi^2).
struct Kovasznay {
  static constexpr double pi = kernels::math::pi;
  int component = 0;
  double re = 40.0;

  KOKKOS_INLINE_FUNCTION double lambda() const {
    return 0.5 * re - kernels::math::sqrt(0.25 * re * re + 4.0 * pi * pi);
  }
  KOKKOS_INLINE_FUNCTION double value(const double* x) const {
    const double l = lambda(), e = kernels::math::exp(l * x[0]);
    if (component == 0) return 1.0 - e * kernels::math::cos(2.0 * pi * x[1]);
    if (component == 1) return l / (2.0 * pi) * e * kernels::math::sin(2.0 * pi * x[1]);
    return 0.5 * (1.0 - e * e);
  }
  KOKKOS_INLINE_FUNCTION void gradient(const double* x, double* d) const {
    const double l = lambda(), e = kernels::math::exp(l * x[0]);
    const double c = kernels::math::cos(2.0 * pi * x[1]), s = kernels::math::sin(2.0 * pi * x[1]);
    if (component == 0) {
      d[0] = -l * e * c, d[1] = 2.0 * pi * e * s;
    } else if (component == 1) {
      d[0] = l * l / (2.0 * pi) * e * s, d[1] = l * e * c;
    } else {
      d[0] = -l * e * e, d[1] = 0.0;
    }
  }
};

/// Plane Poiseuille flow in the channel [0, length] x [0, 1] (walls at y = 0, 1, outflow at
/// x = length where nu du/dn - p n = 0): u = 4 y (1 - y), v = 0, p = 8 nu (length - x).
/// Quadratic velocity, linear pressure: Q_k with k >= 2 holds it exactly.
struct Poiseuille {
  int component = 0;
  double nu = 0.01;
  double length = 2.0;

  KOKKOS_INLINE_FUNCTION double value(const double* x) const {
    if (component == 0) return 4.0 * x[1] * (1.0 - x[1]);
    if (component == 1) return 0.0;
    return 8.0 * nu * (length - x[0]);
  }
  KOKKOS_INLINE_FUNCTION void gradient(const double* x, double* d) const {
    d[0] = 0.0, d[1] = 0.0;
    if (component == 0) d[1] = 4.0 - 8.0 * x[1];
    if (component == 2) d[0] = -8.0 * nu;
  }
};

/// The 3D Taylor-Green vortex's initial state on [-pi, pi]^3 (Brachet et al. 1983; the
/// Re = 1600 case of the high-order workshops): u = (sin x cos y cos z, -cos x sin y cos z, 0),
/// p = (cos 2x + cos 2y)(cos 2z + 2) / 16.
struct TaylorGreen3D {
  int component = 0;

  KOKKOS_INLINE_FUNCTION double value(const double* x) const {
    using kernels::math::cos;
    using kernels::math::sin;
    if (component == 0) return sin(x[0]) * cos(x[1]) * cos(x[2]);
    if (component == 1) return -cos(x[0]) * sin(x[1]) * cos(x[2]);
    if (component == 2) return 0.0;
    return (cos(2.0 * x[0]) + cos(2.0 * x[1])) * (cos(2.0 * x[2]) + 2.0) / 16.0;
  }
};

}  // namespace amphora::physics::ins_fem
