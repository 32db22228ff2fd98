#pragma once
// Transfers between a MAC cell grid and the grid with cells twice as wide, for geometric
// multigrid on the pressure (the choices of McAdams, Sifakis & Teran 2010, sec. 4):
// - prolongation P: cell-centred trilinear interpolation (weights 3/4, 1/4 per direction);
//   beyond a wall the coarse value is copied from the nearest interior cell (even reflection:
//   zero normal derivative), beyond an open box face it is the negated one (odd reflection:
//   p = 0 on the face, so linear functions are interpolated exactly); solid coarse cells inside
//   the box first take the mean of their fluid face neighbours (an extension E that reflects
//   across flat terrain as a wall does), air cells stay zero, and non-fluid fine cells take
//   nothing;
// - restriction R = P^T exactly (E^T included) (so a symmetric smoother gives a symmetric V-cycle,
// as CG needs);
// - coarse matrix by re-discretisation in conductance form: a coarse face conducts half the sum
//   of its four fine faces, a coarse cell keeps half the open-box-face terms of its eight children.
//   For full faces that is the rediscretised Laplacian at 2h (c = 2 in fine units: area 4h^2 over
//   distance 2h), consistent with R = P^T, whose weights sum to 8. The free surface: with a level
//   set on the stencil (PoissonStencil::phi) the coarse level set is the mean of the children's
//   (exact for a linear phi), a coarse cell is an unknown where it has a fluid child and a
//   negative level set, and each face towards a non-solid coarse cell that is not one gets the
//   ghost-fluid term c / theta from the coarse level set, as the finest grid's are built. Halving
//   the children's c / theta instead is the coarse term only for theta = 1/2: a child's distance
//   to the surface is not its parent's, and MG-CG's iterations then grow with the grid; with the
//   coarse level set they stay flat (docs/water.md). Without a level set the free-surface terms
//   are halved.
#include "kernels/mac/poisson_stencil.hpp"

