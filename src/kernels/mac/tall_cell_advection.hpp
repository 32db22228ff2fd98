#pragma once
// The tall-cell parts of a water step (Irving, Guendelman, Losasso & Fedkiw 2006, sec. 4-5):
// - velocity in a tall cell is linear in height through its two samples; when the grid is
//   rebuilt (the band follows the surface), the lattice velocity in the new tall cells is
//   replaced by its least-squares linear fit per sample column, which keeps the column's
//   momentum sum_j u_j h^3 exactly (constants lie in the span of the fit) and reproduces linear
//   profiles;
// - in tall cells the velocity is advected by first-order upwind in flux form (a control volume
//   per face sample, face velocities averaged onto its faces): the fluxes telescope, so momentum
//   moves between samples without being created, and the scheme is stable for a Courant sum
//   dt (|u| + |v| + |w|) / h <= 1 there, which tall_cell_speed() lets the caller keep;
//   semi-Lagrangian tracing stays in the uniform cells, where the surface is;
// - the level set is neither advected nor reinitialised inside tall cells: they lie at least
//   the optical depth below the surface, where only its sign is used.
// The fields stay expanded on the lattice; these kernels choose the scheme per sample.
#include "kernels/mac/level_set.hpp"
#include "kernels/mac/semi_lagrangian.hpp"
#include "mesh/mac/tall_cell_columns.hpp"

