#pragma once
// The MAC Poisson stencil as an assembled CSR matrix over its fluid cells only (compact
// numbering, x fastest), for the back ends that need a matrix: hypre, MIC(0), the coarsest
// multigrid level. Host only (setup).
#include <vector>

#include "kernels/mac/poisson_stencil.hpp"
#include "solvers/csr_matrix.hpp"

namespace amphora::solvers::mac {

/// Fluid cells in compact order: cell[u] is the padded index of unknown u, unknown[c] the
/// unknown of padded index c (-1 if c is not a fluid cell).
struct CompactNumbering {
  std::vector<int> cell;
  std::vector<int> unknown;
  long size() const { return static_cast<long>(cell.size()); }
};

/// Assembles from host arrays on the padded lattice of g.
CsrMatrix stencil_to_csr(const kernels::mac::MacGrid& g, const double* diag, const float* cx,
                         const float* cy, const float* cz, CompactNumbering& numbering);

template <class MemSpace>
CsrMatrix stencil_to_csr(const kernels::mac::PoissonStencil<MemSpace>& A,
                         CompactNumbering& numbering) {
  const auto d = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), A.diag);
  const auto x = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), A.cx);
  const auto y = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), A.cy);
  const auto z = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), A.cz);
  return stencil_to_csr(A.grid, d.data(), x.data(), y.data(), z.data(), numbering);
}

}  // namespace amphora::solvers::mac
