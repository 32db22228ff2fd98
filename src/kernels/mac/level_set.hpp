#pragma once
// Level-set kernels: the signed distance phi (negative in the water) at cell centres.
// Reinitialisation solves phi_tau + S(phi_0) (|grad phi| - 1) = 0 to steady state near the
// interface (Sussman, Smereka & Osher 1994, eq. 2.5) with Godunov's upwind gradient (Osher &
// Fedkiw, Level Set Methods, sec. 7.4), explicit pseudo-time, Jacobi-style (two buffers).
// Cells next to the interface take Russo & Smereka's subcell fix (JCP 163, 2000, eq. 19-20):
// they relax towards phi0 / |grad phi0|, so the zero level set stays where phi0 put it. Without
// it every pseudo-step moves the interface by O(h) in thin sheets and the water shrinks with the
// number of sub-steps.
#include "kernels/mac/mac_grid.hpp"

namespace amphora::kernels::mac {

/// The value of cell (i, j, k) after one pseudo-time step of reinitialisation, dtau = 0.5 h;
/// phi0 is the level set before reinitialisation (its sign is kept). Across a box face that is
/// not an edge (another block's side) the ghost cell is read.
template <class P0, class P>
KOKKOS_INLINE_FUNCTION double reinitialised_value(const kernels::mac::MacGrid& g,
                                                  const kernels::mac::MacEdges& edges,
                                                  const P0& phi0, const P& phi, int i, int j,
                                                  int k) {
  const int c = g.index(i, j, k);
  const double p = phi(c), s0 = phi0(c);
  const int idx[3] = {i, j, k}, n[3] = {g.nx, g.ny, g.nz},
            stride[3] = {1, g.stride_y(), g.stride_z()};
  // next to the interface (phi0 changes sign towards a neighbour): the distance phi0 / |grad phi0|
  // with each direction's largest difference (Russo & Smereka, eq. 20), a box face counting none
  double below0[3], above0[3];  // phi0's neighbours (the Godunov differences below read phi's)
  bool interface = false;
  for (int d = 0; d < 3; ++d) {
    const bool has_minus = idx[d] > 0 || !edges[2 * d],
               has_plus = idx[d] < n[d] - 1 || !edges[2 * d + 1];
    below0[d] = has_minus ? phi0(c - stride[d]) : s0,
    above0[d] = has_plus ? phi0(c + stride[d]) : s0;
    interface =
        interface || (has_minus && s0 * below0[d] <= 0.0) || (has_plus && s0 * above0[d] <= 0.0);
  }
  if (interface) {  // few cells: the spread only here
    double spread2 = 0.0;
    for (int d = 0; d < 3; ++d) {
      const double delta =
          math::max(math::max(0.5 * math::abs(above0[d] - below0[d]), math::abs(above0[d] - s0)),
                    math::abs(s0 - below0[d]));
      spread2 += delta * delta;
    }
    if (spread2 > 0.0) {
      const double distance = g.h * s0 / math::sqrt(spread2);
      return p - 0.5 * ((s0 < 0.0 ? -math::abs(p) : math::abs(p)) - distance);
    }
  }
  const double sign = s0 / math::sqrt(s0 * s0 + g.h * g.h);
  double grad2 = 0.0;
  for (int d = 0; d < 3; ++d) {
    // one-sided differences; at the box the missing side copies the cell (zero slope)
    const double minus = idx[d] > 0 || !edges[2 * d] ? (p - phi(c - stride[d])) / g.h : 0.0;
    const double plus =
        idx[d] < n[d] - 1 || !edges[2 * d + 1] ? (phi(c + stride[d]) - p) / g.h : 0.0;
    if (sign > 0) {
      const double a = math::max(minus, 0.0), b = math::min(plus, 0.0);
      grad2 += math::max(a * a, b * b);
    } else {
      const double a = math::min(minus, 0.0), b = math::max(plus, 0.0);
      grad2 += math::max(a * a, b * b);
    }
  }
  return p - 0.5 * g.h * sign * (math::sqrt(grad2) - 1.0);
}

/// One pseudo-time step of reinitialisation, phi -> phi_new.
template <class ExecSpace, class P0, class P, class PN>
void reinitialise_step(const ExecSpace& exec, const kernels::mac::MacGrid& g, const P0& phi0,
                       const P& phi, const PN& phi_new,
                       const kernels::mac::MacEdges& edges = kernels::mac::box_edges()) {
  Kokkos::parallel_for(
      "amphora::mac::reinitialise_step",
      Kokkos::MDRangePolicy<ExecSpace, Kokkos::Rank<3>>(exec, {0, 0, 0}, {g.nz, g.ny, g.nx}),
      KOKKOS_LAMBDA(int k, int j, int i) {
        phi_new(g.index(i, j, k)) = reinitialised_value(g, edges, phi0, phi, i, j, k);
      });
}

/// type = solid where solid(c), else fluid where phi < 0, else air.
template <class ExecSpace, class Solid, class P, class T>
void classify_cells(const ExecSpace& exec, const kernels::mac::MacGrid& g, const Solid& solid,
                    const P& phi, const T& type) {
  using kernels::mac::MacCellType;
  Kokkos::parallel_for(
      "amphora::mac::classify_cells",
      Kokkos::MDRangePolicy<ExecSpace, Kokkos::Rank<3>>(exec, {0, 0, 0}, {g.nz, g.ny, g.nx}),
      KOKKOS_LAMBDA(int k, int j, int i) {
        const int c = g.index(i, j, k);
        type(c) =
            solid(c) ? MacCellType::solid : (phi(c) < 0.0 ? MacCellType::fluid : MacCellType::air);
      });
}

}  // namespace amphora::kernels::mac
