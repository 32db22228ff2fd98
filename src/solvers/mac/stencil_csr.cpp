#include "solvers/mac/stencil_csr.hpp"

namespace amphora::solvers::mac {

CsrMatrix stencil_to_csr(const kernels::mac::MacGrid& g, const double* diag, const float* cx,
                         const float* cy, const float* cz, CompactNumbering& numbering) {
  numbering.cell.clear();
  numbering.unknown.assign(static_cast<std::size_t>(g.padded_size()), -1);
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) {
        const int c = g.index(i, j, k);
        if (diag[c] > 0.0) {
          numbering.unknown[c] = static_cast<int>(numbering.cell.size());
          numbering.cell.push_back(c);
        }
      }
  const int sy = g.stride_y(), sz = g.stride_z();
  CsrMatrix A;
  A.n = numbering.size();
  A.row_ptr.reserve(A.n + 1);
  A.row_ptr.push_back(0);
  A.cols.reserve(7 * A.n);
  A.values.reserve(7 * A.n);
  for (const int c : numbering.cell) {
    // Columns in increasing order: -z, -y, -x, centre, +x, +y, +z.
    const int nbr[7] = {c - sz, c - sy, c - 1, c, c + 1, c + sy, c + sz};
    const double cond[7] = {cz[c - sz], cy[c - sy], cx[c - 1], 0.0, cx[c], cy[c], cz[c]};
    for (int e = 0; e < 7; ++e) {
      if (e == 3) {
        A.cols.push_back(numbering.unknown[c]);
        A.values.push_back(diag[c]);
      } else if (cond[e] != 0.0) {
        A.cols.push_back(numbering.unknown[nbr[e]]);
        A.values.push_back(-cond[e]);
      }
    }
    A.row_ptr.push_back(static_cast<long>(A.cols.size()));
  }
  return A;
}

}  // namespace amphora::solvers::mac