namespace amphora::kernels::mac {

/// The face velocity component e at padded index c.
template <class U, class V, class W>
KOKKOS_INLINE_FUNCTION double component(int e, const U& u, const V& v, const W& w, int c) {
  return e == 0 ? double(u(c)) : e == 1 ? double(v(c)) : double(w(c));
}

/// Face sample c of component d after dt of first-order upwind advection in flux form:
/// q - dt/h sum_e (F_e+ - F_e-), F = U q_upwind with U the velocity normal to the control
/// volume's face (component e averaged over the two samples that share it).
template <class Q, class U, class V, class W>
KOKKOS_INLINE_FUNCTION double conservative_upwind_sample(const mesh::MacGrid& g, int d, int c, const Q& q, const U& u,
                                                         const V& v, const W& w, double dt) {
  const int stride[3] = {1, g.stride_y(), g.stride_z()};
  const int sd = stride[d];
  double net = 0.0;
  for (int e = 0; e < 3; ++e) {
    const int se = stride[e];
    // along d the control volume's faces are cell centres; across it, cell edges
    const double up = e == d ? 0.5 * (component(e, u, v, w, c) + component(e, u, v, w, c + sd))
                             : 0.5 * (component(e, u, v, w, c + se) + component(e, u, v, w, c + se - sd));
    const double down = e == d ? 0.5 * (component(e, u, v, w, c - sd) + component(e, u, v, w, c))
                               : 0.5 * (component(e, u, v, w, c) + component(e, u, v, w, c - sd));
    net += up * (up > 0.0 ? q(c) : q(c + se)) - down * (down > 0.0 ? q(c - se) : q(c));
  }
  return q(c) - dt / g.h * net;
}

/// q_new = q advected over dt: semi-Lagrangian in uniform cells, conservative upwind for face
/// samples in tall cells, unchanged for cell samples in tall cells. Face samples whose cells
/// both have phi >= reach are only copied: for reach at least the distance the surface can move
/// in dt plus the cells the next classification looks at, such a face lies in the air after the
/// step, where the caller discards the velocity (it is extrapolated afresh). q_new must not
/// alias q.
///
/// q, u, v, w, phi and T live on T.grid; q_new on `out`, whose sample (i, j, k) is T.grid's
/// (i + out_offset[0], j, k + out_offset[2]) (a block inside its widened grid: the traces near
/// the block's faces read the neighbours' cells).
template <class ExecSpace, class MemSpace, class Q, class QN, class U, class V, class W, class P>
void advect(const ExecSpace& exec, const mesh::TallCellColumns<MemSpace>& T, Staggering s, const Q& q, const QN& q_new,
            const U& u, const V& v, const W& w, double dt, const P& phi, double reach, const mesh::MacGrid& out,
            const int out_offset[3]) {
  const mesh::MacGrid g = T.grid, go = out;
  const int d = static_cast<int>(s), oi = out_offset[0], ok = out_offset[2];
  const int ex = go.nx + (d == 0), ey = go.ny + (d == 1), ez = go.nz + (d == 2);
  const int below = d == 0 ? 1 : d == 1 ? g.stride_y() : d == 2 ? g.stride_z() : 0;
  Kokkos::parallel_for(
      "amphora::mac::advect_tall_cells",
      Kokkos::MDRangePolicy<ExecSpace, Kokkos::Rank<3>>(exec, {0, 0, 0}, {ez, ey, ex}),
      KOKKOS_LAMBDA(int k, int j, int i) {
        const int I = i + oi, K = k + ok, c = g.index(I, j, K), o = go.index(i, j, k);
        if (d >= 0 && math::min(phi(c), phi(c - below)) >= reach)
          q_new(o) = q(c);
        else if (!T.in_tall_cell(d, I, j, K))
          q_new(o) = semi_lagrangian_sample(g, s, I, j, K, q, u, v, w, dt);
        else
          q_new(o) = d < 0 ? double(q(c)) : conservative_upwind_sample(g, d, c, q, u, v, w, dt);
      });
}

/// The same on T.grid itself.
template <class ExecSpace, class MemSpace, class Q, class QN, class U, class V, class W, class P>
void advect(const ExecSpace& exec, const mesh::TallCellColumns<MemSpace>& T, Staggering s, const Q& q, const QN& q_new,
            const U& u, const V& v, const W& w, double dt, const P& phi, double reach) {
  const int none[3] = {0, 0, 0};
  advect(exec, T, s, q, q_new, u, v, w, dt, phi, reach, T.grid, none);
}

/// One pseudo-time step of reinitialisation in the uniform cells (tall cells keep phi).
template <class ExecSpace, class MemSpace, class P0, class P, class PN>
void reinitialise_step(const ExecSpace& exec, const mesh::TallCellColumns<MemSpace>& T, const P0& phi0, const P& phi,
                       const PN& phi_new, const mesh::MacEdges& edges = mesh::box_edges()) {
  const mesh::MacGrid g = T.grid;
  Kokkos::parallel_for(
      "amphora::mac::reinitialise_step_tall_cells",
      Kokkos::MDRangePolicy<ExecSpace, Kokkos::Rank<3>>(exec, {0, 0, 0}, {g.nz, g.ny, g.nx}),
      KOKKOS_LAMBDA(int k, int j, int i) {
        const int c = g.index(i, j, k);
        phi_new(c) = T.in_tall_cell(-1, i, j, k) ? double(phi(c)) : reinitialised_value(g, edges, phi0, phi, i, j, k);
      });
}

/// Replaces the samples of face component d inside tall cells by their least-squares linear
/// fit in height, per sample column (sum and first moment kept).
template <class ExecSpace, class MemSpace, class F>
void fit_linear_in_tall_cells(const ExecSpace& exec, const mesh::TallCellColumns<MemSpace>& T, int d, const F& f) {
  const mesh::MacGrid g = T.grid;
  const int ex = g.nx + (d == 0), ez = g.nz + (d == 2), sy = g.stride_y();
  Kokkos::parallel_for(
      "amphora::mac::fit_linear_in_tall_cells", RangePolicy<ExecSpace>(exec, 0, ex * ez), KOKKOS_LAMBDA(int m) {
        const int i = m % ex, k = m / ex;
        int lo, hi;
        T.tall_rows(d, i, k, lo, hi);
        if (hi - lo < 3) return;  // one or two samples are linear already
        // centred heights t = j - mid keep the normal equations diagonal
        const double mid = 0.5 * (lo + hi - 1);
        const int c0 = g.index(i, lo, k);
        double sum = 0.0, moment = 0.0, tt = 0.0;
        for (int j = lo; j < hi; ++j) {
          const double t = j - mid, value = f(c0 + (j - lo) * sy);
          sum += value;
          moment += t * value;
          tt += t * t;
        }
        const double mean = sum / (hi - lo), slope = moment / tt;
        for (int j = lo; j < hi; ++j) f(c0 + (j - lo) * sy) = mean + slope * (j - mid);
      });
}

/// The largest |u| + |v| + |w| (each the larger of a cell's two faces) over the tall cells of
/// the block: the upwind step there is stable for dt <= h / tall_cell_speed (on a split grid the
/// caller takes the largest over the blocks).
template <class ExecSpace, class MemSpace, class U, class V, class W>
double tall_cell_speed(const ExecSpace& exec, const mesh::TallCellColumns<MemSpace>& T, const U& u, const V& v,
                       const W& w) {
  const mesh::MacGrid g = T.grid;
  const int sy = g.stride_y(), sz = g.stride_z();
  double speed = 0.0;
  Kokkos::parallel_reduce(
      "amphora::mac::tall_cell_speed", RangePolicy<ExecSpace>(exec, 0, g.nx * g.nz),
      KOKKOS_LAMBDA(int m, double& acc) {
        const int i = m % g.nx, k = m / g.nx, col = T.column(i, k);
        for (int j = T.terrain(col); j < T.band(col); ++j) {
          const int c = g.index(i, j, k);
          const double s = math::max(math::abs(u(c)), math::abs(u(c + 1))) +
                           math::max(math::abs(v(c)), math::abs(v(c + sy))) +
                           math::max(math::abs(w(c)), math::abs(w(c + sz)));
          acc = math::max(acc, s);
        }
      },
      Kokkos::Max<double>(speed));
  return speed;
}

}  // namespace amphora::kernels::mac
