#pragma once
// Interpolation between the Q1 DoF lattices of one box with different cell counts: the
// non-nested h-transfer of a multigrid that coarsens n cells to ceil(n / 2), odd counts too.
// Q1 interpolates direction by direction (each fine node lies in one coarse cell and takes its
// two end nodes' values with linear weights), so prolongation is P_x (x) P_y (x) P_z and
// restriction its transpose; both are gathers (no atomics, the same bits on every backend).
// Masked weights drop Dirichlet nodes: a DoF is constrained when its index is constrained in
// some direction, so the product of masked 1D weights is the transfer between the free DoFs.
#include <string>
#include <vector>

#include <Kokkos_Core.hpp>

#include "kernels/spaces.hpp"
#include "kernels/sumfac/qk_lattice.hpp"

namespace amphora::kernels::sumfac {

/// The 1D factors of Q1 interpolation from `coarse` to `fine` (both degree 1, the same box).
/// Direction d's fine DoF i reads coarse DoFs lo(at) and lo(at) + 1 (wrapped: hi(at)), at =
/// fine_first[d] + i; coarse DoF a is read by the entries first(c) .. first(c + 1) - 1 of
/// (fine, weight), c = coarse_first[d] + a.
template <int dim, class Mem>
struct LatticeInterpolation {
  QkLattice<dim> coarse, fine;
  int fine_first[3] = {0, 0, 0}, coarse_first[3] = {0, 0, 0};
  Kokkos::View<int*, Mem> lo, hi, first, by_coarse;
  /// [2 * entry + masked]: the weights of lo and hi, and of each transposed entry.
  Kokkos::View<double*, Mem> w_lo, w_hi, w_by_coarse;

  LatticeInterpolation() = default;
  LatticeInterpolation(const QkLattice<dim>& c, const QkLattice<dim>& f) : coarse(c), fine(f) {
    std::vector<int> l, h, fst{0}, by;
    std::vector<double> wl, wh, wb;
    for (int d = 0; d < dim; ++d) {
      fine_first[d] = static_cast<int>(l.size());
      coarse_first[d] = static_cast<int>(fst.size()) - 1;
      const int nf = f.cells[d], nc = c.cells[d];
      std::vector<std::vector<std::pair<int, double>>> rows(c.dofs[d]);
      std::vector<std::vector<double>> masked(c.dofs[d]);
      for (int i = 0; i < f.dofs[d]; ++i) {
        const long num = static_cast<long>(i) * nc;
        int a = static_cast<int>(num / nf);
        double t = static_cast<double>(num % nf) / nf;
        if (a == nc) a = nc - 1, t = 1.0;  // the last node of a bounded direction
        const int ends[2] = {c.dof_1d(d, a), c.dof_1d(d, a + 1)};
        const double w[2] = {1.0 - t, t};
        l.push_back(ends[0]), h.push_back(ends[1]);
        for (int e = 0; e < 2; ++e) {
          const bool drop = f.constrained_1d(d, i) || c.constrained_1d(d, e == 0 ? a : a + 1);
          (e == 0 ? wl : wh).push_back(w[e]);
          (e == 0 ? wl : wh).push_back(drop ? 0.0 : w[e]);
          if (w[e] != 0.0)
            rows[ends[e]].push_back({i, w[e]}), masked[ends[e]].push_back(drop ? 0.0 : w[e]);
        }
      }
      for (int a = 0; a < c.dofs[d]; ++a) {
        for (std::size_t e = 0; e < rows[a].size(); ++e) {
          by.push_back(rows[a][e].first);
          wb.push_back(rows[a][e].second), wb.push_back(masked[a][e]);
        }
        fst.push_back(static_cast<int>(by.size()));
      }
    }
    lo = to_view<int>("amphora::lattice_interpolation::lo", l);
    hi = to_view<int>("amphora::lattice_interpolation::hi", h);
    first = to_view<int>("amphora::lattice_interpolation::first", fst);
    by_coarse = to_view<int>("amphora::lattice_interpolation::by_coarse", by);
    w_lo = to_view<double>("amphora::lattice_interpolation::w_lo", wl);
    w_hi = to_view<double>("amphora::lattice_interpolation::w_hi", wh);
    w_by_coarse = to_view<double>("amphora::lattice_interpolation::w_by_coarse", wb);
  }

