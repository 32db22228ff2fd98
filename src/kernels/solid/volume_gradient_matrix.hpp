#pragma once
// B = dV/dx of the one-ring volumes (kernels/solid/node_volumes.hpp) stored as a sparse
// matrix of 3-vectors on the node graph (nodes that share an element), B_ic = 1/4 sum over
// the elements t holding i and c of g_tc, so that B W B^T applies row by row without atomics:
// (B^T p)_c = sum_i B_ic p_i over row c (through the mirror slot of each entry) and
// (B u)_i = sum_c B_ic . u_c over row i. The graph is built once on the host; the values are
// assembled on the device from the elements' volume gradients.
#include <algorithm>
#include <vector>

#include "kernels/spaces.hpp"

namespace amphora::kernels::solid {

template <class MemSpace>
struct VolumeGradientMatrix {
  Kokkos::View<int*, MemSpace> row;           ///< row i's slots are [row(i), row(i + 1))
  Kokkos::View<int*, MemSpace> col;           ///< the column (node) of each slot, sorted per row
  Kokkos::View<int*, MemSpace> mirror;        ///< the slot of (col, row) for each slot (i, col)
  Kokkos::View<int* [16], MemSpace> slot;     ///< per element: the slot of (node a, node c), 4a + c
  Kokkos::View<double* [3], MemSpace> value;  ///< B_ic per slot
};

/// The graph of the mesh's n nodes and its element slots (host work, once per mesh).
template <class MemSpace>
VolumeGradientMatrix<MemSpace> volume_gradient_graph(const Kokkos::View<int* [4], MemSpace>& tets,
                                                     int n) {
  const auto t = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), tets);
  const int m = static_cast<int>(t.extent(0));
  std::vector<std::vector<int>> adj(n);
  for (int e = 0; e < m; ++e)
    for (int a = 0; a < 4; ++a)
      for (int c = 0; c < 4; ++c) adj[t(e, a)].push_back(t(e, c));
  // Host mirrors of the device views (the same layouts on every backend), filled, then copied.
  VolumeGradientMatrix<MemSpace> B;
  B.row = Kokkos::View<int*, MemSpace>("solid::B::row", n + 1);
  auto row = Kokkos::create_mirror_view(B.row);
  row(0) = 0;
  for (int i = 0; i < n; ++i) {
    std::sort(adj[i].begin(), adj[i].end());
    adj[i].erase(std::unique(adj[i].begin(), adj[i].end()), adj[i].end());
    row(i + 1) = row(i) + static_cast<int>(adj[i].size());
  }
  const int nnz = row(n);
  B.col = Kokkos::View<int*, MemSpace>("solid::B::col", nnz);
  B.mirror = Kokkos::View<int*, MemSpace>("solid::B::mirror", nnz);
  B.slot = Kokkos::View<int* [16], MemSpace>("solid::B::slot", m);
  B.value = Kokkos::View<double* [3], MemSpace>("solid::B::value", nnz);
  auto col = Kokkos::create_mirror_view(B.col);
  auto mirror = Kokkos::create_mirror_view(B.mirror);
  auto slot = Kokkos::create_mirror_view(B.slot);
  auto find = [&](int i, int c) {
    return row(i) +
           static_cast<int>(std::lower_bound(adj[i].begin(), adj[i].end(), c) - adj[i].begin());
  };
  for (int i = 0; i < n; ++i)
    for (size_t k = 0; k < adj[i].size(); ++k) col(row(i) + k) = adj[i][k];
  for (int i = 0; i < n; ++i)
    for (int k = row(i); k < row(i + 1); ++k) mirror(k) = find(col(k), i);
  for (int e = 0; e < m; ++e)
    for (int a = 0; a < 4; ++a)
      for (int c = 0; c < 4; ++c) slot(e, 4 * a + c) = find(t(e, a), t(e, c));
  Kokkos::deep_copy(B.row, row);
  Kokkos::deep_copy(B.col, col);
  Kokkos::deep_copy(B.mirror, mirror);
  Kokkos::deep_copy(B.slot, slot);
  return B;
}

