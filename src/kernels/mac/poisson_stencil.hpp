#pragma once
// The 7-point MAC pressure Poisson matrix in conductance form,
//   (A p)_i = d_i p_i - sum_{fluid neighbours j} c_ij p_j,  d_i = D_i + sum_j c_ij,
// scaled by h (so a full fluid-fluid face has c = 1): A = -h^2 (div grad) restricted to the
// fluid cells. D_i collects the free-surface faces: the ghost-fluid method (Gibou, Fedkiw,
// Cheng & Kang 2002, sec. 3) puts p = 0 on the interface at the fraction theta = phi_i /
// (phi_i - phi_j) of the way to the air cell, which adds 1/theta to d_i. Solid faces add
// nothing (Neumann). Rows of non-fluid cells are zero (d = 0), so every vector stays zero there.
//
// Stored on the padded lattice of MacGrid: d, c_x/c_y/c_z (float: the values are exact small
// fractions) on the + face of each cell, and 1/d (zero on non-fluid cells). Scalar is the
// type of d, 1/d and of the arithmetic: double for the operator CG sees, float for the
// multigrid preconditioner (half the memory traffic; a preconditioner needs no more).
#include <type_traits>

#include "kernels/spaces.hpp"
#include "kernels/mac/mac_grid.hpp"

namespace amphora::kernels::mac {

/// theta of the ghost-fluid method, kept away from zero so d stays bounded (Gibou et al. use
/// the same clamp; 1e-3 keeps the condition number below 1e3 times the uniform one).
inline constexpr double min_ghost_fluid_theta = 1e-3;

/// 1/theta for a fluid cell with level set phi_fluid (< 0) next to an air cell with phi_air.
KOKKOS_INLINE_FUNCTION double ghost_fluid_weight(double phi_fluid, double phi_air) {
  const double denom = phi_fluid - phi_air;
  const double theta = denom < 0.0 ? phi_fluid / denom : 1.0;
  return 1.0 / math::max(theta, min_ghost_fluid_theta);
}

/// The index of the interior x-row (j, k) among g's ny * nz x-rows (per-row data of a lattice).
KOKKOS_INLINE_FUNCTION int x_row(const kernels::mac::MacGrid& g, int j, int k) {
  return j + g.ny * k;
}

template <class MemSpace, class Scalar = double>
struct PoissonStencil {
  using scalar_type = Scalar;
  kernels::mac::MacGrid grid;
  kernels::mac::MacBoxBoundaries box{};  ///< what lies beyond each box face (multigrid transfers)
  Kokkos::View<Scalar*, MemSpace> diag, inverse_diag;
  Kokkos::View<float*, MemSpace> cx, cy, cz;
  /// 1 on solid cells inside the box (terrain, obstacles): multigrid extends a correction into
  /// them as across a wall, where air cells take zero.
  Kokkos::View<std::uint8_t*, MemSpace> solid;
  /// 1 / (fluid face neighbours) of a solid cell, zero elsewhere: the weight of the extension
  /// into solids (grid_transfer.hpp); stored so a ghost solid cell carries its owner's value.
  Kokkos::View<double*, MemSpace> solid_share;
  bool any_solid = false;  ///< some cell is solid (else the multigrid skips the extension)
  /// What a build or a coarsening knows of the values, for an assembler that can then leave
  /// lattice rows unread (the tall-cell matrix, whose tall cells span most rows of a deep pool):
  /// 1 where every cell of the x-row (j, k), at surface_free_row(j, k), has D = 0 (no
  /// free-surface face, no open box face), 0 where that is not known.
  Kokkos::View<std::uint8_t*, MemSpace> surface_free_rows;
  /// Every face between two fluid cells has c = 1 (a build; not a coarsened stencil).
  bool unit_fluid_faces = false;
  /// The level set at the cell centres, when the build had one (empty otherwise): the multigrid
  /// coarsens it to form its coarse levels' free-surface terms (grid_transfer.hpp).
  Kokkos::View<double*, MemSpace> phi;
  /// A full face's conductance on this grid: 1 on a built one, doubled per coarsening.
  double full_face = 1.0;

  KOKKOS_INLINE_FUNCTION int surface_free_row(int j, int k) const { return x_row(grid, j, k); }

