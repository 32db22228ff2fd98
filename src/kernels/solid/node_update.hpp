#pragma once
// The explicit node updates of a lumped-mass solid, as the kick and drift of velocity Verlet
// (the symplectic leapfrog written with velocities at the positions' times): kick v += h (f/m +
// g - alpha v), drift x += dt v. Pinned nodes are held; a ground plane (tilted: a ramp) and
// two moving plates hold the nodes on their side and take away the approaching normal
// velocity (relative to the plane) of the nodes that reach one (inelastic, frictionless).
#include "kernels/spaces.hpp"

namespace amphora::kernels::solid {

struct NodeKick {
  double h = 0.0;  ///< the kick's time span (dt / 2 in velocity Verlet)
  double gravity[3] = {0.0, 0.0, 0.0};
  double alpha = 0.0;  ///< mass-proportional damping rate [1/s]
};

template <class ExecSpace, class MemSpace>
void kick(const ExecSpace& exec, const NodeKick& k, const Kokkos::View<double*, MemSpace>& mass,
          const Kokkos::View<char*, MemSpace>& pinned, const Kokkos::View<double* [3], MemSpace>& f,
          const Kokkos::View<double* [3], MemSpace>& v) {
  Kokkos::parallel_for(
      "amphora::solid::kick", RangePolicy<ExecSpace>(exec, 0, int(v.extent(0))),
      KOKKOS_LAMBDA(const int i) {
        if (pinned(i)) return;
        for (int d = 0; d < 3; ++d)
          v(i, d) += k.h * (f(i, d) / mass(i) + k.gravity[d] - k.alpha * v(i, d));
      });
}

/// The ground n . x >= d (n a unit normal, at rest) and two plates normal to the axis `up`,
/// x_up >= lo (moving at v_lo along up) and x_up <= hi (moving at v_hi).
struct BoundingPlanes {
  double n[3] = {0.0, 0.0, 1.0};
  double d = -1e300;
  int up = 2;
  double lo = -1e300, v_lo = 0.0;
  double hi = 1e300, v_hi = 0.0;
};

template <class ExecSpace, class MemSpace>
void drift(const ExecSpace& exec, double dt, const BoundingPlanes& p,
           const Kokkos::View<char*, MemSpace>& pinned,
           const Kokkos::View<double* [3], MemSpace>& v,
           const Kokkos::View<double* [3], MemSpace>& x) {
  Kokkos::parallel_for(
      "amphora::solid::drift", RangePolicy<ExecSpace>(exec, 0, int(x.extent(0))),
      KOKKOS_LAMBDA(const int i) {
        if (pinned(i)) return;
        for (int d = 0; d < 3; ++d) x(i, d) += dt * v(i, d);
        const double gap = p.n[0] * x(i, 0) + p.n[1] * x(i, 1) + p.n[2] * x(i, 2) - p.d;
        if (gap < 0.0) {
          const double vn = p.n[0] * v(i, 0) + p.n[1] * v(i, 1) + p.n[2] * v(i, 2);
          for (int d = 0; d < 3; ++d) {
            x(i, d) -= gap * p.n[d];
            if (vn < 0.0) v(i, d) -= vn * p.n[d];
          }
        }
        if (x(i, p.up) < p.lo) {
          x(i, p.up) = p.lo;
          if (v(i, p.up) < p.v_lo) v(i, p.up) = p.v_lo;
        }
        if (x(i, p.up) > p.hi) {
          x(i, p.up) = p.hi;
          if (v(i, p.up) > p.v_hi) v(i, p.up) = p.v_hi;
        }
      });
}

}  // namespace amphora::kernels::solid
