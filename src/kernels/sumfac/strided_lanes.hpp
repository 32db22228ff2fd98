#pragma once
// One row of nodes of a cell batch, between the DoF vector and the batch's lanes: the W cells
// of a batch are consecutive along x, so lane l's node i of a row sits at p[l k + i]
// (k = the degree; node k of lane l is node 0 of lane l + 1). With k known at compile time
// the compiler turns the strided reads into whole-vector loads and permutes; the adds go
// through a contiguous buffer, so they are whole vectors too instead of a chain of scalar
// read-modify-writes that may alias one another.
#include "kernels/sumfac/simd.hpp"

namespace amphora::sumfac {

/// u[i][l] = p[l k + i] for i <= k and every lane l.
template <int k, int W>
KOKKOS_FORCEINLINE_FUNCTION void read_strided_row(const double* p, Simd<W>* u) {
  for (int l = 0; l < W; ++l)
    for (int i = 0; i <= k; ++i) u[i][l] = p[l * k + i];
}

/// p[l k + i] += u[i][l] for i <= k and every lane l. Lane l's node k is lane l+1's node 0:
/// folding it in first leaves W k disjoint, contiguous entries and the row's last node.
template <int k, int W>
KOKKOS_FORCEINLINE_FUNCTION void add_strided_row(double* p, const Simd<W>* u) {
  alignas(64) double row[W * k];
  for (int l = 0; l < W; ++l) {
    row[l * k] = u[0][l] + (l > 0 ? u[k][l - 1] : 0.0);
    for (int i = 1; i < k; ++i) row[l * k + i] = u[i][l];
  }
  for (int m = 0; m < W * k; ++m) p[m] += row[m];
  p[W * k] += u[k][W - 1];
}

}  // namespace amphora::sumfac
