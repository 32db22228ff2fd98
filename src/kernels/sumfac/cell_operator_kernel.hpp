#pragma once
// The cell-batch kernel behind every matrix-free operator: gather a batch's nodal values,
// evaluate them (and their gradients) at the quadrature points, apply a point functor
// (point_functors.hpp), integrate, scatter-add. One template serves every (dim, n_p, n_q) and
// point functor; the operators pick the instance from a table. Functors of the mass and
// Laplace structure take the 1D-matrix fast paths on Cartesian and affine cells.
//
// Concurrent scatter-adds into shared nodes are avoided, not locked, on host spaces: a batch's
// lanes are consecutive cells of one row (one thread adds them in order), and the slab blocks of
// batch_schedule.hpp are run coloured. Device spaces use atomics instead.
#include <Kokkos_Core.hpp>

#include "kernels/sumfac/batch_dof_access.hpp"
#include "kernels/sumfac/batch_schedule.hpp"
#include "kernels/sumfac/point_functors.hpp"
#include "kernels/sumfac/point_geometry.hpp"
#include "kernels/sumfac/qk_lattice.hpp"
#include "kernels/sumfac/simd.hpp"
#include "kernels/sumfac/tensor_product_evaluator.hpp"

namespace amphora::kernels::sumfac {

/// How the geometry reaches the quadrature points:
///  cartesian   axis-aligned box cells: dim numbers per cell
///  affine      parallelepipeds: one metric per cell
///  stored      the metric at every quadrature point (any cells; most memory traffic)
///  on_the_fly  recomputed from the node coordinates at each application (most flops)
enum class GeometryMode { cartesian, affine, stored, on_the_fly };

template <int dim, int n_p, int n_q, class ExecSpace, class Point>
struct CellOperatorKernel : BatchDofAccess<dim, n_p, simd_width_v<ExecSpace>> {
  static constexpr int W = simd_width_v<ExecSpace>;
  using Access = BatchDofAccess<dim, n_p, W>;
  using T = Simd<W>;
  using Access::batch_index;
  using Access::gather;
  using Access::gather_nodes;
  using Access::gather_unconstrained;
  using Access::lattice;
  using typename Access::BatchIndex;
  using Eval = TensorProductEvaluator<dim, n_p, n_q>;
  using memory_space = typename ExecSpace::memory_space;
  static constexpr int n_dofs = Eval::n_dofs;
  static constexpr int n_points = Eval::n_points;
  static constexpr int n_jac = dim * dim;
  static constexpr int n_comp = Point::n_components;
  static constexpr bool is_mass = Point::structure == PointStructure::mass;
  static constexpr bool is_laplace = Point::structure == PointStructure::laplace;
  /// Rows of point coefficients in Scratch::jac: the Jacobian's, or more if a functor needs.
  static constexpr int n_coef_rows = Point::n_coefficients > n_jac ? Point::n_coefficients : n_jac;
  static constexpr int n_nodal = dim > Point::n_fields ? dim : Point::n_fields;

  ShapeData<n_p, n_q> shape;
  Point point;
  GeometryMode mode = GeometryMode::stored;
  int n_coef =
      1;  ///< coefficients per point stored: Point::n_coefficients (cartesian Laplace: dim)
  Kokkos::View<const T*, memory_space> batch_coef;  ///< [batch][coef] (cartesian, affine)
  /// Entries between batches in batch_coef: n_coef, or 0 where every cell has the same
  /// coefficients and batch_coef holds them once.
  long batch_coef_stride = 0;
  Kokkos::View<const T*, memory_space> point_coef;        ///< [batch][coef][point] (stored)
  Kokkos::View<const double*, memory_space> coordinates;  ///< node lattice, blocked
  /// The functor's field (Point::n_fields blocked components) as a Q_k field; empty: none.
  Kokkos::View<const double*, memory_space> field;
  /// Components 0 .. constrained_components - 1 take the lattice's Dirichlet constraints; the
  /// rest (a pressure) are free on every face.
  int constrained_components = 1 << 20;
  /// J^-1 is constant in every cell (Cartesian or affine mesh): probed_diagonal is exact.
  bool affine_cells = false;

