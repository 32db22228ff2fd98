#pragma once
// The cell-batch kernel behind every matrix-free operator: gather a batch's nodal values,
// evaluate at quadrature points, apply the point-wise physics, integrate, scatter-add. One
// template serves every (dim, n_p, n_q); MatrixFreeOperator picks the instance from a table.
//
// Concurrent scatter-adds into shared nodes are avoided, not locked, on host spaces: a batch's
// lanes are consecutive cells of one row (one thread adds them in order), and blocks of
// consecutive slabs of cells (a slab: a layer of cells along the last direction) are the
// parallel items, each run in order by one thread, in two colours (three for an odd periodic
// count) so no two concurrent blocks share a node. Sums are then formed in an order that does
// not depend on the thread count. Device spaces use atomics instead.
#include <type_traits>

#include <Kokkos_Core.hpp>

#include "kernels/spaces.hpp"
#include "kernels/sumfac/batch_dof_access.hpp"
#include "kernels/sumfac/row_touch.hpp"
#include "kernels/sumfac/point_geometry.hpp"
#include "kernels/sumfac/qk_lattice.hpp"
#include "kernels/sumfac/simd.hpp"
#include "kernels/sumfac/tensor_product_evaluator.hpp"

namespace amphora::solvers {

enum class OperatorKind { mass, laplace, convection };

/// How the geometry reaches the quadrature points:
///  cartesian   axis-aligned box cells: dim numbers per cell
///  affine      parallelepipeds: one metric per cell
///  stored      the metric at every quadrature point (any cells; most memory traffic)
///  on_the_fly  recomputed from the node coordinates at each application (most flops)
enum class GeometryMode { cartesian, affine, stored, on_the_fly };

template <int dim>
KOKKOS_INLINE_FUNCTION constexpr int n_point_coefficients(OperatorKind kind) {
  return kind == OperatorKind::mass      ? 1
         : kind == OperatorKind::laplace ? sumfac::n_symmetric<dim>
                                         : dim;
}

template <int dim, int n_p, int n_q, class ExecSpace>
struct CellOperatorKernel : sumfac::BatchDofAccess<dim, n_p, sumfac::simd_width_v<ExecSpace>> {
  static constexpr int W = sumfac::simd_width_v<ExecSpace>;
  using Access = sumfac::BatchDofAccess<dim, n_p, W>;
  using T = sumfac::Simd<W>;
  using Access::batch_index;
  using Access::gather;
  using Access::gather_nodes;
  using Access::gather_unconstrained;
  using Access::lattice;
  using typename Access::BatchIndex;
  using Eval = sumfac::TensorProductEvaluator<dim, n_p, n_q>;
  using memory_space = typename ExecSpace::memory_space;
  static constexpr int n_dofs = Eval::n_dofs;
  static constexpr int n_points = Eval::n_points;
  static constexpr int n_jac = dim * dim;

  sumfac::ShapeData<n_p, n_q> shape;
  OperatorKind kind = OperatorKind::laplace;
  GeometryMode mode = GeometryMode::stored;
  int n_coef = 1;
  Kokkos::View<const T*, memory_space> batch_coef;  ///< [batch][coef] (cartesian, affine)
  /// Entries between batches in batch_coef: n_coef, or 0 where every cell has the same
  /// coefficients and batch_coef holds them once.
  long batch_coef_stride = 0;
  Kokkos::View<const T*, memory_space> point_coef;        ///< [batch][coef][point] (stored)
  Kokkos::View<const double*, memory_space> coordinates;  ///< node lattice, blocked
  /// Coefficient a(x) (Laplace) or velocity b(x) (convection, dim blocked components) as a Q_k
  /// field; empty: a = 1.
  Kokkos::View<const double*, memory_space> field;

  /// Scratch of one batch. Allocated on the stack of the calling thread.
  struct Scratch {
    T v[n_points];
    T grad[dim * n_points];
    T tmp[Eval::n_scratch];
    T jac[n_jac * n_points];  ///< Jacobians, then (in place) the point coefficients
    T nodal[dim * n_dofs];
  };

