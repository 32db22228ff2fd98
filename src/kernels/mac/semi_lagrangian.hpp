#pragma once
// Semi-Lagrangian advection on the MAC lattice (Stam 1999; Bridson sec. 3.1): each sample takes
// the value at its departure point, traced back through the velocity field with the midpoint
// rule (second order in time), interpolated trilinearly. Unconditionally stable; the trace may
// cross several cells, which is why the uniform band of a tall-cell grid must be at least the
// CFL number deep.
#include "kernels/mac/staggered_interpolation.hpp"

namespace amphora::kernels::mac {

namespace detail {
template <class U, class V, class W>
KOKKOS_INLINE_FUNCTION void departure_point(const mesh::MacGrid& g, const U& u, const V& v, const W& w, double dt,
                                            const double x[3], double out[3]) {
  double vel[3], mid[3];
  velocity_at(g, u, v, w, x, vel);
  for (int d = 0; d < 3; ++d) mid[d] = x[d] - 0.5 * dt * vel[d];
  velocity_at(g, u, v, w, mid, vel);
  for (int d = 0; d < 3; ++d) out[d] = x[d] - dt * vel[d];
}
}  // namespace detail

/// q_new = q(departure point) for every sample of staggering s: cells (0..n-1)^3, or faces
/// (0..n along the staggered direction). q_new must not alias q.
template <class ExecSpace, class Q, class QN, class U, class V, class W>
void advect(const ExecSpace& exec, const mesh::MacGrid& g, Staggering s, const Q& q, const QN& q_new, const U& u,
            const V& v, const W& w, double dt) {
  const int ex = g.nx + (s == Staggering::x), ey = g.ny + (s == Staggering::y), ez = g.nz + (s == Staggering::z);
  Kokkos::parallel_for(
      "amphora::mac::advect", Kokkos::MDRangePolicy<ExecSpace, Kokkos::Rank<3>>(exec, {0, 0, 0}, {ez, ey, ex}),
      KOKKOS_LAMBDA(int k, int j, int i) {
        double x[3], back[3];
        sample_position(g, s, i, j, k, x);
        detail::departure_point(g, u, v, w, dt, x, back);
        q_new(g.index(i, j, k)) = interpolate(g, q, s, back);
      });
}

}  // namespace amphora::kernels::mac
