#pragma once
// Semi-Lagrangian advection on the MAC lattice (Stam 1999; Bridson sec. 3.1): each sample takes
// the value at its departure point, traced back through the velocity field with the midpoint
// rule (second order in time), interpolated trilinearly. Unconditionally stable; the trace may
// cross several cells, which is why the uniform band of a tall-cell grid must be at least the
// CFL number deep.
#include "kernels/mac/staggered_interpolation.hpp"

namespace amphora::kernels::mac {

namespace detail {
/// The departure point, in cell widths, of sample (i, j, k) of staggering s at q (cell widths)
/// traced back over dt with the midpoint rule.
template <class U, class V, class W>
KOKKOS_FORCEINLINE_FUNCTION void departure_point(const kernels::mac::MacGrid& g, Staggering s,
                                                 int i, int j, int k, const U& u, const V& v,
                                                 const W& w, double dt, const double q[3],
                                                 double out[3]) {
  const double scale = dt / g.h;  // velocity x dt in cell widths
  double vel[3], mid[3];
  velocity_at_sample(g, s, i, j, k, u, v, w, vel);
  for (int d = 0; d < 3; ++d) mid[d] = q[d] - 0.5 * scale * vel[d];
  velocity_at_cells(g, u, v, w, mid, vel);
  for (int d = 0; d < 3; ++d) out[d] = q[d] - scale * vel[d];
}
}  // namespace detail

/// The semi-Lagrangian value of sample (i, j, k) of q (staggering s) after dt.
template <class Q, class U, class V, class W>
KOKKOS_FORCEINLINE_FUNCTION double semi_lagrangian_sample(const kernels::mac::MacGrid& g,
                                                          Staggering s, int i, int j, int k,
                                                          const Q& q, const U& u, const V& v,
                                                          const W& w, double dt) {
  // the sample's position in cell widths from the box corner
  const double x[3] = {i + (s == Staggering::x ? 0.0 : 0.5), j + (s == Staggering::y ? 0.0 : 0.5),
                       k + (s == Staggering::z ? 0.0 : 0.5)};
  double back[3];
  detail::departure_point(g, s, i, j, k, u, v, w, dt, x, back);
  return interpolate_cells(g, q, s, back);
}

}  // namespace amphora::kernels::mac
