#pragma once
// Trilinear interpolation on the MAC lattice (Bridson, Fluid Simulation for Computer Graphics,
// 2nd ed., sec. 3.3): a cell-centred field at (i + 1/2) h, each velocity component at the
// centres of the faces normal to it. Sample positions are clamped to the samples inside the box
// (no values are invented beyond them).
#include "kernels/spaces.hpp"
#include "kernels/mac/mac_grid.hpp"

namespace amphora::kernels::mac {

/// Which lattice a field lives on: cell centres, or faces normal to x, y or z.
enum class Staggering : int { centre = -1, x = 0, y = 1, z = 2 };

/// Interpolates field f (padded lattice) of staggering s at q, a position in cell widths from
/// the box's lower corner.
template <class F>
KOKKOS_FORCEINLINE_FUNCTION double interpolate_cells(const kernels::mac::MacGrid& g, const F& f,
                                                     Staggering s, const double q[3]) {
  const int n[3] = {g.nx, g.ny, g.nz};
  int base[3];
  double w[3];
  for (int d = 0; d < 3; ++d) {
    // samples of this direction sit at (m + offset) h, m = 0 .. last
    const bool on_faces = static_cast<int>(s) == d;
    const int last = on_faces ? n[d] : n[d] - 1;
    const double t = math::clamp(on_faces ? q[d] : q[d] - 0.5, 0.0, double(last));
    const int m = math::min(static_cast<int>(t), math::max(last - 1, 0));
    base[d] = m;
    w[d] = last > 0 ? t - m : 0.0;
  }
  // the eight corners from one base index (in a direction with a single sample the weight of
  // the second corner is zero and it reads a finite ghost entry)
  const int b = g.index(base[0], base[1], base[2]), sy = g.stride_y(), sz = g.stride_z();
  const double x0 = 1.0 - w[0], x1 = w[0];
  const double lo =
      (1.0 - w[1]) * (x0 * f(b) + x1 * f(b + 1)) + w[1] * (x0 * f(b + sy) + x1 * f(b + sy + 1));
  const double hi = (1.0 - w[1]) * (x0 * f(b + sz) + x1 * f(b + sz + 1)) +
                    w[1] * (x0 * f(b + sz + sy) + x1 * f(b + sz + sy + 1));
  return (1.0 - w[2]) * lo + w[2] * hi;
}

/// Position p (physical coordinates) in cell widths from the box's lower corner.
KOKKOS_INLINE_FUNCTION void to_cells(const kernels::mac::MacGrid& g, const double p[3],
                                     double q[3]) {
  const double inv_h = 1.0 / g.h;
  for (int d = 0; d < 3; ++d) q[d] = (p[d] - g.origin[d]) * inv_h;
}

/// Interpolates field f (padded lattice) of staggering s at point p (physical coordinates).
template <class F>
KOKKOS_INLINE_FUNCTION double interpolate(const kernels::mac::MacGrid& g, const F& f, Staggering s,
                                          const double p[3]) {
  double q[3];
  to_cells(g, p, q);
  return interpolate_cells(g, f, s, q);
}

/// The velocity at q (cell widths) from its three face components.
template <class U, class V, class W>
KOKKOS_FORCEINLINE_FUNCTION void velocity_at_cells(const kernels::mac::MacGrid& g, const U& u,
                                                   const V& v, const W& w, const double q[3],
                                                   double vel[3]) {
  vel[0] = interpolate_cells(g, u, Staggering::x, q);
  vel[1] = interpolate_cells(g, v, Staggering::y, q);
  vel[2] = interpolate_cells(g, w, Staggering::z, q);
}

/// The velocity at sample (i, j, k) of staggering s: velocity_at_cells at that sample's position,
/// bit for bit, from the two or four samples of each component around it (the trilinear weights
/// there are 0, 1/2 or 1, so the other loads are skipped). The first step of every trace.
template <class U, class V, class W>
KOKKOS_FORCEINLINE_FUNCTION void velocity_at_sample(const kernels::mac::MacGrid& g, Staggering s,
                                                    int i, int j, int k, const U& u, const V& v,
                                                    const W& w, double vel[3]) {
  const int idx[3] = {i, j, k}, n[3] = {g.nx, g.ny, g.nz},
            stride[3] = {1, g.stride_y(), g.stride_z()};
  const int sd = static_cast<int>(s);
  for (int e = 0; e < 3; ++e) {
    // per direction: the first sample of component e and whether the next one counts half
    int base = 0;
    bool half[3];
    for (int d = 0; d < 3; ++d) {
      int lo = idx[d];
      if (d == e) {
        half[d] = sd != d;   // between faces idx and idx + 1 unless on a face of e itself
      } else if (sd == d) {  // between cells idx - 1 and idx, clamped to the box as
                             // interpolate_cells does
        half[d] = idx[d] > 0 && idx[d] < n[d];
        lo = idx[d] == 0 ? 0 : idx[d] >= n[d] ? n[d] - 1 : idx[d] - 1;
      } else {
        half[d] = false;
      }
      base += (lo + 1) * stride[d];
    }
    const auto f = [&](int c) {
      return e == 0 ? double(u(c)) : e == 1 ? double(v(c)) : double(w(c));
    };
    // x, then y, then z, as interpolate_cells combines them
    double plane[2][2];
    for (int c = 0; c < (half[2] ? 2 : 1); ++c)
      for (int b = 0; b < (half[1] ? 2 : 1); ++b) {
        const int at = base + b * stride[1] + c * stride[2];
        plane[c][b] = half[0] ? 0.5 * f(at) + 0.5 * f(at + 1) : f(at);
      }
    const double lo_z = half[1] ? 0.5 * plane[0][0] + 0.5 * plane[0][1] : plane[0][0];
    if (!half[2]) {
      vel[e] = lo_z;
    } else {
      const double hi_z = half[1] ? 0.5 * plane[1][0] + 0.5 * plane[1][1] : plane[1][0];
      vel[e] = 0.5 * lo_z + 0.5 * hi_z;
    }
  }
}

/// The velocity at point p from its three face components.
template <class U, class V, class W>
KOKKOS_INLINE_FUNCTION void velocity_at(const kernels::mac::MacGrid& g, const U& u, const V& v,
                                        const W& w, const double p[3], double vel[3]) {
  double q[3];
  to_cells(g, p, q);
  velocity_at_cells(g, u, v, w, q, vel);
}

/// Position of sample (i, j, k) of a lattice.
KOKKOS_INLINE_FUNCTION void sample_position(const kernels::mac::MacGrid& g, Staggering s, int i,
                                            int j, int k, double p[3]) {
  const int idx[3] = {i, j, k};
  for (int d = 0; d < 3; ++d)
    p[d] = g.origin[d] + (idx[d] + (static_cast<int>(s) == d ? 0.0 : 0.5)) * g.h;
}

}  // namespace amphora::kernels::mac