  // --- geometry ---------------------------------------------------------------------------
  /// The point coefficients of batch b into s.jac ([coef][point]), from the node coordinates.
  KOKKOS_INLINE_FUNCTION void point_coefficients(int b, Scratch& s) const {
    const long n_nodes = lattice.n_nodes();
    for (int a = 0; a < dim; ++a) {
      gather_nodes(coordinates.data() + a * n_nodes, b, s.nodal);
      Eval::values(shape, s.nodal, s.v, s.tmp);
      Eval::gradients(shape, s.v, s.jac + a * dim * n_points);
    }
    // Field values at the points, into s.grad (free until the operator runs).
    const bool has_field = field.extent(0) > 0;
    if (has_field) {
      const int comps = kind == OperatorKind::convection ? dim : 1;
      const long n = lattice.n_dofs();
      for (int c = 0; c < comps; ++c) {
        gather_unconstrained(field.data() + c * n, b, s.nodal);  // a field is not constrained
        Eval::values(shape, s.nodal, s.grad + c * n_points, s.tmp);
      }
    }
    for (int q = 0; q < n_points; ++q) {
      T J[n_jac];
      for (int e = 0; e < n_jac; ++e) J[e] = s.jac[e * n_points + q];
      const T w(Eval::weight(shape, q));
      T c[dim];
      for (int a = 0; a < dim; ++a) c[a] = T(0.0);
      if (kind == OperatorKind::mass) {
        c[0] = w * sumfac::determinant<dim>(J);
      } else if (kind == OperatorKind::laplace) {
        T G[sumfac::n_symmetric<dim>];
        const T scale = has_field ? w * s.grad[q] : w;
        sumfac::laplace_metric<dim>(J, scale, G);
        for (int e = 0; e < sumfac::n_symmetric<dim>; ++e) s.jac[e * n_points + q] = G[e];
        continue;
      } else {
        T vel[dim];
        for (int a = 0; a < dim; ++a) vel[a] = has_field ? s.grad[a * n_points + q] : T(0.0);
        sumfac::convection_metric<dim>(J, w, vel, c);
      }
      for (int e = 0; e < n_coef; ++e) s.jac[e * n_points + q] = c[e];
    }
  }

  // --- the operator on one batch ----------------------------------------------------------
  /// Point coefficients for batch b: a pointer to stored data, or computed into s.jac.
  KOKKOS_INLINE_FUNCTION const T* coefficients(int b, Scratch& s) const {
    if (mode == GeometryMode::stored)
      return point_coef.data() + static_cast<long>(b) * n_coef * n_points;
    if (mode == GeometryMode::on_the_fly) {
      point_coefficients(b, s);
      return s.jac;
    }
    return batch_coef.data() + b * batch_coef_stride;  // per-cell constants
  }

  /// u <- A_cell u for batch b, with coefficients `c` from coefficients().
  KOKKOS_FORCEINLINE_FUNCTION void apply_local(const T* c, T* u, Scratch& s) const {
    const bool per_cell = mode == GeometryMode::cartesian || mode == GeometryMode::affine;
    // Operators of the 1D matrices (Kronecker products and sums): no points needed.
    if (kind == OperatorKind::laplace && mode == GeometryMode::cartesian) {
      static_assert(dim * n_points >= n_dofs, "the Cartesian Laplace's scratch is s.grad");
      if constexpr (n_p == n_q)
        if (shape.collocated) return Eval::collocated_cartesian_laplace(shape, c, u, s.grad);
      return Eval::cartesian_laplace(shape, c, u, s.grad);
    }
    if (kind == OperatorKind::mass && per_cell && !shape.collocated)
      return Eval::per_cell_mass(shape, c[0], u);
    // The values at the points: in place of u where the sweeps may run in place (u is not read
    // again).
    T* const v = Eval::in_place ? u : s.v;
    Eval::values(shape, u, v, s.tmp);
    if (kind == OperatorKind::mass) {  // collocated (diagonal) or with point coefficients
      if (per_cell) {
        Eval::for_each_weighted_point(shape, [&](int q, double w) { v[q] *= T(w) * c[0]; });
      } else {
        for (int q = 0; q < n_points; ++q) v[q] *= c[q];
      }
      Eval::integrate_values(shape, v, u, s.tmp);
      return;
    }
    Eval::gradients(shape, v, s.grad);
    // The point values to integrate: where the points are the nodes (collocation) they are the
    // result itself, so they go straight into u (read no more), not through s.v.
    bool collocated = false;
    if constexpr (n_p == n_q) collocated = shape.collocated;
    T* const out = collocated ? u : s.v;
    if (kind == OperatorKind::laplace) {
      const long stride = per_cell ? 1 : n_points;  // [coef] per cell, [coef][point] stored
      for (int q = 0; q < n_points; ++q) {
        const long qc = per_cell ? 0 : q;
        const T w = per_cell ? T(Eval::weight(shape, q)) : T(1.0);
        T g[dim];
        for (int a = 0; a < dim; ++a) g[a] = s.grad[a * n_points + q];
        for (int a = 0; a < dim; ++a) {
          T f = T(0.0);
          for (int e = 0; e < dim; ++e) f += c[sumfac::sym_index<dim>(a, e) * stride + qc] * g[e];
          s.grad[a * n_points + q] = per_cell ? w * f : f;
        }
      }
      Eval::template integrate_gradients<false>(shape, s.grad, out);
    } else {  // convection: v = c . grad u
      const long stride = per_cell ? 1 : n_points;
      for (int q = 0; q < n_points; ++q) {
        const long qc = per_cell ? 0 : q;
        T f = T(0.0);
        for (int a = 0; a < dim; ++a) f += c[a * stride + qc] * s.grad[a * n_points + q];
        out[q] = per_cell ? T(Eval::weight(shape, q)) * f : f;
      }
    }
    if (!collocated) Eval::integrate_values(shape, s.v, u, s.tmp);
  }

