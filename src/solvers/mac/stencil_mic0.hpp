#pragma once
// MIC(0) on the 7-point MAC stencil itself (Bridson, Fluid Simulation for Computer Graphics,
// 2nd ed., fig. 5.3/5.4, in 3D): the same factorisation as ModifiedIncompleteCholesky on the
// assembled matrix, with the neighbours found by lattice offsets instead of column indices, as
// fluid codes implement it. Host, sequential (lexicographic triangular solves).
#include <vector>

#include "kernels/mac/poisson_stencil.hpp"

namespace amphora::solvers::mac {

class StencilMic0 {
 public:
  using HostStencil = kernels::mac::PoissonStencil<kernels::HostMemSpace>;

  explicit StencilMic0(const HostStencil& A, double tau = 0.97, double sigma = 0.25) : A_(A) {
    const kernels::mac::MacGrid& g = A.grid;
    inverse_e_.assign(static_cast<std::size_t>(g.padded_size()), 0.0);
    std::vector<double> e(inverse_e_.size(), 0.0);
    const int sy = g.stride_y(), sz = g.stride_z();
    const auto& d = A.diag;
    const auto &cx = A.cx, &cy = A.cy, &cz = A.cz;
    // sum of row m's strictly upper entries: -(cx + cy + cz)(m)
    auto upper = [&](int m) { return -(double(cx(m)) + double(cy(m)) + double(cz(m))); };
    for (int k = 0; k < g.nz; ++k)
      for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i) {
          const int c = g.index(i, j, k);
          if (d(c) == 0.0) continue;
          double ec = d(c);
          const int nbr[3] = {c - 1, c - sy, c - sz};
          const double a[3] = {-double(cx(c - 1)), -double(cy(c - sy)), -double(cz(c - sz))};
          for (int m = 0; m < 3; ++m)
            if (a[m] != 0.0) ec -= a[m] / e[nbr[m]] * (a[m] + tau * (upper(nbr[m]) - a[m]));
          if (ec < sigma * d(c)) ec = d(c);
          e[c] = ec;
          inverse_e_[c] = 1.0 / ec;
        }
  }

  /// z = M^-1 r on the padded lattice (z zero on non-fluid cells).
  void apply(const double* r, double* z) const {
    const kernels::mac::MacGrid& g = A_.grid;
    const int sy = g.stride_y(), sz = g.stride_z();
    const float *cx = A_.cx.data(), *cy = A_.cy.data(), *cz = A_.cz.data();
    const double* inv = inverse_e_.data();
    const int first = g.first_plane_index(), end = g.end_plane_index();
    for (int c = 0; c < first; ++c) z[c] = 0.0;
    for (int c = end; c < end + first; ++c) z[c] = 0.0;
    // (E + L) y = r: the lower neighbours enter with -a = +conductance
    for (int c = first; c < end; ++c)
      z[c] = inv[c] * (r[c] + double(cx[c - 1]) * z[c - 1] + double(cy[c - sy]) * z[c - sy] +
                       double(cz[c - sz]) * z[c - sz]);
    // (E + L^T) z = E y
    for (int c = end - 1; c >= first; --c)
      z[c] += inv[c] *
              (double(cx[c]) * z[c + 1] + double(cy[c]) * z[c + sy] + double(cz[c]) * z[c + sz]);
  }
  template <class ExecSpace, class R, class Z>
  void apply(const ExecSpace&, const R& r, const Z& z) const {
    apply(r.data(), z.data());
  }

 private:
  HostStencil A_;
  std::vector<double> inverse_e_;
};

}  // namespace amphora::solvers::mac