  /// Scratch of one batch. Allocated on the stack of the calling thread.
  struct Scratch {
    T v[n_comp * n_points];
    T grad[n_comp * dim * n_points];
    T tmp[Eval::n_scratch];
    T jac[n_coef_rows * n_points];  ///< Jacobians, then (in place) the point coefficients
    T nodal[n_nodal * n_dofs];
  };

  KOKKOS_INLINE_FUNCTION bool per_cell() const {
    return mode == GeometryMode::cartesian || mode == GeometryMode::affine;
  }

  // --- geometry ---------------------------------------------------------------------------
  /// The point coefficients of batch b into s.jac ([coef][point]), from the node coordinates.
  KOKKOS_INLINE_FUNCTION void point_coefficients(int b, Scratch& s) const {
    const long n_nodes = lattice.n_nodes();
    for (int a = 0; a < dim; ++a) {
      gather_nodes(coordinates.data() + a * n_nodes, b, s.nodal);
      Eval::values(shape, s.nodal, s.v, s.tmp);
      Eval::gradients(shape, s.v, s.jac + a * dim * n_points);
    }
    // Field values at the points, into s.grad (free until the operator runs), then the
    // reference gradients of those the functor asks for.
    constexpr int n_fg = gradient_fields_v<Point>;
    static_assert(Point::n_fields + n_fg * dim <= n_comp * dim,
                  "a functor's field values and gradients must fit in Scratch::grad");
    const bool has_field = Point::n_fields > 0 && field.extent(0) > 0;
    if (has_field) {
      const long n = lattice.n_dofs();
      for (int c = 0; c < Point::n_fields; ++c) {
        gather_unconstrained(field.data() + c * n, b, s.nodal);  // a field is not constrained
        Eval::values(shape, s.nodal, s.grad + c * n_points, s.tmp);
      }
      if constexpr (n_fg > 0)
        for (int e = 0; e < n_fg; ++e)
          Eval::gradients(shape, s.grad + (Point::gradient_field_first + e) * n_points,
                          s.grad + (Point::n_fields + e * dim) * n_points);
    }
    for (int q = 0; q < n_points; ++q) point_coefficients_at(q, has_field, s);
  }