  /// Entry e of the point coefficients at point q (per-cell modes: times the weight; the
  /// cartesian Laplace metric is diagonal).
  KOKKOS_INLINE_FUNCTION T coefficient(const T* c, int e, int q) const {
    if (mode == GeometryMode::stored || mode == GeometryMode::on_the_fly)
      return c[e * n_points + q];
    const T w(Eval::weight(shape, q));
    if (mode == GeometryMode::cartesian && kind == OperatorKind::laplace) {
      for (int a = 0; a < dim; ++a)
        if (sumfac::sym_index<dim>(a, a) == e) return w * c[a];
      return T(0.0);
    }
    return w * c[e];
  }

  /// d = the diagonal of A_cell: for each term of the bilinear form, the point coefficient
  /// integrated against products of 1D values/derivatives (ShapeData::ss_t, sd_t, dd_t).
  KOKKOS_INLINE_FUNCTION void diagonal_local(const T* c, T* d, Scratch& s) const {
    for (int i = 0; i < n_dofs; ++i) d[i] = T(0.0);
    using M = sumfac::EvenOddMatrix<n_p, n_q>;
    if (kind == OperatorKind::mass) {
      for (int q = 0; q < n_points; ++q) s.v[q] = coefficient(c, 0, q);
      const M* m[3] = {&shape.ss_t, &shape.ss_t, &shape.ss_t};
      Eval::template integrate_tensor<true>(m, s.v, d, s.tmp);
      return;
    }
    for (int a = 0; a < dim; ++a)
      for (int b = a; b < dim; ++b) {
        if (mode == GeometryMode::cartesian && a != b) continue;
        const int e = sumfac::sym_index<dim>(a, b);
        const T f(a == b ? 1.0 : 2.0);
        for (int q = 0; q < n_points; ++q) s.v[q] = f * coefficient(c, e, q);
        const M* m[3];
        for (int dd = 0; dd < dim; ++dd)
          m[dd] = (dd == a && dd == b)   ? &shape.dd_t
                  : (dd == a || dd == b) ? &shape.sd_t
                                         : &shape.ss_t;
        Eval::template integrate_tensor<true>(m, s.v, d, s.tmp);
      }
  }