/// B's values from the element volume gradients g (tet_volume_gradients).
template <class ExecSpace, class MemSpace>
void assemble_volume_gradient(const ExecSpace& exec,
                              const Kokkos::View<double* [4][3], MemSpace>& g,
                              const VolumeGradientMatrix<MemSpace>& B) {
  const auto value = B.value;
  const auto slot = B.slot;
  Kokkos::deep_copy(exec, value, 0.0);
  Kokkos::parallel_for(
      "amphora::solid::assemble_volume_gradient", RangePolicy<ExecSpace>(exec, 0, int(g.extent(0))),
      KOKKOS_LAMBDA(const int t) {
        for (int a = 0; a < 4; ++a)
          for (int c = 0; c < 4; ++c)
            for (int d = 0; d < 3; ++d)
              Kokkos::atomic_add(&value(slot(t, 4 * a + c), d), 0.25 * g(t, c, d));
      });
}

/// u_c = W_c (B^T p)_c with W_c = w_c (I - n_c n_c^T) (a weight and a unit normal or zero).
template <class ExecSpace, class MemSpace>
void volume_gradient_transpose_weighted(const ExecSpace& exec,
                                        const VolumeGradientMatrix<MemSpace>& B,
                                        const Kokkos::View<double*, MemSpace>& w,
                                        const Kokkos::View<double* [3], MemSpace>& normal,
                                        const Kokkos::View<double*, MemSpace>& p,
                                        const Kokkos::View<double* [3], MemSpace>& u) {
  const auto row = B.row;
  const auto col = B.col;
  const auto mirror = B.mirror;
  const auto value = B.value;
  Kokkos::parallel_for(
      "amphora::solid::volume_gradient_transpose_weighted",
      RangePolicy<ExecSpace>(exec, 0, int(u.extent(0))), KOKKOS_LAMBDA(const int c) {
        double s[3] = {0.0, 0.0, 0.0};
        for (int k = row(c); k < row(c + 1); ++k)
          for (int d = 0; d < 3; ++d) s[d] += value(mirror(k), d) * p(col(k));
        const double sn = s[0] * normal(c, 0) + s[1] * normal(c, 1) + s[2] * normal(c, 2);
        for (int d = 0; d < 3; ++d) u(c, d) = w(c) * (s[d] - sn * normal(c, d));
      });
}

/// out_i = (B u)_i.
template <class ExecSpace, class MemSpace>
void volume_gradient_matrix_apply(const ExecSpace& exec, const VolumeGradientMatrix<MemSpace>& B,
                                  const Kokkos::View<double* [3], MemSpace>& u,
                                  const Kokkos::View<double*, MemSpace>& out) {
  const auto row = B.row;
  const auto col = B.col;
  const auto value = B.value;
  Kokkos::parallel_for(
      "amphora::solid::volume_gradient_matrix_apply",
      RangePolicy<ExecSpace>(exec, 0, int(out.extent(0))), KOKKOS_LAMBDA(const int i) {
        double s = 0.0;
        for (int k = row(i); k < row(i + 1); ++k)
          for (int d = 0; d < 3; ++d) s += value(k, d) * u(col(k), d);
        out(i) = s;
      });
}

/// D_i = (B W B^T)_ii = sum_c B_ic . W_c B_ic.
template <class ExecSpace, class MemSpace>
void volume_operator_diagonal(const ExecSpace& exec, const VolumeGradientMatrix<MemSpace>& B,
                              const Kokkos::View<double*, MemSpace>& w,
                              const Kokkos::View<double* [3], MemSpace>& normal,
                              const Kokkos::View<double*, MemSpace>& D) {
  const auto row = B.row;
  const auto col = B.col;
  const auto value = B.value;
  Kokkos::parallel_for(
      "amphora::solid::volume_operator_diagonal", RangePolicy<ExecSpace>(exec, 0, int(D.extent(0))),
      KOKKOS_LAMBDA(const int i) {
        double s = 0.0;
        for (int k = row(i); k < row(i + 1); ++k) {
          const int c = col(k);
          double bb = 0.0, bn = 0.0;
          for (int d = 0; d < 3; ++d)
            bb += value(k, d) * value(k, d), bn += value(k, d) * normal(c, d);
          s += w(c) * (bb - bn * bn);
        }
        D(i) = s;
      });
}

}  // namespace amphora::kernels::solid
