#pragma once
// u = prod_d sin(pi x_d) on the unit square/cube, -lap u = dim pi^2 u, u = 0 on the boundary:
// the manufactured solution of poisson_fem and of the convergence tests.
#include "kernels/kokkos_compat.hpp"
#include "mesh/hex/structured_hex_mesh.hpp"

namespace amphora::physics::poisson_fem {

template <int dim>
struct SineSolution {
  static constexpr double pi = 3.14159265358979323846;
  KOKKOS_INLINE_FUNCTION double value(const double* x) const {
    double v = 1.0;
    for (int d = 0; d < dim; ++d) v *= kernels::math::sin(pi * x[d]);
    return v;
  }
  KOKKOS_INLINE_FUNCTION void gradient(const double* x, double* g) const {
    for (int a = 0; a < dim; ++a) {
      g[a] = pi;
      for (int d = 0; d < dim; ++d)
        g[a] *= d == a ? kernels::math::cos(pi * x[d]) : kernels::math::sin(pi * x[d]);
    }
  }
  /// -lap u at x (host; for interpolating the right-hand side).
  double source(const mesh::hex::Point3& x) const {
    double v = dim * pi * pi;
    for (int d = 0; d < dim; ++d) v *= kernels::math::sin(pi * x[d]);
    return v;
  }
};

}  // namespace amphora::physics::poisson_fem