  /// dst += A src on batches b0 .. b1 - 1 of one row of cells, every component. The row's part
  /// of the batch index is formed once (row_index); each batch adds its lanes' (lane_index).
  template <bool atomic>
  KOKKOS_INLINE_FUNCTION void apply_row(const double* src, double* dst, int n_components, int b0,
                                        int b1) const {
    Scratch s;
    T u[n_dofs];
    BatchIndex ix;
    int cell[3];
    lattice.batch_cell(b0, cell);
    this->row_index(cell, ix);
    const long n = lattice.n_dofs();
    const int k = lattice.degree;
    for (int b = b0; b < b1; ++b, cell[0] += lattice.width) {
      this->lane_index(cell, ix);
      const T* c = coefficients(b, s);
      // The next batch's source lines: W k entries further along the same rows, or at the end
      // of the row the first batch of the next row of the slab (its rows k node lines further
      // along direction 1; at the slab's last row, none).
      const bool next_in_row = b + 1 < b1,
                 next_row = !next_in_row && cell[1] + 1 < lattice.cells[1];
      const long shift = next_in_row ? static_cast<long>(W) * k
                                     : static_cast<long>(k) * lattice.dofs[0] - ix.start;
      for (int comp = 0; comp < n_components; ++comp) {
        gather(src + comp * n, ix, u);
        if constexpr (Access::prefetch_rows) {
          // while the batch computes: the lines its scatter will add to, and the next batch's
          this->prefetch(dst + comp * n, ix, true);
          if (next_in_row || next_row) this->prefetch(src + comp * n, ix, false, shift);
        }
        apply_local(c, u, s);
        this->template scatter_add<atomic>(dst + comp * n, ix, u);
      }
    }
  }

  /// diag += the diagonal of A_cell on batch b (unit vectors through apply_local), every component.
  template <bool atomic>
  KOKKOS_INLINE_FUNCTION void diagonal_batch(double* diag, int n_components, int b) const {
    Scratch s;
    T d[n_dofs];
    const T* c = coefficients(b, s);
    diagonal_local(c, d, s);
    const long n = lattice.n_dofs();
    BatchIndex ix;
    batch_index(b, ix);
    for (int comp = 0; comp < n_components; ++comp)
      this->template scatter_add<atomic>(diag + comp * n, ix, d);
  }