  /// The functor's coefficients at point q from the Jacobian and fields in s, into s.jac.
  KOKKOS_INLINE_FUNCTION void point_coefficients_at(int q, bool has_field, Scratch& s) const {
    constexpr int n_fg = gradient_fields_v<Point>;
    T J[n_jac], f[Point::n_fields > 0 ? Point::n_fields : 1], c[Point::n_coefficients];
    for (int e = 0; e < n_jac; ++e) J[e] = s.jac[e * n_points + q];
    for (int e = 0; e < Point::n_fields; ++e) f[e] = has_field ? s.grad[e * n_points + q] : T(0.0);
    const T w(Eval::weight(shape, q));
    if constexpr (n_fg > 0) {
      T fg[n_fg * dim];
      for (int e = 0; e < n_fg * dim; ++e)
        fg[e] = has_field ? s.grad[(Point::n_fields + e) * n_points + q] : T(0.0);
      point.coefficients(J, w, f, fg, c);
    } else {
      point.coefficients(J, w, has_field ? f : nullptr, c);
    }
    for (int e = 0; e < Point::n_coefficients; ++e) s.jac[e * n_points + q] = c[e];
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

  /// u <- A_cell u for batch b (n_comp blocks of n_dofs), with coefficients `c` from
  /// coefficients().
  KOKKOS_FORCEINLINE_FUNCTION void apply_local(const T* c, T* u, Scratch& s) const {
    if constexpr (is_laplace) {  // Kronecker sums of the 1D matrices: no points needed
      if (mode == GeometryMode::cartesian) {
        static_assert(dim * n_points >= n_dofs, "the Cartesian Laplace's scratch is s.grad");
        if constexpr (n_p == n_q)
          if (shape.collocated) return Eval::collocated_cartesian_laplace(shape, c, u, s.grad);
        return Eval::cartesian_laplace(shape, c, u, s.grad);
      }
    }
    if constexpr (is_mass)
      apply_mass(c, u, s);
    else
      apply_points(c, u, s);
  }

  /// The mass structure: Kronecker products of the 1D mass per cell, or a diagonal at the
  /// points (collocation, stored coefficients).
  KOKKOS_FORCEINLINE_FUNCTION void apply_mass(const T* c, T* u, Scratch& s) const {
    if (per_cell() && !shape.collocated) return Eval::per_cell_mass(shape, c[0], u);
    T* const v = Eval::in_place ? u : s.v;
    Eval::values(shape, u, v, s.tmp);
    if (per_cell()) {
      Eval::for_each_weighted_point(shape, [&](int q, double w) { v[q] *= T(w) * c[0]; });
    } else {
      for (int q = 0; q < n_points; ++q) v[q] *= c[q];
    }
    Eval::integrate_values(shape, v, u, s.tmp);
  }

  /// Any functor through the points: values and gradients of every component, the functor at
  /// each point, integration against values and gradients.
  KOKKOS_FORCEINLINE_FUNCTION void apply_points(const T* c, T* u, Scratch& s) const {
    bool collocated = false;
    if constexpr (n_p == n_q) collocated = shape.collocated;
    // The values at the points: in place of u where the sweeps may run in place (u is not read
    // again); the integrands go straight into u where the points are the nodes.
    for (int comp = 0; comp < n_comp; ++comp) {
      T* const uc = u + comp * n_dofs;
      T* const v = Eval::in_place ? uc : s.v + comp * n_points;
      Eval::values(shape, uc, v, s.tmp);
      if constexpr (Point::reads_gradients)
        Eval::gradients(shape, v, s.grad + comp * dim * n_points);
    }
    const bool cell = per_cell();
    const long stride = cell ? 1 : n_points;  // [coef] per cell, [coef][point] stored
    constexpr int n_lap = laplacian_components_v<Point>;
    T lap[n_lap > 0 ? n_lap * n_points : 1];
    if constexpr (n_lap > 0)
      if (point.needs_laplacian()) laplacians(c, lap, s);
    for (int q = 0; q < n_points; ++q) {
      T val[n_comp], g[n_comp * dim], val_out[n_comp], g_out[n_comp * dim];
      for (int comp = 0; comp < n_comp; ++comp) {
        const T* v = Eval::in_place ? u + comp * n_dofs : s.v + comp * n_points;
        if constexpr (Point::reads_values) val[comp] = v[q];
        for (int a = 0; a < dim; ++a) g[comp * dim + a] = s.grad[(comp * dim + a) * n_points + q];
      }
      const PointCoefficients<T> pc{c + (cell ? 0 : q), stride};
      if constexpr (n_lap > 0) {
        T lq[n_lap];
        for (int i = 0; i < n_lap; ++i) lq[i] = lap[i * n_points + q];
        point.at_point(pc, val, g, lq, val_out, g_out);
      } else {
        point.at_point(pc, val, g, val_out, g_out);
      }
      const T w = cell ? T(Eval::weight(shape, q)) : T(1.0);
      for (int comp = 0; comp < n_comp; ++comp) {
        T* const out = collocated ? u + comp * n_dofs : s.v + comp * n_points;
        if constexpr (Point::writes_values) out[q] = cell ? w * val_out[comp] : val_out[comp];
        for (int a = 0; a < dim && Point::writes_gradients; ++a)
          s.grad[(comp * dim + a) * n_points + q] =
              cell ? w * g_out[comp * dim + a] : g_out[comp * dim + a];
      }
    }
    for (int comp = 0; comp < n_comp; ++comp) {
      T* const out = collocated ? u + comp * n_dofs : s.v + comp * n_points;
      if constexpr (Point::writes_gradients)
        Eval::template integrate_gradients<Point::writes_values>(
            shape, s.grad + comp * dim * n_points, out);
      if (!collocated) Eval::integrate_values(shape, out, u + comp * n_dofs, s.tmp);
    }
  }

  /// lap[i * n_points + q] = the physical Laplacian of component i at point q, from the
  /// reference gradients in s.grad (stored or on-the-fly coefficients): the physical gradient
  /// J^-T grad_xi u at the points, differentiated again through the points' collocation
  /// derivative (exact on affine cells; on curved ones J^-1 is interpolated at the points, as
  /// deal.II's hessians are without jacobian gradients).
  KOKKOS_INLINE_FUNCTION void laplacians(const T* c, T* lap, Scratch& s) const {
    constexpr int n_lap = laplacian_components_v<Point>;
    T G[n_points], H[dim * n_points];
    for (int q = 0; q < n_lap * n_points; ++q) lap[q] = T(0.0);
    for (int i = 0; i < n_lap; ++i)
      for (int a = 0; a < dim; ++a) {
        for (int q = 0; q < n_points; ++q) {
          const PointCoefficients<T> pc{c + q, n_points};
          T v = T(0.0);
          for (int b = 0; b < dim; ++b)
            v += s.grad[(i * dim + b) * n_points + q] * Point::inverse_jacobian(pc, b, a);
          G[q] = v;
        }
        Eval::gradients(shape, G, H);
        for (int q = 0; q < n_points; ++q) {
          const PointCoefficients<T> pc{c + q, n_points};
          for (int b = 0; b < dim; ++b)
            lap[i * n_points + q] += H[b * n_points + q] * Point::inverse_jacobian(pc, b, a);
        }
      }
  }

  /// Entry e of the point coefficients at point q (per-cell modes: times the weight; the
  /// cartesian Laplace metric is diagonal).
  KOKKOS_INLINE_FUNCTION T coefficient(const T* c, int e, int q) const {
    if (mode == GeometryMode::stored || mode == GeometryMode::on_the_fly)
      return c[e * n_points + q];
    const T w(Eval::weight(shape, q));
    if (is_laplace && mode == GeometryMode::cartesian) {
      for (int a = 0; a < dim; ++a)
        if (sym_index<dim>(a, a) == e) return w * c[a];
      return T(0.0);
    }
    return w * c[e];
  }

  /// d = the diagonal of A_cell. Mass and Laplace structure: for each term of the bilinear
  /// form, the point coefficient integrated against products of 1D values/derivatives
  /// (ShapeData::ss_t, sd_t, dd_t); other functors: probed at the points (probed_diagonal).
  KOKKOS_INLINE_FUNCTION void diagonal_local(const T* c, T* d, Scratch& s) const {
    if constexpr (!is_mass && !is_laplace) {
      probed_diagonal(c, d, s);
    } else {
      for (int i = 0; i < n_dofs; ++i) d[i] = T(0.0);
      if constexpr (is_mass)
        diagonal_term(c, -1, -1, d, s);
      else
        for (int a = 0; a < dim; ++a)
          for (int b = a; b < dim; ++b)
            if (mode != GeometryMode::cartesian || a == b) diagonal_term(c, a, b, d, s);
    }
  }

  /// d += the diagonal of the term of reference derivatives a, b (-1, -1: values) of the mass
  /// or Laplace structure.
  KOKKOS_INLINE_FUNCTION void diagonal_term(const T* c, int a, int b, T* d, Scratch& s) const {
    using M = EvenOddMatrix<n_p, n_q>;
    const int e = a < 0 ? 0 : sym_index<dim>(a, b);
    const T f(a == b ? 1.0 : 2.0);
    for (int q = 0; q < n_points; ++q) s.v[q] = f * coefficient(c, e, q);
    const M* m[3];
    for (int dd = 0; dd < dim; ++dd)
      m[dd] = (dd == a && dd == b) ? &shape.dd_t : (dd == a || dd == b) ? &shape.sd_t : &shape.ss_t;
    Eval::template integrate_tensor<true>(m, s.v, d, s.tmp);
  }

  /// The diagonal of a general functor, which is linear in what it reads of a component: for
  /// each component and each input of one basis function phi_i (its value, reference gradient
  /// and, where the functor reads Laplacians, its reference second derivatives), the functor's
  /// integrands of that component at every point (probe), each integrated against the 1D
  /// products of phi_i's factors that the input and the integrand's test function multiply.
  /// (At most (1 + dim) (1 + dim + dim (dim + 1) / 2) integrations per component, against
  /// n_comp n_dofs cell applications for unit vectors.) Exact where J^-1 is constant in each cell.
  /// On curved cells the Laplacian differentiates the interpolant of J^-1 times the gradient
  /// (laplacians()), which no 1D product reproduces: there a functor reading Laplacians takes unit
  /// vectors.
  KOKKOS_INLINE_FUNCTION void probed_diagonal(const T* c, T* d, Scratch& s) const {
    constexpr int n_lap = laplacian_components_v<Point>, n_hess = dim * (dim + 1) / 2;
    bool lap = false;
    if constexpr (n_lap > 0) lap = point.needs_laplacian();
    if (lap && !affine_cells) return diagonal_by_columns(c, d, s);
    for (int i = 0; i < n_comp * n_dofs; ++i) d[i] = T(0.0);
    for (int comp = 0; comp < n_comp; ++comp) {
      const int n_in = 1 + dim + (lap && comp < n_lap ? n_hess : 0);
      for (int in = 0; in < n_in; ++in) {
        if ((in == 0 && !Point::reads_values) || (in > 0 && !Point::reads_gradients)) continue;
        int trial[3] = {0, 0, 0};  // derivative orders of the input, per direction
        if (in > 0 && in <= dim) trial[in - 1] = 1;
        int ha = -1, hb = -1;
        if (in > dim) {
          hessian_pair(in - dim - 1, ha, hb);
          ++trial[ha], ++trial[hb];
        }
        probe(c, comp, in, ha, hb, s);
        for (int out = 0; out <= dim; ++out) {
          if ((out == 0 && !Point::writes_values) || (out > 0 && !Point::writes_gradients))
            continue;
          T* const f = out == 0 ? s.v : s.grad + (out - 1) * n_points;
          if (is_zero(f)) continue;  // the terms a Cartesian cell's J^-1 zeroes
          const EvenOddMatrix<n_p, n_q>* m[3];
          for (int dd = 0; dd < dim; ++dd) m[dd] = product(out == dd + 1 ? 1 : 0, trial[dd]);
          Eval::template integrate_tensor<true>(m, f, d + comp * n_dofs, s.tmp);
        }
      }
    }
  }

  /// The functor's integrands of component comp at every point for one input of that component
  /// (0: a unit value; 1 .. dim: a unit reference gradient; above: the unit reference second
  /// derivative d_ha d_hb, given as the Laplacian it makes through J^-1 at the point): value
  /// integrands into s.v, those of reference gradient a into s.grad + a n_points.
  KOKKOS_INLINE_FUNCTION void probe(const T* c, int comp, int in, int ha, int hb,
                                    Scratch& s) const {
    constexpr int n_lap = laplacian_components_v<Point>;
    const bool cell = per_cell();
    const long stride = cell ? 1 : n_points;
    for (int q = 0; q < n_points; ++q) {
      T val[n_comp], g[n_comp * dim], val_out[n_comp], g_out[n_comp * dim];
      for (int i = 0; i < n_comp; ++i) val[i] = T(0.0), val_out[i] = T(0.0);
      for (int i = 0; i < n_comp * dim; ++i) g[i] = T(0.0), g_out[i] = T(0.0);
      if (in == 0) val[comp] = T(1.0);
      if (in > 0 && in <= dim) g[comp * dim + in - 1] = T(1.0);
      const PointCoefficients<T> pc{c + (cell ? 0 : q), stride};
      if constexpr (n_lap > 0) {
        T lq[n_lap];
        for (int i = 0; i < n_lap; ++i) lq[i] = T(0.0);
        if (ha >= 0) {
          T h = T(0.0);
          for (int a = 0; a < dim; ++a)
            h += Point::inverse_jacobian(pc, ha, a) * Point::inverse_jacobian(pc, hb, a);
          lq[comp] = T(ha == hb ? 1.0 : 2.0) * h;
        }
        point.at_point(pc, val, g, lq, val_out, g_out);
      } else {
        point.at_point(pc, val, g, val_out, g_out);
      }
      const T w = cell ? T(Eval::weight(shape, q)) : T(1.0);
      s.v[q] = w * val_out[comp];
      for (int a = 0; a < dim; ++a) s.grad[a * n_points + q] = w * g_out[comp * dim + a];
    }
  }

  /// d = the diagonal of A_cell through unit vectors, one cell application per cell DoF.
  KOKKOS_INLINE_FUNCTION void diagonal_by_columns(const T* c, T* d, Scratch& s) const {
    T u[n_comp * n_dofs];
    for (int j = 0; j < n_comp * n_dofs; ++j) {
      for (int i = 0; i < n_comp * n_dofs; ++i) u[i] = T(i == j ? 1.0 : 0.0);
      apply_local(c, u, s);
      d[j] = u[j];
    }
  }

  /// The p-th reference second derivative (ha <= hb) in the order (0,0), (0,1), ..., (1,1), ...
  KOKKOS_INLINE_FUNCTION static void hessian_pair(int p, int& ha, int& hb) {
    for (int a = 0; a < dim; ++a)
      for (int b = a; b < dim; ++b, --p)
        if (p == 0) {
          ha = a, hb = b;
          return;
        }
  }

  /// The 1D products phi_i^(test) phi_i^(trial) at the points, transposed (test: 0, 1; trial:
  /// 0, 1, 2 derivatives).
  KOKKOS_INLINE_FUNCTION const EvenOddMatrix<n_p, n_q>* product(int test, int trial) const {
    if (test == 0) return trial == 0 ? &shape.ss_t : trial == 1 ? &shape.sd_t : &shape.sh_t;
    return trial == 0 ? &shape.sd_t : trial == 1 ? &shape.dd_t : &shape.dh_t;
  }

  /// Every lane of f is 0 at every point (the integration would add nothing).
  KOKKOS_INLINE_FUNCTION static bool is_zero(const T* f) {
    for (int q = 0; q < n_points; ++q)
      for (int l = 0; l < W; ++l)
        if (f[q][l] != 0.0) return false;
    return true;
  }

  /// dst += A src on batches b0 .. b1 - 1 of one row of cells; n_components blocked copies
  /// (each n_comp components) of the operator. The row's part of the batch index is formed
  /// once (row_index); each batch adds its lanes' (lane_index).
  template <bool atomic>
  KOKKOS_INLINE_FUNCTION void apply_row(const double* src, double* dst, int n_components, int b0,
                                        int b1) const {
    Scratch s;
    T u[n_comp * n_dofs];
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
      for (int block = 0; block < n_components; block += n_comp) {
        for (int comp = 0; comp < n_comp; ++comp)
          gather(src + (block + comp) * n, ix, u + comp * n_dofs,
                 block + comp < constrained_components);
        if constexpr (Access::prefetch_rows) {
          // while the batch computes: the lines its scatter will add to, and the next batch's
          this->prefetch(dst + block * n, ix, true);
          if (next_in_row || next_row) this->prefetch(src + block * n, ix, false, shift);
        }
        apply_local(c, u, s);
        for (int comp = 0; comp < n_comp; ++comp)
          this->template scatter_add<atomic>(dst + (block + comp) * n, ix, u + comp * n_dofs,
                                             block + comp < constrained_components);
      }
    }
  }

