#pragma once
// The explicit node updates of a lumped-mass solid, as the kick and drift of velocity Verlet
// (the symplectic leapfrog written with velocities at the positions' times): kick v += h (f/m +
// g - alpha v), drift x += dt v. Pinned nodes are held; a ground plane x_up >= floor stops the
// normal velocity of the nodes that reach it (inelastic contact).
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

template <class ExecSpace, class MemSpace>
void drift(const ExecSpace& exec, double dt, int up, double floor,
           const Kokkos::View<char*, MemSpace>& pinned,
           const Kokkos::View<double* [3], MemSpace>& v,
           const Kokkos::View<double* [3], MemSpace>& x) {
  Kokkos::parallel_for(
      "amphora::solid::drift", RangePolicy<ExecSpace>(exec, 0, int(x.extent(0))),
      KOKKOS_LAMBDA(const int i) {
        if (pinned(i)) return;
        for (int d = 0; d < 3; ++d) x(i, d) += dt * v(i, d);
        if (x(i, up) < floor) {
          x(i, up) = floor;
          if (v(i, up) < 0.0) v(i, up) = 0.0;
        }
      });
}

}  // namespace amphora::kernels::solid