  /// Columns of A_cell (cell-local, lexicographic) of batch b: out[(j * n_dofs + i)] = A_ij.
  KOKKOS_INLINE_FUNCTION void element_matrix(int b, T* out) const {
    Scratch s;
    const T* c = coefficients(b, s);
    for (int j = 0; j < n_dofs; ++j) {
      T* u = out + j * n_dofs;
      for (int i = 0; i < n_dofs; ++i) u[i] = T(i == j ? 1.0 : 0.0);
      apply_local(c, u, s);
    }
  }
};

/// The block colouring of a lattice's slabs (see the top of this file): colours 0 and 1 take
/// alternate blocks of slabs_per_block() consecutive slabs (the last block may be short), colour
/// 2 the last block of an odd count along a periodic direction. Item i of a colour is one block.
template <int dim>
struct SlabBlockColouring {
  int slabs = 0, run = 1, blocks = 0;
  bool odd_periodic = false;
  explicit SlabBlockColouring(const sumfac::QkLattice<dim>& lattice)
      : slabs(lattice.n_slabs()),
        run(lattice.slabs_per_block()),
        blocks(lattice.n_slab_blocks()),
        odd_periodic(lattice.block_colour(lattice.n_slab_blocks() - 1) == 2) {}
  int items(int colour) const {
    const int regular = odd_periodic ? blocks - 1 : blocks;
    return colour < 2 ? (regular - colour + 1) / 2 : (odd_periodic ? 1 : 0);
  }
  KOKKOS_INLINE_FUNCTION int first_slab(int colour, int i) const {
    return (colour < 2 ? 2 * i + colour : blocks - 1) * run;
  }
  KOKKOS_INLINE_FUNCTION int end_slab(int colour, int i) const {
    const int end = first_slab(colour, i) + run;
    return end < slabs ? end : slabs;
  }
};

/// Runs body(b) for every batch b so that batches running at once share no node (see the top
/// of this file), calling first_touch(slab, row) before and last_touch(slab, row) after each
/// row of a slab's batches on host spaces (so a destination can be zeroed row by row while it
/// is in cache, and vector work done on the nodes a row reads first or writes last:
/// sumfac/row_touch.hpp). A body taking two ints is called as body(b0, b1) for the batches
/// b0 .. b1 - 1 of one row of cells instead (one batch at a time on devices), so it can form
/// what the row's batches share once.
/// Device spaces run all batches at once: body must add atomically, first_touch and last_touch
/// are not called. Returns whether they were called.
template <class ExecSpace, int dim, class FirstTouch, class Body, class LastTouch = sumfac::NoTouch>
bool for_each_batch_coloured(const ExecSpace& exec, const sumfac::QkLattice<dim>& lattice,
                             const char* label, const FirstTouch& first_touch, const Body& body,
                             const LastTouch& last_touch = {}) {
  constexpr bool host = runs_on_host_v<ExecSpace>;
  constexpr bool by_row = std::is_invocable_v<const Body&, int, int>;
  if constexpr (!host) {
    if constexpr (by_row)
      Kokkos::parallel_for(
          label, RangePolicy<ExecSpace>(exec, 0, lattice.n_batches()),
          KOKKOS_LAMBDA(int b) { body(b, b + 1); });
    else
      Kokkos::parallel_for(label, RangePolicy<ExecSpace>(exec, 0, lattice.n_batches()), body);
    return false;
  } else {
    const SlabBlockColouring<dim> colouring(lattice);
    const int per_slab = lattice.batches_per_slab();
    const int rows = lattice.rows_per_slab(), per_row = per_slab / rows;
    for (int colour = 0; colour < 3; ++colour) {
      const int items = colouring.items(colour);
      if (items <= 0) continue;
      // a host lambda: this branch runs on host spaces only (and nvcc's extended lambdas may not
      // first-capture body inside the if constexpr below)
      Kokkos::parallel_for(label, RangePolicy<ExecSpace>(exec, 0, items), [=](int i) {
        for (int slab = colouring.first_slab(colour, i); slab < colouring.end_slab(colour, i);
             ++slab)
          for (int row = 0; row < rows; ++row) {
            first_touch(slab, row);
            const int b0 = slab * per_slab + row * per_row;
            if constexpr (by_row)
              body(b0, b0 + per_row);
            else
              for (int b = b0; b < b0 + per_row; ++b) body(b);
            last_touch(slab, row);
          }
      });
    }
    return true;
  }
}

/// Runs body(team, b, b + 1) for every batch b, one team of team_size (an int or Kokkos::AUTO)
/// per batch, all at once, with scratch_bytes of level-1 team scratch per team: body must add
/// atomically. The schedule of device spaces in for_each_batch_team; on a host space with
/// team_size > 1 it shows that a body shares its work correctly.
template <class ExecSpace, int dim, class TeamSize, class Body>
void for_each_batch_team_at_once(const ExecSpace& exec, const sumfac::QkLattice<dim>& lattice,
                                 const char* label, std::size_t scratch_bytes, TeamSize team_size,
                                 const Body& body) {
  using Policy = Kokkos::TeamPolicy<ExecSpace>;
  Policy policy(exec, lattice.n_batches(), team_size);
  policy.set_scratch_size(1, Kokkos::PerTeam(scratch_bytes));
  Kokkos::parallel_for(
      label, policy, KOKKOS_LAMBDA(const typename Policy::member_type& team) {
        body(team, team.league_rank(), team.league_rank() + 1);
      });
}

/// Runs body(team, b0, b1) on the batches b0 .. b1 - 1 with one team per call and scratch_bytes
/// of level-1 team scratch per team, for bodies whose team shares each batch's work (a team's
/// scratch is taken once per call: it is not returned within it). On host spaces a team of one
/// thread takes one block of slabs, blocks coloured as above; device spaces run one team per
/// batch, all at once (for_each_batch_team_at_once), and body must add atomically.
template <class ExecSpace, int dim, class Body>
void for_each_batch_team(const ExecSpace& exec, const sumfac::QkLattice<dim>& lattice,
                         const char* label, std::size_t scratch_bytes, const Body& body) {
  using Policy = Kokkos::TeamPolicy<ExecSpace>;
  constexpr bool host = runs_on_host_v<ExecSpace>;
  if constexpr (!host) {
    for_each_batch_team_at_once(exec, lattice, label, scratch_bytes, Kokkos::AUTO, body);
  } else {
    const SlabBlockColouring<dim> colouring(lattice);
    const int per_slab = lattice.batches_per_slab();
    for (int colour = 0; colour < 3; ++colour) {
      const int items = colouring.items(colour);
      if (items <= 0) continue;
      Policy policy(exec, items, 1);
      policy.set_scratch_size(1, Kokkos::PerTeam(scratch_bytes));
      Kokkos::parallel_for(
          label, policy, KOKKOS_LAMBDA(const typename Policy::member_type& team) {
            const int i = team.league_rank();
            body(team, colouring.first_slab(colour, i) * per_slab,
                 colouring.end_slab(colour, i) * per_slab);
          });
    }
  }
}

}  // namespace amphora::solvers