  /// xf = P xc (masked: between the free DoFs, constrained fine DoFs 0).
  template <class ExecSpace>
  void prolongate(const ExecSpace& exec, const double* xc, double* xf, bool masked) const {
    const LatticeInterpolation L = *this;
    const int m = masked ? 1 : 0;
    Kokkos::parallel_for(
        "amphora::LatticeInterpolation::prolongate",
        RangePolicy<ExecSpace>(exec, 0, static_cast<int>(fine.n_dofs())), KOKKOS_LAMBDA(int idx) {
          int at[3] = {0, 0, 0};
          for (int d = 0, r = idx; d < dim; ++d)
            at[d] = L.fine_first[d] + r % L.fine.dofs[d], r /= L.fine.dofs[d];
          double s = 0.0;
          for (int corner = 0; corner < (1 << dim); ++corner) {
            double w = 1.0;
            long c = 0;
            for (int d = dim - 1; d >= 0; --d) {
              const bool up = corner >> d & 1;
              w *= up ? L.w_hi(2 * at[d] + m) : L.w_lo(2 * at[d] + m);
              c = c * L.coarse.dofs[d] + (up ? L.hi(at[d]) : L.lo(at[d]));
            }
            if (w != 0.0) s += w * xc[c];
          }
          xf[idx] = s;
        });
  }

  /// xc = P^T xf (masked: between the free DoFs, constrained coarse DoFs 0).
  template <class ExecSpace>
  void restrict_to_coarse(const ExecSpace& exec, const double* xf, double* xc, bool masked) const {
    const LatticeInterpolation L = *this;
    const int m = masked ? 1 : 0;
    Kokkos::parallel_for(
        "amphora::LatticeInterpolation::restrict",
        RangePolicy<ExecSpace>(exec, 0, static_cast<int>(coarse.n_dofs())), KOKKOS_LAMBDA(int idx) {
          int row[3] = {0, 0, 0};
          for (int d = 0, r = idx; d < dim; ++d)
            row[d] = L.coarse_first[d] + r % L.coarse.dofs[d], r /= L.coarse.dofs[d];
          double s = 0.0;
          const int z0 = dim > 2 ? L.first(row[2]) : 0, z1 = dim > 2 ? L.first(row[2] + 1) : 1;
          for (int ez = z0; ez < z1; ++ez) {
            const double wz = dim > 2 ? L.w_by_coarse(2 * ez + m) : 1.0;
            const long kz = dim > 2 ? L.by_coarse(ez) : 0;
            for (int ey = L.first(row[1]); ey < L.first(row[1] + 1); ++ey) {
              const double wyz = wz * L.w_by_coarse(2 * ey + m);
              const long ky = kz * L.fine.dofs[1] + L.by_coarse(ey);
              for (int ex = L.first(row[0]); ex < L.first(row[0] + 1); ++ex) {
                const double w = wyz * L.w_by_coarse(2 * ex + m);
                if (w != 0.0) s += w * xf[ky * L.fine.dofs[0] + L.by_coarse(ex)];
              }
            }
          }
          xc[idx] = s;
        });
  }

 private:
  template <class V>
  static Kokkos::View<V*, Mem> to_view(const char* label, const std::vector<V>& v) {
    Kokkos::View<V*, Mem> out(std::string(label), v.size());
    Kokkos::deep_copy(out, Kokkos::View<const V*, Kokkos::HostSpace>(v.data(), v.size()));
    return out;
  }
};

}  // namespace amphora::kernels::sumfac
