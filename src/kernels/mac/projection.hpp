#pragma once
// The pieces of the pressure projection on a MAC grid (Bridson, Fluid Simulation for Computer
// Graphics, 2nd ed., ch. 5), in the units of kernels/mac/poisson_stencil.hpp:
//   A p = b,  b = -(rho h^2 / dt) div u*  on fluid cells,
//   u = u* - dt / (rho h) (p_R - p_L) on faces next to fluid,
// where across a free-surface face p on the air side is the ghost-fluid value that vanishes at
// the interface: (p_R - p_L) -> -p_fluid / theta (Gibou et al. 2002). Faces touching a solid
// or the box keep the solid's (zero) normal velocity. Velocities are extrapolated from the faces
// next to fluid into the air, layer by layer, for the next advection.
#include "kernels/mac/poisson_stencil.hpp"

namespace amphora::kernels::mac {

// On a block of a grid split over ranks, `edges` says which box faces end the domain: a face on
// another block's side is an inner face, its outer cell a ghost (exchanged by the caller).

namespace detail {
/// The two cells of face c of component d: L = c - stride, R = c; false if the face is on an
/// edge of the domain (i == 0 or i == n along d, on a face that is an edge).
KOKKOS_INLINE_FUNCTION bool face_cells(const kernels::mac::MacGrid& g,
                                       const kernels::mac::MacEdges& edges, int d, int i, int j,
                                       int k, int& L, int& R) {
  const int idx[3] = {i, j, k}, n[3] = {g.nx, g.ny, g.nz},
            stride[3] = {1, g.stride_y(), g.stride_z()};
  R = g.index(i, j, k);
  L = R - stride[d];
  return (idx[d] > 0 || !edges[2 * d]) && (idx[d] < n[d] || !edges[2 * d + 1]);
}
}  // namespace detail

/// The faces of component d that touch a solid cell or the box (padded indices, in lattice
/// order). Solids that do not move keep the list: the water module makes it once, and zeroing it
/// costs per listed face, not per face of the lattice (3.6 m pool: the terrain's rows and the
/// walls, 4 % of the faces).
template <class ExecSpace, class T>
Kokkos::View<int*, typename ExecSpace::memory_space> solid_faces(
    const ExecSpace& exec, const kernels::mac::MacGrid& g, int d, const T& type,
    const kernels::mac::MacEdges& edges = kernels::mac::box_edges()) {
  using kernels::mac::MacCellType;
  const int ex = g.nx + (d == 0), ey = g.ny + (d == 1), ez = g.nz + (d == 2);
  const auto touches_solid = KOKKOS_LAMBDA(int n, int& c) {
    const int i = n % ex, j = (n / ex) % ey, k = n / (ex * ey);
    int L, R;
    c = g.index(i, j, k);
    return !detail::face_cells(g, edges, d, i, j, k, L, R) || type(L) == MacCellType::solid ||
           type(R) == MacCellType::solid;
  };
  int count = 0;
  Kokkos::parallel_reduce(
      "amphora::mac::count_solid_faces", RangePolicy<ExecSpace>(exec, 0, ex * ey * ez),
      KOKKOS_LAMBDA(int n, int& acc) {
        int c;
        acc += touches_solid(n, c);
      },
      count);
  Kokkos::View<int*, typename ExecSpace::memory_space> list("amphora::mac::solid_faces", count);
  Kokkos::parallel_scan(
      "amphora::mac::list_solid_faces", RangePolicy<ExecSpace>(exec, 0, ex * ey * ez),
      KOKKOS_LAMBDA(int n, int& at, bool final) {
        int c;
        if (!touches_solid(n, c)) return;
        if (final) list(at) = c;
        ++at;
      });
  return list;
}

/// The listed faces (solid_faces) take the solid's (zero) normal velocity: before the divergence
/// is taken, so the right-hand side sees the walls.
template <class ExecSpace, class L, class F>
void enforce_solid_faces(const ExecSpace& exec, const L& list, const F& face) {
  Kokkos::parallel_for(
      "amphora::mac::enforce_solid_faces",
      RangePolicy<ExecSpace>(exec, 0, static_cast<int>(list.extent(0))),
      KOKKOS_LAMBDA(int n) { face(list(n)) = 0.0; });
}

/// b = -(rho h / dt) (sum of outward face velocities) on fluid cells, zero elsewhere.
template <class ExecSpace, class T, class U, class V, class W, class B>
void pressure_rhs(const ExecSpace& exec, const kernels::mac::MacGrid& g, const T& type, const U& u,
                  const V& v, const W& w, double rho, double dt, const B& b) {
  const int sy = g.stride_y(), sz = g.stride_z();
  const double scale = -rho * g.h / dt;
  Kokkos::parallel_for(
      "amphora::mac::pressure_rhs",
      RangePolicy<ExecSpace>(exec, 0, static_cast<int>(g.padded_size())), KOKKOS_LAMBDA(int c) {
        int i, j, k;
        g.ijk(c, i, j, k);
        if (!g.interior(i, j, k) || type(c) != kernels::mac::MacCellType::fluid) {
          b(c) = 0.0;
          return;
        }
        b(c) = scale * (u(c + 1) - u(c) + v(c + sy) - v(c) + w(c + sz) - w(c));
      });
}

/// u -= dt/(rho h) dp on the faces of component d next to fluid (ghost fluid at the surface);
/// zero on faces touching a solid or the box.
template <class ExecSpace, class T, class Phi, class P, class F>
void subtract_pressure_gradient(const ExecSpace& exec, const kernels::mac::MacGrid& g, int d,
                                const T& type, const Phi& phi, const P& p, double rho, double dt,
                                const F& face,
                                const kernels::mac::MacEdges& edges = kernels::mac::box_edges()) {
  using kernels::mac::MacCellType;
  const double scale = dt / (rho * g.h);
  const int ex = g.nx + (d == 0), ey = g.ny + (d == 1), ez = g.nz + (d == 2);
  Kokkos::parallel_for(
      "amphora::mac::subtract_pressure_gradient",
      Kokkos::MDRangePolicy<ExecSpace, Kokkos::Rank<3>>(exec, {0, 0, 0}, {ez, ey, ex}),
      KOKKOS_LAMBDA(int k, int j, int i) {
        int L, R;
        if (!detail::face_cells(g, edges, d, i, j, k, L, R)) {
          face(g.index(i, j, k)) = 0.0;
          return;
        }
        const MacCellType tl = type(L), tr = type(R);
        if (tl == MacCellType::solid || tr == MacCellType::solid) {
          face(R) = 0.0;
        } else if (tl == MacCellType::fluid && tr == MacCellType::fluid) {
          face(R) -= scale * (p(R) - p(L));
        } else if (tl == MacCellType::fluid) {  // air on the right
          face(R) -= scale * (-p(L) * ghost_fluid_weight(phi(L), phi(R)));
        } else if (tr == MacCellType::fluid) {  // air on the left
          face(R) -= scale * (p(R) * ghost_fluid_weight(phi(R), phi(L)));
        }
      });
}

/// valid(face) = 1 where the face of component d touches fluid and no solid (its velocity is
/// known after the projection), else 0; on the faces of rows first_row.. (the others keep theirs).
template <class ExecSpace, class T, class M>
void mark_fluid_faces(const ExecSpace& exec, const kernels::mac::MacGrid& g, int d, const T& type,
                      const M& valid,
                      const kernels::mac::MacEdges& edges = kernels::mac::box_edges(),
                      int first_row = 0) {
  using kernels::mac::MacCellType;
  const int ex = g.nx + (d == 0), ey = g.ny + (d == 1), ez = g.nz + (d == 2);
  Kokkos::parallel_for(
      "amphora::mac::mark_fluid_faces",
      Kokkos::MDRangePolicy<ExecSpace, Kokkos::Rank<3>>(exec, {0, math::min(first_row, ey), 0},
                                                        {ez, ey, ex}),
      KOKKOS_LAMBDA(int k, int j, int i) {
        int L, R;
        const bool inside = detail::face_cells(g, edges, d, i, j, k, L, R);
        const bool solid =
            !inside || type(L) == MacCellType::solid || type(R) == MacCellType::solid;
        valid(R) = !solid && (type(L) == MacCellType::fluid || type(R) == MacCellType::fluid);
      });
}

/// The lowest row of the block holding an air cell (ny if none). Extrapolation fills faces
/// between two air cells only, so it has nothing to do below this row: under deep water most
/// of the lattice.
template <class ExecSpace, class T>
int lowest_air_row(const ExecSpace& exec, const kernels::mac::MacGrid& g, const T& type) {
  int lowest = g.ny;
  Kokkos::parallel_reduce(
      "amphora::mac::lowest_air_row",
      Kokkos::MDRangePolicy<ExecSpace, Kokkos::Rank<3>>(exec, {0, 0, 0}, {g.nz, g.ny, g.nx}),
      KOKKOS_LAMBDA(int k, int j, int i, int& acc) {
        if (type(g.index(i, j, k)) == kernels::mac::MacCellType::air && j < acc) acc = j;
      },
      Kokkos::Min<int>(lowest));
  return lowest;
}

/// Layer `layer` (>= 2) of extrapolation, in place: every unknown (mark 0), non-solid face of
/// component d with face neighbours (same component, 6 directions) marked 1 .. layer - 1 takes
/// their mean and the mark `layer`. Faces marked in this layer are not read by it (their mark is
/// either 0 or `layer` while it runs), so the update is order- and thread-count-free without a
/// second buffer. Marks: 1 = known (next to fluid), 0 = unknown. Rows below first_row are
/// skipped: pass lowest_air_row(), below which no face lies between two air cells.
template <class ExecSpace, class T, class F, class M>
void extrapolate_layer(const ExecSpace& exec, const kernels::mac::MacGrid& g, int d, const T& type,
                       const F& face, const M& mark, int layer,
                       const kernels::mac::MacEdges& edges = kernels::mac::box_edges(),
                       int first_row = 0) {
  using kernels::mac::MacCellType;
  const int ex = g.nx + (d == 0), ey = g.ny + (d == 1), ez = g.nz + (d == 2);
  const int sy = g.stride_y(), sz = g.stride_z();
  Kokkos::parallel_for(
      "amphora::mac::extrapolate_layer",
      Kokkos::MDRangePolicy<ExecSpace, Kokkos::Rank<3>>(exec, {0, math::min(first_row, ey), 0},
                                                        {ez, ey, ex}),
      KOKKOS_LAMBDA(int k, int j, int i) {
        int L, R;
        const bool inside = detail::face_cells(g, edges, d, i, j, k, L, R);
        if (mark(R) || !inside || type(L) == MacCellType::solid || type(R) == MacCellType::solid)
          return;
        const int idx[3] = {i, j, k}, ext[3] = {ex, ey, ez}, stride[3] = {1, sy, sz};
        // the last face before another block is that block's first: it computes it (its
        // neighbours beyond lie outside this block's lattice) and the exchange brings it
        if (idx[d] + 1 == ext[d] && !edges[2 * d + 1]) return;
        double sum = 0.0;
        int n = 0;
        for (int e = 0; e < 3; ++e) {
          for (int side = -1; side <= 1; side += 2) {
            if ((side < 0 && idx[e] == 0 && edges[2 * e]) ||
                (side > 0 && idx[e] + 1 >= ext[e] && edges[2 * e + 1]))
              continue;
            const int nb = R + side * stride[e];
            const int m = mark(nb);
            if (m >= 1 && m < layer) sum += face(nb), ++n;
          }
        }
        if (n > 0) {
          face(R) = sum / n;
          mark(R) = static_cast<typename M::non_const_value_type>(layer);
        }
      });
}

}  // namespace amphora::kernels::mac