  /// diag += the diagonal of A_cell on batch b, every component.
  template <bool atomic>
  KOKKOS_INLINE_FUNCTION void diagonal_batch(double* diag, int n_components, int b) const {
    Scratch s;
    T d[n_comp * n_dofs];
    const T* c = coefficients(b, s);
    diagonal_local(c, d, s);
    const long n = lattice.n_dofs();
    BatchIndex ix;
    batch_index(b, ix);
    for (int block = 0; block < n_components; block += n_comp)
      for (int comp = 0; comp < n_comp; ++comp)
        this->template scatter_add<atomic>(diag + (block + comp) * n, ix, d + comp * n_dofs,
                                           block + comp < constrained_components);
  }

  /// Columns of A_cell (cell-local, component-blocked, lexicographic) of batch b:
  /// out[j * m + i] = A_ij, m = n_comp n_dofs.
  KOKKOS_INLINE_FUNCTION void element_matrix(int b, T* out) const {
    constexpr int m = n_comp * n_dofs;
    Scratch s;
    const T* c = coefficients(b, s);
    for (int j = 0; j < m; ++j) {
      T* u = out + j * m;
      for (int i = 0; i < m; ++i) u[i] = T(i == j ? 1.0 : 0.0);
      apply_local(c, u, s);
    }
  }
};

}  // namespace amphora::kernels::sumfac
