#pragma once
// The quadrature-centred solid fraction of unresolved CFD-DEM (QCM; Geitani, Golshan & Blais,
// Chem. Eng. Sci. 2023, as Lethe computes it): at each quadrature point q of the flow's cells a
// reference sphere of radius R, and the solid fraction there is the volume the particles share
// with it over its volume. Each particle's shares are scaled so that their integral is its own
// volume: the load (1 - solid, v) then holds the particles' volume exactly, and it moves
// continuously with the particles (the lens volume of two spheres is continuous in their
// distance). 3D, Cartesian cells, Gauss points (k + 1 per direction).
#include <array>
#include <stdexcept>
#include <string>
#include <vector>

#include <Kokkos_Core.hpp>

#include "kernels/grow_view.hpp"
#include "kernels/kokkos_compat.hpp"
#include "kernels/spaces.hpp"
#include "kernels/sumfac/qk_point_basis.hpp"
#include "kernels/sumfac/quadrature_1d.hpp"

namespace amphora::coupling::cfd_dem {

/// Volume shared by spheres of radii r and R whose centres lie d apart (the lens of two caps).
KOKKOS_INLINE_FUNCTION double sphere_overlap(double r, double R, double d) {
  if (d >= r + R) return 0.0;
  const double small = r < R ? r : R, large = r < R ? R : r;
  if (d <= large - small) return 4.0 / 3.0 * M_PI * small * small * small;
  const double s = r + R - d;
  return M_PI * s * s * (d * d + 2.0 * d * (r + R) - 3.0 * (r - R) * (r - R)) / (12.0 * d);
}

template <class ExecSpace>
class QuadratureCentred {
 public:
  using Mem = typename ExecSpace::memory_space;
  using Vector = Kokkos::View<double*, Mem>;
  using Points = Kokkos::View<double* [3], Kokkos::LayoutRight, Mem>;
  static constexpr int max_q = kernels::sumfac::max_point_basis_degree + 1;

  /// The cells and numbering of `basis` (3D); radius R <= 0: the sphere of a cell's volume.
  QuadratureCentred(const kernels::sumfac::QkPointBasis<3>& basis, double radius)
      : QuadratureCentred(basis, basis, 0, radius) {}
  /// On a slab of cells [first_cell, first_cell + slab's cells) along z of the box `whole`
  /// (a DistributedQkSpace's): the shares are taken over the whole box's cells, so a particle's
  /// scale is the same on every rank that sees it, and only the slab's cells are loaded, in
  /// `slab`'s numbering.
  QuadratureCentred(const kernels::sumfac::QkPointBasis<3>& whole,
                    const kernels::sumfac::QkPointBasis<3>& slab, int first_cell, double radius)
      : b_(whole), slab_(slab), first_(first_cell) {
    const int k = whole.lattice.degree, nq = k + 1;
    const auto g = kernels::sumfac::gauss(nq);
    const auto phi = kernels::sumfac::lagrange_values(
        std::vector<double>(whole.nodes, whole.nodes + k + 1), g.points);
    for (int q = 0; q < nq; ++q) {
      points_[q] = g.points[q];
      weights_[q] = g.weights[q];
      for (int a = 0; a <= k; ++a) phi_[q * max_q + a] = phi[q * (k + 1) + a];
    }
    const double cell = whole.h[0] * whole.h[1] * whole.h[2];
    radius_ = radius > 0 ? radius : std::cbrt(3.0 * cell / (4.0 * M_PI));
    solid_ = Vector("amphora::cfd_dem::qcm_solid", slab_cells() * nq * nq * nq);
  }

  double radius() const { return radius_; }