  /// sum_j c_ij x_j over the six neighbours of cell c (x zero where a cell is not fluid).
  template <class X>
  KOKKOS_INLINE_FUNCTION Scalar neighbour_sum(const X& x, int c) const {
    const int sy = grid.stride_y(), sz = grid.stride_z();
    return Scalar(cx(c - 1)) * x(c - 1) + Scalar(cx(c)) * x(c + 1) +
           Scalar(cy(c - sy)) * x(c - sy) + Scalar(cy(c)) * x(c + sy) +
           Scalar(cz(c - sz)) * x(c - sz) + Scalar(cz(c)) * x(c + sz);
  }

  /// Which box faces are walls, as a device-copyable array.
  Kokkos::Array<bool, 6> walls() const {
    Kokkos::Array<bool, 6> w;
    for (int f = 0; f < 6; ++f) w[f] = box[f] == kernels::mac::MacBoundary::wall;
    return w;
  }
  /// Which box faces end the grid (wall or open, not another block's face).
  Kokkos::Array<bool, 6> edges() const {
    Kokkos::Array<bool, 6> e;
    for (int f = 0; f < 6; ++f) e[f] = box[f] != kernels::mac::MacBoundary::neighbour;
    return e;
  }

  PoissonStencil() = default;
  explicit PoissonStencil(const kernels::mac::MacGrid& g)
      : grid(g),
        diag("amphora::mac::diag", g.padded_size()),
        inverse_diag("amphora::mac::inverse_diag", g.padded_size()),
        cx("amphora::mac::cx", g.padded_size()),
        cy("amphora::mac::cy", g.padded_size()),
        cz("amphora::mac::cz", g.padded_size()),
        solid("amphora::mac::solid", g.padded_size()),
        solid_share("amphora::mac::solid_share", g.padded_size()),
        surface_free_rows("amphora::mac::surface_free_rows",
                          static_cast<std::size_t>(g.ny) * g.nz) {}
};

/// v = 0 on the ghost planes k = -1 and k = nz, which the flat stencil loops do not visit (the
/// ghost cells inside the planes they visit come out zero because their coefficients are).
template <class ExecSpace, class V>
void zero_ghost_planes(const ExecSpace& exec, const kernels::mac::MacGrid& g, const V& v) {
  const int plane = g.stride_z(), last = g.end_plane_index();
  Kokkos::parallel_for(
      "amphora::mac::zero_ghost_planes", RangePolicy<ExecSpace>(exec, 0, plane),
      KOKKOS_LAMBDA(int c) {
        v(c) = 0.0;
        v(last + c) = 0.0;
      });
}

/// v = 0 on every ghost cell beyond the x and z faces (the y ghosts of the planes are zero
/// after apply/residual, whose coefficients there are).
template <class ExecSpace, class V>
void zero_ghost_cells(const ExecSpace& exec, const kernels::mac::MacGrid& g, const V& v) {
  zero_ghost_planes(exec, g, v);
  Kokkos::parallel_for(
      "amphora::mac::zero_ghost_columns", RangePolicy<ExecSpace>(exec, 0, (g.ny + 2) * g.nz),
      KOKKOS_LAMBDA(int row) {
        const int j = row % (g.ny + 2) - 1, k = row / (g.ny + 2);
        v(g.index(-1, j, k)) = 0.0;
        v(g.index(g.nx, j, k)) = 0.0;
      });
}

/// y = A x on every interior cell; every ghost entry of y is zero (on one block).
template <class ExecSpace, class MemSpace, class S, class X, class Y>
void apply(const ExecSpace& exec, const PoissonStencil<MemSpace, S>& A, const X& x, const Y& y) {
  const PoissonStencil<MemSpace, S> a = A;
  Kokkos::parallel_for(
      "amphora::mac::apply",
      RangePolicy<ExecSpace>(exec, A.grid.first_plane_index(), A.grid.end_plane_index()),
      KOKKOS_LAMBDA(int c) { y(c) = a.diag(c) * x(c) - a.neighbour_sum(x, c); });
  zero_ghost_planes(exec, A.grid, y);
}

/// r = b - A x on every interior cell, zero on every ghost cell. (The flat loop also passes the
/// x ghost columns, where the -x neighbour of cell -1 is the last ghost of the row below: on a
/// block with a neighbour beyond +x, its conductance and value are the neighbour's, so the
/// columns are zeroed after.)
template <class ExecSpace, class MemSpace, class S, class B, class X, class R>
void residual(const ExecSpace& exec, const PoissonStencil<MemSpace, S>& A, const B& b, const X& x,
              const R& r) {
  const PoissonStencil<MemSpace, S> a = A;
  Kokkos::parallel_for(
      "amphora::mac::residual",
      RangePolicy<ExecSpace>(exec, A.grid.first_plane_index(), A.grid.end_plane_index()),
      KOKKOS_LAMBDA(int c) { r(c) = b(c) - a.diag(c) * x(c) + a.neighbour_sum(x, c); });
  zero_ghost_cells(exec, A.grid, r);
}

/// red_black_gauss_seidel's schedule on devices: one work item per cell of the colour, so
/// neighbouring threads touch neighbouring addresses (every other cell of an x-row).
template <class ExecSpace, class MemSpace, class S, class B, class X>
void red_black_gauss_seidel_cells(const ExecSpace& exec, const PoissonStencil<MemSpace, S>& A,
                                  const B& b, const X& x, int colour) {
  const PoissonStencil<MemSpace, S> a = A;
  const kernels::mac::MacGrid g = A.grid;
  const int half = (g.nx + 1) / 2;
  Kokkos::parallel_for(
      "amphora::mac::red_black_gauss_seidel_cells",
      RangePolicy<ExecSpace>(exec, 0, half * g.ny * g.nz), KOKKOS_LAMBDA(int t) {
        const int row = t / half, j = row % g.ny, k = row / g.ny;
        const int i = 2 * (t % half) + ((j + k + colour) & 1);
        if (i >= g.nx) return;
        const int c = g.index(i, j, k);
        x(c) = a.inverse_diag(c) * (b(c) + a.neighbour_sum(x, c));
      });
}

/// One Gauss–Seidel half-sweep over the cells with (i + j + k) % 2 == colour: the cells of one
/// colour only couple to the other colour, so the update is order-free and thread-count-free.
template <class ExecSpace, class MemSpace, class S, class B, class X>
void red_black_gauss_seidel(const ExecSpace& exec, const PoissonStencil<MemSpace, S>& A, const B& b,
                            const X& x, int colour) {
  if constexpr (!runs_on_host_v<ExecSpace>) {
    red_black_gauss_seidel_cells(exec, A, b, x, colour);
    return;
  }
  const PoissonStencil<MemSpace, S> a = A;
  const kernels::mac::MacGrid g = A.grid;
  // One work item per x-row. The row is updated in chunks: first every cell's Gauss–Seidel
  // value into a local buffer (contiguous, so it vectorises; only other-colour cells are read for
  // the cells that are kept), then the cells of this colour are written.
  constexpr int chunk = 32;
  Kokkos::parallel_for(
      "amphora::mac::red_black_gauss_seidel", RangePolicy<ExecSpace>(exec, 0, g.ny * g.nz),
      KOKKOS_LAMBDA(int row) {
        const int j = row % g.ny, k = row / g.ny;
        const int first = (j + k + colour) & 1;
        const int base = g.index(0, j, k);
        for (int i0 = 0; i0 < g.nx; i0 += chunk) {
          const int len = math::min(chunk, g.nx - i0);
          S value[chunk];
          for (int m = 0; m < len; ++m) {
            const int c = base + i0 + m;
            value[m] = a.inverse_diag(c) * (b(c) + a.neighbour_sum(x, c));
          }
          // i0 is even, so the kept cells are m = first, first + 2, ...
          for (int m = first; m < len; m += 2) x(base + i0 + m) = value[m];
        }
      });
}

/// `steps` red-black Gauss–Seidel steps (each `colour`, then the other) in one launch, by one
/// team with a barrier after each half-sweep: for grids so small that a device's launches, not
/// its bandwidth, bound the sweeps (a multigrid's coarse levels). Each cell's update is
/// red_black_gauss_seidel's. team_size 0: the largest the space allows for this kernel (at most
/// 1024).
template <class ExecSpace, class MemSpace, class S, class B, class X>
void red_black_gauss_seidel_team(const ExecSpace& exec, const PoissonStencil<MemSpace, S>& A,
                                 const B& b, const X& x, int colour, int steps, int team_size = 0) {
  using Policy = Kokkos::TeamPolicy<ExecSpace>;
  using Member = typename Policy::member_type;
  const PoissonStencil<MemSpace, S> a = A;
  const kernels::mac::MacGrid g = A.grid;
  const int half = (g.nx + 1) / 2, n = half * g.ny * g.nz;
  const auto body = KOKKOS_LAMBDA(const Member& team) {
    for (int s = 0; s < 2 * steps; ++s) {
      const int c0 = colour ^ (s & 1);
      Kokkos::parallel_for(Kokkos::TeamThreadRange(team, n), [&](int t) {
        const int row = t / half, j = row % g.ny, k = row / g.ny;
        const int i = 2 * (t % half) + ((j + k + c0) & 1);
        if (i >= g.nx) return;
        const int c = g.index(i, j, k);
        x(c) = a.inverse_diag(c) * (b(c) + a.neighbour_sum(x, c));
      });
      team.team_barrier();
    }
  };
  if (team_size <= 0)
    team_size = math::min(1024, Policy(exec, 1, 1).team_size_max(body, Kokkos::ParallelForTag()));
  Kokkos::parallel_for("amphora::mac::red_black_gauss_seidel_team", Policy(exec, 1, team_size),
                       body);
}

/// Damped Jacobi: x_new = x + omega D^-1 (b - A x), written to x_new (x is read only).
template <class ExecSpace, class MemSpace, class S, class B, class X, class XN>
void jacobi(const ExecSpace& exec, const PoissonStencil<MemSpace, S>& A, const B& b, const X& x,
            const XN& x_new, S omega) {
  const PoissonStencil<MemSpace, S> a = A;
  Kokkos::parallel_for(
      "amphora::mac::jacobi",
      RangePolicy<ExecSpace>(exec, A.grid.first_plane_index(), A.grid.end_plane_index()),
      KOKKOS_LAMBDA(int c) {
        const S r = b(c) - a.diag(c) * x(c) + a.neighbour_sum(x, c);
        x_new(c) = x(c) + omega * a.inverse_diag(c) * r;
      });
}

/// Number of solid cells.
template <class ExecSpace, class MemSpace, class S>
int count_solid(const ExecSpace& exec, const PoissonStencil<MemSpace, S>& A) {
  const auto solid = A.solid;
  int n = 0;
  Kokkos::parallel_reduce(
      "amphora::mac::count_solid",
      RangePolicy<ExecSpace>(exec, 0, static_cast<int>(solid.extent(0))),
      KOKKOS_LAMBDA(int c, int& acc) { acc += solid(c); }, n);
  return n;
}

/// solid_share = 1 / (fluid face neighbours) on the interior solid cells (zero without any),
/// from the ghost layer as it is (zero diagonals beyond a box face, the owners' across a block
/// face once exchanged).
/// Rows below first_row are left as they are.
template <class ExecSpace, class MemSpace, class S>
void compute_solid_shares(const ExecSpace& exec, const PoissonStencil<MemSpace, S>& A,
                          int first_row = 0) {
  const kernels::mac::MacGrid g = A.grid;
  const auto active = A.inverse_diag;
  const auto solid = A.solid;
  const auto share = A.solid_share;
  const int sy = g.stride_y(), sz = g.stride_z();
  Kokkos::parallel_for(
      "amphora::mac::compute_solid_shares",
      Kokkos::MDRangePolicy<ExecSpace, Kokkos::Rank<3>>(
          exec, {0, math::clamp(first_row, 0, g.ny), 0}, {g.nz, g.ny, g.nx}),
      KOKKOS_LAMBDA(int k, int j, int i) {
        const int c = g.index(i, j, k);
        int n = 0;
        if (solid(c)) {
          const int offsets[6] = {-1, 1, -sy, sy, -sz, sz};
          for (int f = 0; f < 6; ++f) n += active(c + offsets[f]) != 0;
        }
        share(c) = n > 0 ? 1.0 / n : 0.0;
      });
}

/// The matrix of a grid's fluid cells: conductance 1 between fluid cells, 1/theta towards air
/// (phi from the level set; an empty phi puts the interface at the air cell's centre, theta =
/// 1), Dirichlet p = 0 on open box faces (theta = 1/2), nothing at walls and solids. Across a
/// `neighbour` face the ghost cells (type and phi filled by a halo exchange) are treated as
/// interior; the conductances of the ghost cells' own + faces (towards this block's first layer)
/// are then filled by exchanging cx/cy/cz.
///
/// Into A (allocated on g; its ghost entries as an earlier build and exchange left them), the
/// rows from first_row up: every interior cell of them written (zero off the fluid). The rows
/// below keep what A holds, which must be what a build would give there: a caller passes a row
/// below which nothing that the stencil reads has changed since A was built (the water module
/// on tall cells: the row under the lowest band, below which every cell is fluid or solid).
template <class ExecSpace, class MemSpace, class Types, class Phi>
void build_poisson_stencil(const ExecSpace& exec, const kernels::mac::MacGrid& g, const Types& type,
                           const Phi& phi, const kernels::mac::MacBoxBoundaries& box,
                           PoissonStencil<MemSpace>& A, int first_row) {
  A.box = box;
  const auto d = A.diag, inv = A.inverse_diag;
  const auto cx = A.cx, cy = A.cy, cz = A.cz;
  const auto solid = A.solid;
  const auto free_rows = A.surface_free_rows;
  const bool has_phi = phi.extent(0) > 0;
  Kokkos::Array<bool, 6> open_face, neighbour_face;
  for (int f = 0; f < 6; ++f) {
    open_face[f] = box[f] == kernels::mac::MacBoundary::open;
    neighbour_face[f] = box[f] == kernels::mac::MacBoundary::neighbour;
  }
  using kernels::mac::MacCellType;
  // One work item per x-row, x fastest inside it; the box faces are tested once per row for y
  // and z. An MDRange over the cells, testing every neighbour against the box, took three times
  // as long on the host (3.6 m pool, 20 builds: 0.18-0.20 s against 0.062-0.068 s).
  const int sy = g.stride_y(), sz = g.stride_z();
  const int j0 = math::clamp(first_row, 0, g.ny), rows = g.ny - j0;
  Kokkos::parallel_for(
      "amphora::mac::build_poisson_stencil", RangePolicy<ExecSpace>(exec, 0, rows * g.nz),
      KOKKOS_LAMBDA(int row) {
        const int j = j0 + row % rows, k = row / rows;
        // per direction -x, +x, -y, +y, -z, +z: the neighbour lies beyond a box face (not
        // another block's), and that face is open
        bool beyond[6] = {false, false, j == 0, j + 1 == g.ny, k == 0, k + 1 == g.nz};
        for (int f = 2; f < 6; ++f) beyond[f] = beyond[f] && !neighbour_face[f];
        const int offset[6] = {-1, 1, -sy, sy, -sz, sz};
        const int first = g.index(0, j, k);
        bool surface = false;  // some cell of the row has a free-surface or open-face term
        for (int i = 0; i < g.nx; ++i) {
          const int c = first + i;
          const MacCellType t = type(c);
          solid(c) = t == MacCellType::solid;
          if (t != MacCellType::fluid) {
            cx(c) = cy(c) = cz(c) = 0.0f;
            d(c) = inv(c) = 0.0;
            continue;
          }
          beyond[0] = i == 0 && !neighbour_face[0], beyond[1] = i + 1 == g.nx && !neighbour_face[1];
          double diag = 0.0;
          float conductance[6];
          for (int f = 0; f < 6; ++f) {
            conductance[f] = 0.0f;
            if (beyond[f]) {
              if (open_face[f]) diag += 2.0, surface = true;  // p = 0 on the box face, h/2 away
              continue;
            }
            const int n = c + offset[f];
            const MacCellType tn = type(n);
            if (tn == MacCellType::fluid) {
              conductance[f] = 1.0f;
              diag += 1.0;
            } else if (tn == MacCellType::air) {
              diag += has_phi ? ghost_fluid_weight(phi(c), phi(n)) : 1.0;
              surface = true;
            }
          }
          cx(c) = conductance[1], cy(c) = conductance[3], cz(c) = conductance[5];
          d(c) = diag;
          inv(c) = diag > 0.0 ? 1.0 / diag : 0.0;
        }
        free_rows(x_row(g, j, k)) = surface ? 0 : 1;
      });
  A.unit_fluid_faces = true;
  A.full_face = 1.0;
  if (has_phi) {  // whole, ghost layers included (the rows below first_row hold what they held)
    if (A.phi.extent(0) != static_cast<std::size_t>(g.padded_size()))
      A.phi = Kokkos::View<double*, MemSpace>("amphora::mac::phi", g.padded_size());
    Kokkos::deep_copy(exec, A.phi, phi);
  } else {
    A.phi = {};
  }
  A.any_solid = count_solid(exec, A) > 0;
  // a solid cell's share reads the cells beside it: from the row under the first rebuilt one
  compute_solid_shares(exec, A, j0 - 1);
}

/// A new stencil, every row built.
template <class ExecSpace, class MemSpace, class Types, class Phi>
PoissonStencil<MemSpace> build_poisson_stencil(const ExecSpace& exec,
                                               const kernels::mac::MacGrid& g, const Types& type,
                                               const Phi& phi,
                                               const kernels::mac::MacBoxBoundaries& box) {
  PoissonStencil<MemSpace> A(g);
  build_poisson_stencil(exec, g, type, phi, box, A, 0);
  return A;
}

/// A deep copy of A in another memory space (setup: host assembly, device solves).
template <class DstMemSpace, class MemSpace, class S>
PoissonStencil<DstMemSpace, S> copy_stencil(const PoissonStencil<MemSpace, S>& A) {
  PoissonStencil<DstMemSpace, S> B;
  B.grid = A.grid;
  B.box = A.box;
  B.any_solid = A.any_solid;
  auto copy = [](const auto& v) {
    using V = std::decay_t<decltype(v)>;
    Kokkos::View<typename V::non_const_value_type*, DstMemSpace> w(
        Kokkos::view_alloc(Kokkos::WithoutInitializing, v.label()), v.extent(0));
    Kokkos::deep_copy(w, v);
    return w;
  };
  B.diag = copy(A.diag), B.inverse_diag = copy(A.inverse_diag);
  B.cx = copy(A.cx), B.cy = copy(A.cy), B.cz = copy(A.cz);
  B.solid = copy(A.solid);
  B.solid_share = copy(A.solid_share);
  B.surface_free_rows = copy(A.surface_free_rows);
  B.unit_fluid_faces = A.unit_fluid_faces;
  if (A.phi.extent(0) > 0) B.phi = copy(A.phi);
  B.full_face = A.full_face;
  return B;
}

/// A readable on the host: A itself where its memory is host-accessible (no copy: the tall-cell
/// setup reads it every sub-step), else a host copy. Read-only use.
template <class MemSpace, class S>
PoissonStencil<HostMemSpace, S> host_stencil(const PoissonStencil<MemSpace, S>& A) {
  if constexpr (std::is_same_v<MemSpace, HostMemSpace>)
    return A;
  else
    return copy_stencil<HostMemSpace>(A);
}

/// The same matrix with d and 1/d in another precision.
template <class Scalar, class ExecSpace, class MemSpace, class S>
PoissonStencil<MemSpace, Scalar> convert_stencil(const ExecSpace& exec,
                                                 const PoissonStencil<MemSpace, S>& A) {
  PoissonStencil<MemSpace, Scalar> B;
  B.grid = A.grid;
  B.box = A.box;
  B.cx = A.cx, B.cy = A.cy, B.cz = A.cz;  // float already: shared
  B.solid = A.solid;
  B.solid_share = A.solid_share;
  B.any_solid = A.any_solid;
  B.surface_free_rows = A.surface_free_rows;
  B.unit_fluid_faces = A.unit_fluid_faces;
  B.diag = Kokkos::View<Scalar*, MemSpace>("amphora::mac::diag", A.diag.extent(0));
  B.inverse_diag = Kokkos::View<Scalar*, MemSpace>("amphora::mac::inverse_diag", A.diag.extent(0));
  const auto d = A.diag, inv = A.inverse_diag;
  const auto bd = B.diag, binv = B.inverse_diag;
  Kokkos::parallel_for(
      "amphora::mac::convert_stencil",
      RangePolicy<ExecSpace>(exec, 0, static_cast<int>(d.extent(0))), KOKKOS_LAMBDA(int c) {
        bd(c) = static_cast<Scalar>(d(c));
        binv(c) = static_cast<Scalar>(inv(c));
      });
  return B;
}

}  // namespace amphora::kernels::mac
