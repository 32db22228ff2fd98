#pragma once
// Transfers between a MAC cell grid and the grid with cells twice as wide, for geometric
// multigrid on the pressure (the choices of McAdams, Sifakis & Teran 2010, sec. 4):
// - prolongation P: cell-centred trilinear interpolation (weights 3/4, 1/4 per direction);
//   beyond a box face the coarse value is copied from the nearest interior cell (zero normal
//   derivative), and non-fluid cells of either grid take and give nothing;
// - restriction R = P^T exactly (so a symmetric smoother gives a symmetric V-cycle, as CG needs);
// - coarse matrix by re-discretisation in conductance form: a coarse face conducts half the sum
//   of its four fine faces, a coarse cell keeps half the free-surface terms of its eight children.
//   For full faces that is the rediscretised Laplacian at 2h (c = 2 in fine units: area 4h^2 over
//   distance 2h), consistent with R = P^T, whose weights sum to 8.
#include "kernels/mac/poisson_stencil.hpp"

namespace amphora::kernels::mac {

namespace detail {
/// Weight of fine index f (in [-1, 2n_c]) towards coarse index I under P, with the box clamp.
KOKKOS_INLINE_FUNCTION double transfer_weight_1d(int f, int I, int n_c) {
  if (f < 0 || f >= 2 * n_c) return 0.0;
  const int parent = f >> 1;
  const int other = (f & 1) ? parent + 1 : parent - 1;  // the second-nearest coarse cell
  const int other_clamped = other < 0 ? 0 : (other >= n_c ? n_c - 1 : other);
  return (parent == I ? 0.75 : 0.0) + (other_clamped == I ? 0.25 : 0.0);
}
}  // namespace detail

/// coarse = R fine, on coarse fluid cells (zero elsewhere).
template <class ExecSpace, class MemSpace, class FineView, class CoarseView>
void restrict_to_coarse(const ExecSpace& exec, const PoissonStencil<MemSpace>& fine_A,
                        const PoissonStencil<MemSpace>& coarse_A, const FineView& fine, const CoarseView& coarse) {
  const mesh::MacGrid gf = fine_A.grid, gc = coarse_A.grid;
  const auto active = coarse_A.inverse_diag;
  Kokkos::parallel_for(
      "amphora::mac::restrict_to_coarse",
      Kokkos::MDRangePolicy<ExecSpace, Kokkos::Rank<3>>(exec, {0, 0, 0}, {gc.nz, gc.ny, gc.nx}),
      KOKKOS_LAMBDA(int K, int J, int I) {
        const int C = gc.index(I, J, K);
        if (active(C) == 0.0) {
          coarse(C) = 0.0;
          return;
        }
        double wx[4], wy[4], wz[4];
        for (int a = 0; a < 4; ++a) {
          wx[a] = detail::transfer_weight_1d(2 * I - 1 + a, I, gc.nx);
          wy[a] = detail::transfer_weight_1d(2 * J - 1 + a, J, gc.ny);
          wz[a] = detail::transfer_weight_1d(2 * K - 1 + a, K, gc.nz);
        }
        // Fine indices 2I-1 .. 2I+2 exist in the padded lattice (the ghost layer holds zeros).
        double sum = 0.0;
        for (int c = 0; c < 4; ++c) {
          for (int b = 0; b < 4; ++b) {
            const int row = gf.index(2 * I - 1, 2 * J - 1 + b, 2 * K - 1 + c);
            double s = 0.0;
            for (int a = 0; a < 4; ++a) s += wx[a] * fine(row + a);
            sum += wz[c] * wy[b] * s;
          }
        }
        coarse(C) = sum;
      });
}

/// fine += P coarse, on fine fluid cells.
template <class ExecSpace, class MemSpace, class CoarseView, class FineView>
void prolongate_add(const ExecSpace& exec, const PoissonStencil<MemSpace>& coarse_A,
                    const PoissonStencil<MemSpace>& fine_A, const CoarseView& coarse, const FineView& fine) {
  const mesh::MacGrid gf = fine_A.grid, gc = coarse_A.grid;
  const auto active = fine_A.inverse_diag;
  Kokkos::parallel_for(
      "amphora::mac::prolongate_add",
      Kokkos::MDRangePolicy<ExecSpace, Kokkos::Rank<3>>(exec, {0, 0, 0}, {gf.nz, gf.ny, gf.nx}),
      KOKKOS_LAMBDA(int k, int j, int i) {
        const int c = gf.index(i, j, k);
        if (active(c) == 0.0) return;
        const int I0 = i >> 1, J0 = j >> 1, K0 = k >> 1;
        const int I1 = math::clamp((i & 1) ? I0 + 1 : I0 - 1, 0, gc.nx - 1);
        const int J1 = math::clamp((j & 1) ? J0 + 1 : J0 - 1, 0, gc.ny - 1);
        const int K1 = math::clamp((k & 1) ? K0 + 1 : K0 - 1, 0, gc.nz - 1);
        const int Is[2] = {I0, I1}, Js[2] = {J0, J1}, Ks[2] = {K0, K1};
        const double w[2] = {0.75, 0.25};
        double sum = 0.0;
        for (int c3 = 0; c3 < 2; ++c3)
          for (int b = 0; b < 2; ++b)
            for (int a = 0; a < 2; ++a) sum += w[a] * w[b] * w[c3] * coarse(gc.index(Is[a], Js[b], Ks[c3]));
        fine(c) += sum;
      });
}

/// The coarse matrix of a fine one (grid dimensions even): see the header comment.
template <class ExecSpace, class MemSpace>
PoissonStencil<MemSpace> coarsen_stencil(const ExecSpace& exec, const PoissonStencil<MemSpace>& fine_A) {
  const mesh::MacGrid gf = fine_A.grid, gc = gf.coarsened();
  PoissonStencil<MemSpace> coarse_A(gc);
  const auto fd = fine_A.diag, fcx = fine_A.cx, fcy = fine_A.cy, fcz = fine_A.cz;
  const auto cd = coarse_A.diag, cinv = coarse_A.inverse_diag, ccx = coarse_A.cx, ccy = coarse_A.cy, ccz = coarse_A.cz;
  const int sy = gf.stride_y(), sz = gf.stride_z();
  // Pass 1: conductances of the + faces of every coarse cell.
  Kokkos::parallel_for(
      "amphora::mac::coarsen_stencil::faces",
      Kokkos::MDRangePolicy<ExecSpace, Kokkos::Rank<3>>(exec, {0, 0, 0}, {gc.nz, gc.ny, gc.nx}),
      KOKKOS_LAMBDA(int K, int J, int I) {
        float sx = 0, sy_ = 0, sz_ = 0;
        for (int b = 0; b < 2; ++b)
          for (int a = 0; a < 2; ++a) {
            sx += fcx(gf.index(2 * I + 1, 2 * J + a, 2 * K + b));
            sy_ += fcy(gf.index(2 * I + a, 2 * J + 1, 2 * K + b));
            sz_ += fcz(gf.index(2 * I + a, 2 * J + b, 2 * K + 1));
          }
        const int c = gc.index(I, J, K);
        ccx(c) = 0.5f * sx;
        ccy(c) = 0.5f * sy_;
        ccz(c) = 0.5f * sz_;
      });
  // Pass 2: diagonal = half the children's free-surface terms + the coarse conductances.
  const int csy = gc.stride_y(), csz = gc.stride_z();
  Kokkos::parallel_for(
      "amphora::mac::coarsen_stencil::diagonal",
      Kokkos::MDRangePolicy<ExecSpace, Kokkos::Rank<3>>(exec, {0, 0, 0}, {gc.nz, gc.ny, gc.nx}),
      KOKKOS_LAMBDA(int K, int J, int I) {
        double dirichlet = 0.0;
        bool any_fluid = false;
        for (int c3 = 0; c3 < 2; ++c3)
          for (int b = 0; b < 2; ++b)
            for (int a = 0; a < 2; ++a) {
              const int f = gf.index(2 * I + a, 2 * J + b, 2 * K + c3);
              if (fd(f) == 0.0) continue;
              any_fluid = true;
              dirichlet += fd(f) - (double(fcx(f - 1)) + double(fcx(f)) + double(fcy(f - sy)) + double(fcy(f)) +
                                    double(fcz(f - sz)) + double(fcz(f)));
            }
        const int c = gc.index(I, J, K);
        const double diag = any_fluid ? 0.5 * dirichlet + (double(ccx(c - 1)) + double(ccx(c)) + double(ccy(c - csy)) +
                                                           double(ccy(c)) + double(ccz(c - csz)) + double(ccz(c)))
                                      : 0.0;
        cd(c) = diag;
        cinv(c) = diag > 0.0 ? 1.0 / diag : 0.0;
      });
  return coarse_A;
}

}  // namespace amphora::kernels::mac