  /// b -= (solid, phi_j) over the slab's cells for the particles in rows [0, rows) (centres x,
  /// radii r): the owned ones [0, owned) and ghosts (another rank's particles near the slab).
  /// A ghost placed outside the box along a direction with `own_images` set is an image of a
  /// particle already counted and is skipped. `placed` holds the positions that test reads:
  /// where the rows were when the ghosts were made (a DEM's positions at its last list build;
  /// empty: x). The current positions cannot tell: between rebuilds an owned particle drifts
  /// past a periodic face and its image into the box. Returns the owned particles that share
  /// no volume with any reference sphere (R too small for the cells).
  int load(const ExecSpace& exec, const Points& x, const Vector& r, int owned, int rows,
           const std::array<bool, 3>& own_images, const Points& placed, const Vector& b) const {
    Kokkos::deep_copy(exec, solid_, 0.0);
    if (scale_.extent(0) < static_cast<std::size_t>(rows))  // kept: no allocation in a step
      kernels::grow_uninitialized(scale_, rows + rows / 8, "amphora::cfd_dem::qcm_scale");
    const Vector scale = scale_;
    double lo[3], hi[3];
    for (int d = 0; d < 3; ++d) {
      const bool skip = own_images[d] && b_.lattice.periodic[d];
      lo[d] = skip ? b_.lower[d] : -1e300;
      hi[d] = skip ? b_.lower[d] + b_.lattice.cells[d] * b_.h[d] : 1e300;
    }
    const Points at = placed.extent(0) > 0 ? placed : x;
    int unseen = 0;
    Kokkos::parallel_reduce(
        "amphora::cfd_dem::qcm_shares", kernels::RangePolicy<ExecSpace>(exec, 0, rows),
        KOKKOS_CLASS_LAMBDA(int p, int& count) {
          bool image = false;
          for (int d = 0; d < 3; ++d) image = image || at(p, d) < lo[d] || at(p, d) >= hi[d];
          double s = 0.0;
          if (p < owned || !image) visit(x, r, p, [&](long, double share) { s += share; });
          const double volume = 4.0 / 3.0 * M_PI * r(p) * r(p) * r(p);
          scale(p) = s > 0 ? volume / s : 0.0;
          count += s > 0 || p >= owned ? 0 : 1;
        },
        unseen);
    const auto solid = solid_;
    Kokkos::parallel_for(
        "amphora::cfd_dem::qcm_solid", kernels::RangePolicy<ExecSpace>(exec, 0, rows),
        KOKKOS_CLASS_LAMBDA(int p) {
          const double c = scale(p);
          if (c == 0.0) return;
          visit(x, r, p, [&](long point, double share) {
            if (point >= 0) Kokkos::atomic_add(&solid(point), c * share / weight(point));
          });
        });
    integrate(exec, b);
    return unseen;
  }

  /// The solid fraction at quadrature point `point` (slab cell * nq^3 + local), after load().
  const Vector& solid_fraction() const { return solid_; }

  /// Calls f(point, W_q V(p cap q) / V_R) for every quadrature point of the box whose
  /// reference sphere particle p meets (W_q the point's weight times the cell's volume), with
  /// point the slab's index of it or -1 where its cell lies off the slab. Periodic directions
  /// wrap; the distance is taken to the unwrapped point.
  template <class F>
  KOKKOS_INLINE_FUNCTION void visit(const Points& x, const Vector& r, int p, const F& f) const {
    const int nq = b_.lattice.degree + 1;
    const double reach = radius_ + r(p);
    const double vr = 4.0 / 3.0 * M_PI * radius_ * radius_ * radius_;
    int lo[3], hi[3];
    for (int d = 0; d < 3; ++d) {
      lo[d] = int(kernels::math::floor((x(p, d) - reach - b_.lower[d]) / b_.h[d]));
      hi[d] = int(kernels::math::floor((x(p, d) + reach - b_.lower[d]) / b_.h[d]));
      if (!b_.lattice.periodic[d]) {
        lo[d] = lo[d] < 0 ? 0 : lo[d];
        hi[d] = hi[d] >= b_.lattice.cells[d] ? b_.lattice.cells[d] - 1 : hi[d];
      }
    }
    const int slab_z = slab_.lattice.cells[2];
    for (int c2 = lo[2]; c2 <= hi[2]; ++c2)
      for (int c1 = lo[1]; c1 <= hi[1]; ++c1)
        for (int c0 = lo[0]; c0 <= hi[0]; ++c0) {
          const int c[3] = {c0, c1, c2};
          int w[3];
          for (int d = 0; d < 3; ++d) {
            const int n = b_.lattice.cells[d];
            w[d] = ((c[d] % n) + n) % n;
          }
          const int z = w[2] - first_;
          const long cell = z >= 0 && z < slab_z ? w[0] + long(b_.lattice.cells[0]) *
                                                              (w[1] + long(b_.lattice.cells[1]) * z)
                                                 : -1;
          for (int q = 0; q < nq * nq * nq; ++q) {
            const int qd[3] = {q % nq, (q / nq) % nq, q / (nq * nq)};
            double d2 = 0.0;
            for (int d = 0; d < 3; ++d) {
              const double xq = b_.lower[d] + (c[d] + points_[qd[d]]) * b_.h[d];
              d2 += (x(p, d) - xq) * (x(p, d) - xq);
            }
            const double v = sphere_overlap(r(p), radius_, kernels::math::sqrt(d2));
            if (v > 0) f(cell < 0 ? -1L : cell * nq * nq * nq + q, weight(q) * v / vr);
          }
        }
  }