namespace amphora::kernels::mac {

namespace detail {
/// Weights of fine cells 2I-1 .. 2I+2 towards coarse cell I under P^T along one direction: 1/4,
/// 3/4, 3/4, 1/4, where a box face (an edge: clamped prolongation) moves the outer 1/4 onto the
/// inner cell. (Fine cells beyond an edge are ghosts holding zero; their weight does not matter.
/// Beyond another block's face they hold that block's values.)
template <class S>
KOKKOS_INLINE_FUNCTION void restriction_weights(int I, int n_c, bool edge_below, bool edge_above,
                                                bool wall_below, bool wall_above, S w[4]) {
  w[0] = S(0.25);
  w[1] = I == 0 && edge_below ? (wall_below ? S(1) : S(0.5)) : S(0.75);
  w[2] = I == n_c - 1 && edge_above ? (wall_above ? S(1) : S(0.5)) : S(0.75);
  w[3] = S(0.25);
}

/// The weight 1/4 of the second-nearest coarse cell, moved onto the nearest one beyond the box:
/// +1/4 at a wall (even reflection), -1/4 at an open face (odd reflection).
template <class S>
KOKKOS_INLINE_FUNCTION S reflected_weight(bool wall) {
  return wall ? S(0.25) : S(-0.25);
}
}  // namespace detail

/// coarse = R fine, on coarse fluid cells (zero elsewhere). fine must be zero on ghost cells.
template <class ExecSpace, class MemSpace, class S, class FineView, class CoarseView>
void restrict_to_coarse(const ExecSpace& exec, const PoissonStencil<MemSpace, S>& fine_A,
                        const PoissonStencil<MemSpace, S>& coarse_A, const FineView& fine,
                        const CoarseView& coarse) {
  const kernels::mac::MacGrid gf = fine_A.grid, gc = coarse_A.grid;
  const auto active = coarse_A.inverse_diag;
  const auto solid = coarse_A.solid;
  const int sy = gf.stride_y(), sz = gf.stride_z();
  const auto wall = coarse_A.walls();
  const auto edge = coarse_A.edges();
  Kokkos::parallel_for(
      "amphora::mac::restrict_to_coarse",
      Kokkos::MDRangePolicy<ExecSpace, Kokkos::Rank<3>>(exec, {0, 0, 0}, {gc.nz, gc.ny, gc.nx}),
      KOKKOS_LAMBDA(int K, int J, int I) {
        const int C = gc.index(I, J, K);
        if (active(C) == 0.0 && !solid(C)) {
          coarse(C) = 0.0;
          return;
        }
        S wx[4], wy[4], wz[4];
        detail::restriction_weights(I, gc.nx, edge[0], edge[1], wall[0], wall[1], wx);
        detail::restriction_weights(J, gc.ny, edge[2], edge[3], wall[2], wall[3], wy);
        detail::restriction_weights(K, gc.nz, edge[4], edge[5], wall[4], wall[5], wz);
        // Fine cells 2I-1 .. 2I+2 lie in the padded lattice; the ghost ones hold zeros.
        const int corner = gf.index(2 * I - 1, 2 * J - 1, 2 * K - 1);
        S sum = 0;
        for (int c = 0; c < 4; ++c) {
          S plane = 0;
          for (int b = 0; b < 4; ++b) {
            const int row = corner + b * sy + c * sz;
            plane += wy[b] * (wx[0] * fine(row) + wx[1] * fine(row + 1) + wx[2] * fine(row + 2) +
                              wx[3] * fine(row + 3));
          }
          sum += wz[c] * plane;
        }
        coarse(C) = sum;
      });
}

/// fine += P coarse, on fine fluid cells: each coarse cell fills its eight children from its
/// 3x3x3 neighbourhood (clamped at the box), one direction at a time.
template <class ExecSpace, class MemSpace, class S, class CoarseView, class FineView>
void prolongate_add(const ExecSpace& exec, const PoissonStencil<MemSpace, S>& coarse_A,
                    const PoissonStencil<MemSpace, S>& fine_A, const CoarseView& coarse,
                    const FineView& fine) {
  const kernels::mac::MacGrid gf = fine_A.grid, gc = coarse_A.grid;
  const auto active = fine_A.inverse_diag;
  const int fsy = gf.stride_y(), fsz = gf.stride_z();
  const auto wall = coarse_A.walls();
  const auto edge = coarse_A.edges();
  Kokkos::parallel_for(
      "amphora::mac::prolongate_add",
      Kokkos::MDRangePolicy<ExecSpace, Kokkos::Rank<3>>(exec, {0, 0, 0}, {gc.nz, gc.ny, gc.nx}),
      KOKKOS_LAMBDA(int K, int J, int I) {
        const S q = 0.25, t3 = 0.75;
        // beyond an edge of the grid, the neighbour is the cell itself with weight +-1/4 (see
        // above); beyond another block's face, the ghost cell holds it
        const bool outside_x[2] = {I == 0 && edge[0], I == gc.nx - 1 && edge[1]},
                   outside_y[2] = {J == 0 && edge[2], J == gc.ny - 1 && edge[3]},
                   outside_z[2] = {K == 0 && edge[4], K == gc.nz - 1 && edge[5]};
        const int xs[3] = {outside_x[0] ? I : I - 1, I, outside_x[1] ? I : I + 1};
        const int ys[3] = {outside_y[0] ? J : J - 1, J, outside_y[1] ? J : J + 1};
        const int zs[3] = {outside_z[0] ? K : K - 1, K, outside_z[1] ? K : K + 1};
        const S wx[2] = {outside_x[0] ? detail::reflected_weight<S>(wall[0]) : q,
                         outside_x[1] ? detail::reflected_weight<S>(wall[1]) : q};
        const S wy[2] = {outside_y[0] ? detail::reflected_weight<S>(wall[2]) : q,
                         outside_y[1] ? detail::reflected_weight<S>(wall[3]) : q};
        const S wz[2] = {outside_z[0] ? detail::reflected_weight<S>(wall[4]) : q,
                         outside_z[1] ? detail::reflected_weight<S>(wall[5]) : q};
        // along x: t[c][b][s] for child side s
        S t[3][3][2];
        for (int c = 0; c < 3; ++c)
          for (int b = 0; b < 3; ++b) {
            const int row = gc.index(0, ys[b], zs[c]);
            const S centre = coarse(row + I);
            t[c][b][0] = t3 * centre + wx[0] * coarse(row + xs[0]);
            t[c][b][1] = t3 * centre + wx[1] * coarse(row + xs[2]);
          }
        // along y, then z, then add to the children
        S u[3][2][2];
        for (int c = 0; c < 3; ++c)
          for (int sx = 0; sx < 2; ++sx) {
            u[c][0][sx] = t3 * t[c][1][sx] + wy[0] * t[c][0][sx];
            u[c][1][sx] = t3 * t[c][1][sx] + wy[1] * t[c][2][sx];
          }
        const int first = gf.index(2 * I, 2 * J, 2 * K);
        for (int sz_ = 0; sz_ < 2; ++sz_)
          for (int sy_ = 0; sy_ < 2; ++sy_)
            for (int sx = 0; sx < 2; ++sx) {
              const S v = t3 * u[1][sy_][sx] + wz[sz_] * u[sz_ == 0 ? 0 : 2][sy_][sx];
              const int f = first + sx + sy_ * fsy + sz_ * fsz;
              if (active(f) != 0.0) fine(f) += v;
            }
      });
}

namespace detail {
/// Fluid face neighbours of cell c.
template <class Active>
KOKKOS_INLINE_FUNCTION int fluid_neighbours(const Active& active, int c, int sy, int sz,
                                            int nbr[6]) {
  const int offsets[6] = {-1, 1, -sy, sy, -sz, sz};
  int n = 0;
  for (int f = 0; f < 6; ++f)
    if (active(c + offsets[f]) != 0) nbr[n++] = c + offsets[f];
  return n;
}
}  // namespace detail

/// E: every solid cell takes the mean of its fluid face neighbours (zero if it has none).
template <class ExecSpace, class MemSpace, class S, class V>
void extend_into_solids(const ExecSpace& exec, const PoissonStencil<MemSpace, S>& A, const V& v) {
  const kernels::mac::MacGrid g = A.grid;
  const auto active = A.inverse_diag;
  const auto solid = A.solid;
  const int sy = g.stride_y(), sz = g.stride_z();
  Kokkos::parallel_for(
      "amphora::mac::extend_into_solids",
      RangePolicy<ExecSpace>(exec, g.first_plane_index(), g.end_plane_index()),
      KOKKOS_LAMBDA(int c) {
        if (!solid(c)) return;
        int nbr[6];
        const int n = detail::fluid_neighbours(active, c, sy, sz, nbr);
        typename V::non_const_value_type sum = 0;
        for (int m = 0; m < n; ++m) sum += v(nbr[m]);
        v(c) = n > 0 ? sum / n : 0;
      });
}

/// E^T, then zero on every non-fluid cell: each fluid cell adds the share it gave to each solid
/// neighbour (ghost solid cells: their owners' values and shares).
template <class ExecSpace, class MemSpace, class S, class V>
void gather_from_solids(const ExecSpace& exec, const PoissonStencil<MemSpace, S>& A, const V& v) {
  const kernels::mac::MacGrid g = A.grid;
  const auto active = A.inverse_diag;
  const auto solid = A.solid;
  const auto share = A.solid_share;
  const int sy = g.stride_y(), sz = g.stride_z();
  const int first = g.first_plane_index(), end = g.end_plane_index();
  Kokkos::parallel_for(
      "amphora::mac::gather_from_solids", RangePolicy<ExecSpace>(exec, first, end),
      KOKKOS_LAMBDA(int c) {
        if (active(c) == 0) return;
        const int offsets[6] = {-1, 1, -sy, sy, -sz, sz};
        typename V::non_const_value_type add = 0;
        for (int f = 0; f < 6; ++f) {
          const int s = c + offsets[f];
          if (solid(s)) add += v(s) * static_cast<typename V::non_const_value_type>(share(s));
        }
        v(c) += add;
      });
  Kokkos::parallel_for(
      "amphora::mac::zero_non_fluid", RangePolicy<ExecSpace>(exec, first, end),
      KOKKOS_LAMBDA(int c) {
        if (active(c) == 0) v(c) = 0;
      });
}

/// The restriction of a multigrid cycle: coarse = R fine = E^T P^T fine (zero off the fluid).
template <class ExecSpace, class MemSpace, class S, class FineView, class CoarseView>
void restrict_residual(const ExecSpace& exec, const PoissonStencil<MemSpace, S>& fine_A,
                       const PoissonStencil<MemSpace, S>& coarse_A, const FineView& fine,
                       const CoarseView& coarse) {
  restrict_to_coarse(exec, fine_A, coarse_A, fine, coarse);
  if (coarse_A.any_solid) gather_from_solids(exec, coarse_A, coarse);
}

/// The prolongation of a multigrid cycle: fine += P E coarse (E writes coarse's solid cells).
template <class ExecSpace, class MemSpace, class S, class CoarseView, class FineView>
void prolongate_correction(const ExecSpace& exec, const PoissonStencil<MemSpace, S>& coarse_A,
                           const PoissonStencil<MemSpace, S>& fine_A, const CoarseView& coarse,
                           const FineView& fine) {
  if (coarse_A.any_solid) extend_into_solids(exec, coarse_A, coarse);
  prolongate_add(exec, coarse_A, fine_A, coarse, fine);
}

/// Pass 2 of coarsen_stencil: diagonal = the coarse conductances towards unknowns + half the
/// children's open-box-face terms + the free-surface terms (see the top of this file), from coarse
/// row first_row up; with a level set also the coarse level set, and the conductances towards
/// non-unknowns zeroed. ghosts_known: the ghost cells' diagonal (which says whether a cell is an
/// unknown), solid flags and level set hold the neighbouring blocks' (a split grid's second call,
/// after the exchange); otherwise a coarse face towards a ghost cell counts as one between
/// unknowns.
template <class ExecSpace, class MemSpace>
void coarse_diagonal(const ExecSpace& exec, const PoissonStencil<MemSpace>& fine_A,
                     const PoissonStencil<MemSpace>& coarse_A, int first_row = 0,
                     bool ghosts_known = false) {
  const kernels::mac::MacGrid gf = fine_A.grid, gc = coarse_A.grid;
  const auto fd = fine_A.diag;
  const auto fcx = fine_A.cx, fcy = fine_A.cy, fcz = fine_A.cz;
  const auto cd = coarse_A.diag, cinv = coarse_A.inverse_diag;
  const auto ccx = coarse_A.cx, ccy = coarse_A.cy, ccz = coarse_A.cz;
  const auto fsolid = fine_A.solid, csolid = coarse_A.solid;
  const auto fphi = fine_A.phi, cphi = coarse_A.phi;
  const bool level_set = fphi.extent(0) > 0 && cphi.extent(0) > 0;
  const double fine_face = fine_A.full_face, coarse_face = coarse_A.full_face;
  const auto edge = coarse_A.edges();
  const auto wall = coarse_A.walls();
  const int sy = gf.stride_y(), sz = gf.stride_z();
  const int csy = gc.stride_y(), csz = gc.stride_z();
  const int J0 = math::clamp(first_row, 0, gc.ny);
  const auto cells =
      Kokkos::MDRangePolicy<ExecSpace, Kokkos::Rank<3>>(exec, {0, J0, 0}, {gc.nz, gc.ny, gc.nx});
  // With a level set, first each coarse cell's level set (the children's mean), solid flag and
  // whether it is an unknown (a fluid child and a negative level set), which its neighbours read.
  // (From the row under the first one: the first one reads it.)
  Kokkos::View<std::uint8_t*, MemSpace> unknown;
  if (level_set) {
    unknown =
        Kokkos::View<std::uint8_t*, MemSpace>("amphora::mac::coarse_unknown", gc.padded_size());
    Kokkos::parallel_for(
        "amphora::mac::coarsen_stencil::level_set",
        Kokkos::MDRangePolicy<ExecSpace, Kokkos::Rank<3>>(exec, {0, math::max(J0 - 1, 0), 0},
                                                          {gc.nz, gc.ny, gc.nx}),
        KOKKOS_LAMBDA(int K, int J, int I) {
          bool fluid = false, all_solid = true;
          double phi = 0.0;
          for (int c3 = 0; c3 < 2; ++c3)
            for (int b = 0; b < 2; ++b)
              for (int a = 0; a < 2; ++a) {
                const int f = gf.index(2 * I + a, 2 * J + b, 2 * K + c3);
                fluid = fluid || fd(f) != 0.0;
                all_solid = all_solid && fsolid(f);
                phi += fphi(f);
              }
          const int c = gc.index(I, J, K);
          cphi(c) = 0.125 * phi;
          csolid(c) = all_solid;
          unknown(c) = fluid && phi < 0.0;
        });
  }
  // Per direction e = -x, +x, -y, +y, -z, +z of coarse cell (I, J, K): whether a box face lies
  // that way, and whether the neighbour that way is an unknown, with its solid flag and level set
  // (a ghost cell's from the exchange when known, else taken to be an unknown).
  const auto beyond_box = KOKKOS_LAMBDA(int I, int J, int K, int e) {
    const int at[6] = {I, gc.nx - 1 - I, J, gc.ny - 1 - J, K, gc.nz - 1 - K};
    return at[e] == 0 && edge[e];
  };
  const auto neighbour = KOKKOS_LAMBDA(int I, int J, int K, int e, double& phi_n, bool& solid_n) {
    const int NI = I + (e == 1) - (e == 0), NJ = J + (e == 3) - (e == 2),
              NK = K + (e == 5) - (e == 4);
    const bool ghost = NI < 0 || NJ < 0 || NK < 0 || NI >= gc.nx || NJ >= gc.ny || NK >= gc.nz;
    if (ghost && !ghosts_known) {
      phi_n = 0.0, solid_n = false;
      return true;
    }
    const int n = gc.index(NI, NJ, NK);
    phi_n = cphi(n), solid_n = csolid(n);
    return ghost ? cd(n) != 0.0 : unknown(n) != 0;
  };
  Kokkos::parallel_for(
      "amphora::mac::coarsen_stencil::diagonal", cells, KOKKOS_LAMBDA(int K, int J, int I) {
        // The children's free-surface and open-box-face terms: without a level set all of them
        // (the diagonal beyond the faces towards fluid); with one only the open-box-face terms
        // (the diagonal beyond the faces towards unknowns and air inside the box), which only
        // the children of a cell on a box face have.
        bool beyond[6];
        for (int e = 0; e < 6; ++e) beyond[e] = beyond_box(I, J, K, e);
        // (a wall adds no term)
        const bool open_face = (beyond[0] && !wall[0]) || (beyond[1] && !wall[1]) ||
                               (beyond[2] && !wall[2]) || (beyond[3] && !wall[3]) ||
                               (beyond[4] && !wall[4]) || (beyond[5] && !wall[5]);
        double dirichlet = 0.0;
        bool any_fluid = false, all_solid = true;
        const int offset[6] = {-1, 1, -sy, sy, -sz, sz};
        for (int c3 = 0; c3 < 2 && (open_face || !level_set); ++c3)
          for (int b = 0; b < 2; ++b)
            for (int a = 0; a < 2; ++a) {
              const int f = gf.index(2 * I + a, 2 * J + b, 2 * K + c3);
              all_solid = all_solid && fsolid(f);
              if (fd(f) == 0.0) continue;
              any_fluid = true;
              const double c[6] = {double(fcx(f - 1)), double(fcx(f)),      double(fcy(f - sy)),
                                   double(fcy(f)),     double(fcz(f - sz)), double(fcz(f))};
              if (!level_set) {
                dirichlet += fd(f) - (c[0] + c[1] + c[2] + c[3] + c[4] + c[5]);
                continue;
              }
              const bool child_beyond[6] = {a == 0 && beyond[0],  a == 1 && beyond[1],
                                            b == 0 && beyond[2],  b == 1 && beyond[3],
                                            c3 == 0 && beyond[4], c3 == 1 && beyond[5]};
              double d = fd(f);
              for (int e = 0; e < 6; ++e) {
                if (child_beyond[e]) continue;
                const int n = f + offset[e];
                if (fd(n) != 0.0)
                  d -= c[e];
                else if (!fsolid(n))
                  d -= fine_face * ghost_fluid_weight(fphi(f), fphi(n));
              }
              dirichlet += d;
            }
        const int c = gc.index(I, J, K);
        double diag = 0.0;
        if (level_set ? unknown(c) != 0 : any_fluid) {
          const double cc[6] = {double(ccx(c - 1)), double(ccx(c)),       double(ccy(c - csy)),
                                double(ccy(c)),     double(ccz(c - csz)), double(ccz(c))};
          diag = 0.5 * dirichlet;
          for (int e = 0; e < 6; ++e) {
            if (beyond[e]) continue;
            if (!level_set) {
              diag += cc[e];
              continue;
            }
            double phi_n = 0.0;
            bool solid_n = false;
            if (neighbour(I, J, K, e, phi_n, solid_n))
              diag += cc[e];
            else if (!solid_n)
              diag += coarse_face * ghost_fluid_weight(cphi(c), phi_n);
          }
        }
        cd(c) = diag;
        cinv(c) = diag > 0.0 ? 1.0 / diag : 0.0;
        if (!level_set) csolid(c) = all_solid;  // (with one: above)
      });
  if (!level_set) return;
  // the conductances of faces with a non-unknown on either side (no unknown couples through
  // them); none beyond a box face
  Kokkos::parallel_for(
      "amphora::mac::coarsen_stencil::faces_of_unknowns", cells,
      KOKKOS_LAMBDA(int K, int J, int I) {
        const int c = gc.index(I, J, K);
        if (!unknown(c)) {
          ccx(c) = ccy(c) = ccz(c) = 0.0f;
          return;
        }
        double phi_n = 0.0;
        bool solid_n = false;
        if (beyond_box(I, J, K, 1) || !neighbour(I, J, K, 1, phi_n, solid_n)) ccx(c) = 0.0f;
        if (beyond_box(I, J, K, 3) || !neighbour(I, J, K, 3, phi_n, solid_n)) ccy(c) = 0.0f;
        if (beyond_box(I, J, K, 5) || !neighbour(I, J, K, 5, phi_n, solid_n)) ccz(c) = 0.0f;
      });
  // the x-rows free of free-surface and open-box-face terms (PoissonStencil::surface_free_rows):
  // no unknown in them beside a non-solid cell that is not one, or at an open box face
  const auto cfree = coarse_A.surface_free_rows;
  const int rows = gc.ny - J0;
  Kokkos::parallel_for(
      "amphora::mac::coarsen_stencil::surface_free_rows",
      RangePolicy<ExecSpace>(exec, 0, rows * gc.nz), KOKKOS_LAMBDA(int m) {
        const int J = J0 + m % rows, K = m / rows;
        bool row_free = true;
        for (int I = 0; I < gc.nx && row_free; ++I) {
          const int c = gc.index(I, J, K);
          if (!unknown(c)) continue;
          for (int e = 0; e < 6 && row_free; ++e) {
            double phi_n = 0.0;
            bool solid_n = false;
            if (beyond_box(I, J, K, e))
              row_free = wall[e];
            else if (!neighbour(I, J, K, e, phi_n, solid_n))
              row_free = solid_n;
          }
        }
        cfree(x_row(gc, J, K)) = row_free ? 1 : 0;
      });
}

/// The first coarse row that a change of the fine stencil from fine row `first_row` up can
/// reach: a coarse row reads the fine rows 2J - 1 (the -y faces) to 2J + 1; with a level set
/// also its neighbours' children (whether they are unknowns, their level set) and the faces of
/// the row below, which that decides: fine rows 2J - 2 to 2J + 3.
inline int first_coarse_row_changed(int first_row, bool level_set = false) {
  return level_set ? math::max(math::max(first_row, 0) / 2 - 2, 0) : math::max(first_row, 0) / 2;
}

/// The coarse matrix of a fine one (grid dimensions even; see the header comment) into
/// coarse_A (allocated on the coarsened grid), from coarse row first_row up. The rows below
/// keep what coarse_A holds, which must be what a coarsening gives there: pass
/// first_coarse_row_changed(the fine row from which the fine stencil changed since coarse_A was
/// coarsened from it).
template <class ExecSpace, class MemSpace>
void coarsen_stencil(const ExecSpace& exec, const PoissonStencil<MemSpace>& fine_A,
                     PoissonStencil<MemSpace>& coarse_A, int first_row) {
  const kernels::mac::MacGrid gf = fine_A.grid, gc = coarse_A.grid;
  const bool level_set = fine_A.phi.extent(0) > 0;
  const int J0 = math::clamp(first_row, 0, gc.ny);
  coarse_A.box = fine_A.box;
  coarse_A.full_face = 2.0 * fine_A.full_face;
  if (!level_set)
    coarse_A.phi = {};
  else if (coarse_A.phi.extent(0) != static_cast<std::size_t>(gc.padded_size()))
    coarse_A.phi = Kokkos::View<double*, MemSpace>("amphora::mac::phi", gc.padded_size());
  const auto fcx = fine_A.cx, fcy = fine_A.cy, fcz = fine_A.cz;
  const auto ccx = coarse_A.cx, ccy = coarse_A.cy, ccz = coarse_A.cz;
  // Pass 1: conductances of the + faces of every coarse cell.
  Kokkos::parallel_for(
      "amphora::mac::coarsen_stencil::faces",
      Kokkos::MDRangePolicy<ExecSpace, Kokkos::Rank<3>>(exec, {0, J0, 0}, {gc.nz, gc.ny, gc.nx}),
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
  coarse_diagonal(exec, fine_A, coarse_A, J0);
  // Without a level set a coarse cell's free-surface term is half its children's
  // (coarse_diagonal): zero on a row whose four child rows are all known free of them. (With
  // one, coarse_diagonal marks the rows.)
  const auto ffree = fine_A.surface_free_rows, cfree = coarse_A.surface_free_rows;
  const int rows = gc.ny - J0;
  if (!level_set) {
    Kokkos::parallel_for(
        "amphora::mac::coarsen_stencil::surface_free_rows",
        RangePolicy<ExecSpace>(exec, 0, rows * gc.nz), KOKKOS_LAMBDA(int m) {
          const int J = J0 + m % rows, K = m / rows;
          std::uint8_t all = 1;
          for (int c3 = 0; c3 < 2; ++c3)
            for (int b = 0; b < 2; ++b) all = all & ffree(x_row(gf, 2 * J + b, 2 * K + c3));
          cfree(x_row(gc, J, K)) = all;
        });
  }
  coarse_A.unit_fluid_faces = false;
  coarse_A.any_solid = fine_A.any_solid && count_solid(exec, coarse_A) > 0;
  // a solid cell's share reads the cells beside it: from the row under the first coarsened one
  compute_solid_shares(exec, coarse_A, J0 - 1);
}

/// A new coarse matrix of a fine one, every row coarsened.
template <class ExecSpace, class MemSpace>
PoissonStencil<MemSpace> coarsen_stencil(const ExecSpace& exec,
                                         const PoissonStencil<MemSpace>& fine_A) {
  PoissonStencil<MemSpace> coarse_A(fine_A.grid.coarsened());
  coarsen_stencil(exec, fine_A, coarse_A, 0);
  return coarse_A;
}

}  // namespace amphora::kernels::mac
