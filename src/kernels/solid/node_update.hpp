#pragma once
// The explicit node updates of a lumped-mass solid, as the kick and drift of velocity Verlet
// (the symplectic leapfrog written with velocities at the positions' times): kick v += h (f/m +
// g - alpha v), drift x += dt v. Pinned nodes are held; a ground plane (tilted: a ramp) and
// two moving plates hold the nodes on their side and take away the approaching normal
// velocity (relative to the plane) of the nodes that reach one (inelastic), and with a
// friction coefficient mu as much tangential velocity as mu times the normal velocity taken
// (Coulomb friction as an impulse; Bridson, Fedkiw & Anderson, SIGGRAPH 2002, section 7.2).
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
  double friction = 0.0;  ///< Coulomb coefficient mu of the ground and the plates
};

namespace node_detail {

/// v's components other than `skip` (a plate's normal axis; -1: v minus its part along n)
/// scaled by max(0, 1 - mu dvn / |v_t|): the tangential velocity a normal impulse dvn can stop.
template <class Velocities>
KOKKOS_INLINE_FUNCTION void apply_friction(const Velocities& v, int i, double mu, double dvn,
                                           const double* n, int skip) {
  double t[3];
  for (int d = 0; d < 3; ++d) t[d] = v(i, d);
  if (skip < 0) {
    const double vn = n[0] * t[0] + n[1] * t[1] + n[2] * t[2];
    for (int d = 0; d < 3; ++d) t[d] -= vn * n[d];
  } else {
    t[skip] = 0.0;
  }
  const double vt = math::sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
  const double keep = vt > mu * dvn ? 1.0 - mu * dvn / vt : 0.0;
  for (int d = 0; d < 3; ++d) v(i, d) -= (1.0 - keep) * t[d];
}

}  // namespace node_detail

/// x += dt v for the free nodes, then the planes: a node that passes one is put back on it,
/// loses its approaching normal velocity and, with friction, tangential velocity; its
/// tangential step is then redone with the velocity friction left (so a stuck node stays).
template <class ExecSpace, class MemSpace>
void drift(const ExecSpace& exec, double dt, const BoundingPlanes& p,
           const Kokkos::View<char*, MemSpace>& pinned,
           const Kokkos::View<double* [3], MemSpace>& v,
           const Kokkos::View<double* [3], MemSpace>& x) {
  Kokkos::parallel_for(
      "amphora::solid::drift", RangePolicy<ExecSpace>(exec, 0, int(x.extent(0))),
      KOKKOS_LAMBDA(const int i) {
        if (pinned(i)) return;
        double y[3];
        for (int d = 0; d < 3; ++d) y[d] = x(i, d) + dt * v(i, d);
        const double gap = p.n[0] * y[0] + p.n[1] * y[1] + p.n[2] * y[2] - p.d;
        if (gap < 0.0) {
          const double vn = p.n[0] * v(i, 0) + p.n[1] * v(i, 1) + p.n[2] * v(i, 2);
          if (vn < 0.0) {
            for (int d = 0; d < 3; ++d) v(i, d) -= vn * p.n[d];
            if (p.friction > 0.0) {
              node_detail::apply_friction(v, i, p.friction, -vn, p.n, -1);
              for (int d = 0; d < 3; ++d) y[d] = x(i, d) + dt * v(i, d);
            }
          }
          const double g = p.n[0] * y[0] + p.n[1] * y[1] + p.n[2] * y[2] - p.d;
          if (g < 0.0)
            for (int d = 0; d < 3; ++d) y[d] -= g * p.n[d];
        }
        const int u = p.up;
        const bool below = y[u] < p.lo;
        const bool above = y[u] > p.hi;
        if (below || above) {
          const double target = below ? p.lo : p.hi, vp = below ? p.v_lo : p.v_hi;
          const double dvn = below ? vp - v(i, u) : v(i, u) - vp;
          if (dvn > 0.0) {
            v(i, u) = vp;
            if (p.friction > 0.0) {
              node_detail::apply_friction(v, i, p.friction, dvn, p.n, u);
              for (int d = 0; d < 3; ++d)
                if (d != u) y[d] = x(i, d) + dt * v(i, d);
            }
          }
          y[u] = target;
        }
        for (int d = 0; d < 3; ++d) x(i, d) = y[d];
      });
}

}  // namespace amphora::kernels::solid