  /// W_q: the quadrature weight of local point q (or of a global point: its local index) times
  /// the cell's volume.
  KOKKOS_INLINE_FUNCTION double weight(long point) const {
    const int nq = b_.lattice.degree + 1;
    const int q = int(point % (nq * nq * nq));
    return weights_[q % nq] * weights_[(q / nq) % nq] * weights_[q / (nq * nq)] * b_.h[0] *
           b_.h[1] * b_.h[2];
  }

  /// b_j -= sum_q W_q solid_q phi_j(x_q), cell by cell.
  void integrate(const ExecSpace& exec, const Vector& b) const {
    const int nq = b_.lattice.degree + 1, k1 = nq;
    const long n_cells = slab_cells();
    const auto solid = solid_;
    Kokkos::parallel_for(
        "amphora::cfd_dem::qcm_load", kernels::RangePolicy<ExecSpace>(exec, 0, int(n_cells)),
        KOKKOS_CLASS_LAMBDA(int cell) {
          int c[3], rest = cell;
          for (int d = 0; d < 3; ++d) {
            c[d] = rest % slab_.lattice.cells[d];
            rest /= slab_.lattice.cells[d];
          }
          const long first = long(cell) * nq * nq * nq;
          for (int i = 0; i < k1 * k1 * k1; ++i) {
            const int a[3] = {i % k1, (i / k1) % k1, i / (k1 * k1)};
            double s = 0.0;
            for (int q = 0; q < nq * nq * nq; ++q) {
              const double w = solid(first + q);
              if (w == 0.0) continue;
              const int qd[3] = {q % nq, (q / nq) % nq, q / (nq * nq)};
              s += weight(q) * w * phi_[qd[0] * max_q + a[0]] * phi_[qd[1] * max_q + a[1]] *
                   phi_[qd[2] * max_q + a[2]];
            }
            if (s != 0.0) Kokkos::atomic_add(&b(slab_.dof(c, a)), -s);
          }
        });
  }

 private:
  long slab_cells() const {
    return long(slab_.lattice.cells[0]) * slab_.lattice.cells[1] * slab_.lattice.cells[2];
  }

  kernels::sumfac::QkPointBasis<3> b_;     // the whole box: the shares' geometry
  kernels::sumfac::QkPointBasis<3> slab_;  // this rank's slab: its cells and DoFs
  int first_ = 0;                          // the slab's first cell along z
  double points_[max_q] = {}, weights_[max_q] = {};
  double phi_[max_q * max_q] = {};  // phi_[q * max_q + a]: 1D basis a at Gauss point q
  double radius_ = 0.0;
  mutable Vector scale_;  // each row's volume over its shares' sum (load's scratch)
  Vector solid_;
};

}  // namespace amphora::coupling::cfd_dem
