#pragma once
// One-ring nodal volumes of a linear-tetrahedron mesh and their gradient B (Irving, Schroeder
// & Fedkiw, "Volume conserving finite element simulations of deformable models", SIGGRAPH
// 2007, section 3): V_i(x) = 1/4 sum_{t ni i} V_t(x), so that the V_i add up to the body's
// volume, and B = dV/dx (N x 3N), applied element by element with g_tc = dV_t/dx_c:
// (B u)_i = 1/4 sum_{t ni i} sum_c g_tc . u_c and (B^T p)_c = sum_{t ni c} g_tc 1/4 sum_{i in t}
// p_i. Both scatter with atomics.
#include "kernels/spaces.hpp"

namespace amphora::kernels::solid {

/// V_t (signed) and g_tc = dV_t/dx_c per element at x: with e_k = x_k - x_0,
/// g_1 = e_2 x e_3 / 6, g_2 = e_3 x e_1 / 6, g_3 = e_1 x e_2 / 6, g_0 = -(g_1 + g_2 + g_3).
template <class ExecSpace, class MemSpace>
void tet_volume_gradients(const ExecSpace& exec, const Kokkos::View<int* [4], MemSpace>& tets,
                          const Kokkos::View<double* [3], MemSpace>& x,
                          const Kokkos::View<double*, MemSpace>& volume,
                          const Kokkos::View<double* [4][3], MemSpace>& grad) {
  Kokkos::parallel_for(
      "amphora::solid::tet_volume_gradients", RangePolicy<ExecSpace>(exec, 0, int(tets.extent(0))),
      KOKKOS_LAMBDA(const int t) {
        double e[3][3];
        for (int k = 0; k < 3; ++k)
          for (int d = 0; d < 3; ++d) e[k][d] = x(tets(t, k + 1), d) - x(tets(t, 0), d);
        for (int k = 0; k < 3; ++k) {
          const double* a = e[(k + 1) % 3];
          const double* b = e[(k + 2) % 3];
          grad(t, k + 1, 0) = (a[1] * b[2] - a[2] * b[1]) / 6.0;
          grad(t, k + 1, 1) = (a[2] * b[0] - a[0] * b[2]) / 6.0;
          grad(t, k + 1, 2) = (a[0] * b[1] - a[1] * b[0]) / 6.0;
        }
        for (int d = 0; d < 3; ++d)
          grad(t, 0, d) = -(grad(t, 1, d) + grad(t, 2, d) + grad(t, 3, d));
        volume(t) = e[0][0] * grad(t, 1, 0) + e[0][1] * grad(t, 1, 1) + e[0][2] * grad(t, 1, 2);
      });
}

/// out = the one-ring volumes V_i of the element volumes (out is zeroed first).
template <class ExecSpace, class MemSpace>
void node_volumes(const ExecSpace& exec, const Kokkos::View<int* [4], MemSpace>& tets,
                  const Kokkos::View<double*, MemSpace>& volume,
                  const Kokkos::View<double*, MemSpace>& out) {
  Kokkos::deep_copy(exec, out, 0.0);
  Kokkos::parallel_for(
      "amphora::solid::node_volumes", RangePolicy<ExecSpace>(exec, 0, int(tets.extent(0))),
      KOKKOS_LAMBDA(const int t) {
        for (int c = 0; c < 4; ++c) Kokkos::atomic_add(&out(tets(t, c)), 0.25 * volume(t));
      });
}

/// out = B u (one value per node; out is zeroed first).
template <class ExecSpace, class MemSpace>
void volume_gradient_apply(const ExecSpace& exec, const Kokkos::View<int* [4], MemSpace>& tets,
                           const Kokkos::View<double* [4][3], MemSpace>& grad,
                           const Kokkos::View<double* [3], MemSpace>& u,
                           const Kokkos::View<double*, MemSpace>& out) {
  Kokkos::deep_copy(exec, out, 0.0);
  Kokkos::parallel_for(
      "amphora::solid::volume_gradient_apply", RangePolicy<ExecSpace>(exec, 0, int(tets.extent(0))),
      KOKKOS_LAMBDA(const int t) {
        double rate = 0.0;
        for (int c = 0; c < 4; ++c)
          for (int d = 0; d < 3; ++d) rate += grad(t, c, d) * u(tets(t, c), d);
        for (int c = 0; c < 4; ++c) Kokkos::atomic_add(&out(tets(t, c)), 0.25 * rate);
      });
}

/// out = B^T p (a vector per node; out is zeroed first).
template <class ExecSpace, class MemSpace>
void volume_gradient_transpose_apply(const ExecSpace& exec,
                                     const Kokkos::View<int* [4], MemSpace>& tets,
                                     const Kokkos::View<double* [4][3], MemSpace>& grad,
                                     const Kokkos::View<double*, MemSpace>& p,
                                     const Kokkos::View<double* [3], MemSpace>& out) {
  Kokkos::deep_copy(exec, out, 0.0);
  Kokkos::parallel_for(
      "amphora::solid::volume_gradient_transpose_apply",
      RangePolicy<ExecSpace>(exec, 0, int(tets.extent(0))), KOKKOS_LAMBDA(const int t) {
        const double pt = 0.25 * (p(tets(t, 0)) + p(tets(t, 1)) + p(tets(t, 2)) + p(tets(t, 3)));
        for (int c = 0; c < 4; ++c)
          for (int d = 0; d < 3; ++d) Kokkos::atomic_add(&out(tets(t, c), d), grad(t, c, d) * pt);
      });
}

}  // namespace amphora::kernels::solid
