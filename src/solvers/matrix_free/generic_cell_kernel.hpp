#pragma once
// The generic fallback of the matrix-free operators: mass and Laplace (scalar or blocked
// components) for any degree and number of quadrature points the compiled table lacks, by the
// same sum factorisation with run-time sizes, one cell at a time, geometry from the node
// coordinates (isoparametric, as GeometryMode::on_the_fly). Slower than the compiled kernels
// (no unrolling, no SIMD across cells) and meant for what they do not cover, e.g. a rule with
// degree + 3 points. Sizes up to n_p <= max_nodes_1d, n_q <= max_points_1d. One team per cell
// batch shares each sweep; its arrays are team scratch (Work), so a GPU launch needs no
// per-thread arrays sized for the largest degree.
#include <Kokkos_Core.hpp>

#include "kernels/host_vector.hpp"
#include "kernels/sumfac/point_geometry.hpp"
#include "kernels/sumfac/quadrature_1d.hpp"
#include "kernels/sumfac/qk_lattice.hpp"
#include "solvers/matrix_free/cell_operator_kernel.hpp"

namespace amphora::solvers {

template <int dim, class ExecSpace>
struct GenericCellKernel {
  static constexpr int max_nodes_1d = 9, max_points_1d = 12;
  using Mem = typename ExecSpace::memory_space;
  using Team = typename Kokkos::TeamPolicy<ExecSpace>::member_type;
  using DoubleScratch =
      Kokkos::View<double*, typename ExecSpace::scratch_memory_space, Kokkos::MemoryUnmanaged>;
  using LongScratch =
      Kokkos::View<long*, typename ExecSpace::scratch_memory_space, Kokkos::MemoryUnmanaged>;

  sumfac::QkLattice<dim> lattice;
  OperatorKind kind = OperatorKind::laplace;
  int n_p = 2, n_q = 2;
  Kokkos::View<const double*, Mem> values, derivatives;  // [q * n_p + i] at the points
  Kokkos::View<const double*, Mem> weights;              // n_q, sum 1 on [0, 1]
  Kokkos::View<const double*, Mem> coordinates;          // QkSpace::coordinates()

  KOKKOS_INLINE_FUNCTION int n_cell_dofs() const { return power(n_p); }
  /// Length of a point tensor, and of every intermediate of a sweep: max(n_p, n_q)^dim.
  KOKKOS_INLINE_FUNCTION int tensor_size() const { return power(n_p < n_q ? n_q : n_p); }
  KOKKOS_INLINE_FUNCTION static int power(int n) { return dim == 3 ? n * n * n : n * n; }

  /// A team's working arrays: the cell's node coordinates X [d * n_cell_dofs + i], its DoF
  /// numbers (-1 where constrained), nodal in/out vectors u, y, column and the sweep scratch s.
  /// They live in level-1 team scratch, sized for this n_p and n_q: in 3D with n_p = 9, n_q = 12
  /// about 200 KB, far more than a GPU thread's registers or local memory should hold.
  struct Work {
    double *X, *u, *y, *column, *s;
    long* dof;
  };
  KOKKOS_INLINE_FUNCTION int work_doubles() const {
    return (dim + 3) * n_cell_dofs() + (1 + dim + dim * dim) * tensor_size();
  }
  std::size_t scratch_bytes() const {
    return DoubleScratch::shmem_size(work_doubles()) + LongScratch::shmem_size(n_cell_dofs());
  }
  KOKKOS_INLINE_FUNCTION Work work(const Team& team) const {
    const int nd = n_cell_dofs();
    DoubleScratch d(team.team_scratch(1), work_doubles());
    LongScratch l(team.team_scratch(1), nd);
    double* p = d.data();
    return Work{p,       p + dim * nd, p + (dim + 1) * nd, p + (dim + 2) * nd, p + (dim + 3) * nd,
                l.data()};
  }

  /// out = M (or M^T) applied along direction d of the tensor `in` with extents ext (x
  /// fastest); M is n_q x n_p (row q); ext[d] goes from n_p to n_q (or back with transpose).
  /// The team shares the output lines.
  KOKKOS_INLINE_FUNCTION void sweep(const Team& team, const double* M, bool transpose, int d,
                                    int* ext, const double* in, double* out) const {
    const int from = ext[d], to = transpose ? n_p : n_q;
    int before = 1, after = 1;
    for (int e = 0; e < d; ++e) before *= ext[e];
    for (int e = d + 1; e < dim; ++e) after *= ext[e];
    const int np = n_p;
    Kokkos::parallel_for(Kokkos::TeamThreadRange(team, after * to), [&](int m) {
      const int r = m % to, a = m / to;
      const double* i = in + a * from * before;
      for (int b = 0; b < before; ++b) {
        double s = 0.0;
        for (int c = 0; c < from; ++c)
          s += (transpose ? M[c * np + r] : M[r * np + c]) * i[c * before + b];
        out[m * before + b] = s;
      }
    });
    team.team_barrier();
    ext[d] = to;
  }

  /// The tensor of nodal values u mapped to the points, with the derivative matrix in
  /// direction `deriv` (-1: none), into out; tmp is scratch of tensor_size().
  KOKKOS_INLINE_FUNCTION void evaluate(const Team& team, const double* u, int deriv, double* out,
                                       double* tmp) const {
    int ext[3] = {n_p, n_p, n_p};
    const double* in = u;
    double* bufs[2] = {dim % 2 == 1 ? out : tmp, dim % 2 == 1 ? tmp : out};
    for (int d = 0; d < dim; ++d) {
      sweep(team, d == deriv ? derivatives.data() : values.data(), false, d, ext, in, bufs[d % 2]);
      in = bufs[d % 2];
    }
  }
  /// u += the transpose of evaluate() applied to v (v and tmp are overwritten).
  KOKKOS_INLINE_FUNCTION void integrate_add(const Team& team, double* v, int deriv, double* u,
                                            double* tmp) const {
    int ext[3] = {n_q, n_q, n_q};
    double* in = v;
    double* out = tmp;
    for (int d = 0; d < dim; ++d) {
      sweep(team, d == deriv ? derivatives.data() : values.data(), true, d, ext, in, out);
      double* t = in;
      in = out;
      out = t;
    }
    const double* sum = in;
    Kokkos::parallel_for(Kokkos::TeamThreadRange(team, n_cell_dofs()),
                         [&](int i) { u[i] += sum[i]; });
    team.team_barrier();
  }

  /// y = A_cell u for the cell with node coordinates X [d * n_cell_dofs + i]; s: the sweep
  /// scratch of Work.
  KOKKOS_INLINE_FUNCTION void apply_cell(const Team& team, const double* X, const double* u,
                                         double* y, double* s) const {
    const int stride = tensor_size();
    double* tmp = s;
    double* grad = s + stride;          // dim blocks
    double* geo = grad + dim * stride;  // dim * dim blocks: J[a][b] = d x_a / d xi_b
    const int nq = power(n_q), nd = n_cell_dofs();
    Kokkos::parallel_for(Kokkos::TeamThreadRange(team, nd), [&](int i) { y[i] = 0.0; });
    for (int a = 0; a < dim; ++a)
      for (int b = 0; b < dim; ++b)
        evaluate(team, X + a * nd, b, geo + (a * dim + b) * stride, tmp);
    auto jacobian = [&](int q, double* J) {
      for (int e = 0; e < dim * dim; ++e) J[e] = geo[e * stride + q];
    };
    if (kind == OperatorKind::mass) {
      evaluate(team, u, -1, grad, tmp);
      Kokkos::parallel_for(Kokkos::TeamThreadRange(team, nq), [&](int q) {
        double J[dim * dim];
        jacobian(q, J);
        grad[q] *= point_weight(q) * sumfac::determinant<dim>(J);
      });
      team.team_barrier();
      integrate_add(team, grad, -1, y, tmp);
      return;
    }
    for (int b = 0; b < dim; ++b) evaluate(team, u, b, grad + b * stride, tmp);
    Kokkos::parallel_for(Kokkos::TeamThreadRange(team, nq), [&](int q) {
      // reference flux G grad_xi u, G = w det J J^-1 J^-T (point_geometry.hpp)
      double J[dim * dim], G[dim * (dim + 1) / 2], g[dim];
      jacobian(q, J);
      sumfac::laplace_metric<dim>(J, point_weight(q), G);
      for (int b = 0; b < dim; ++b) g[b] = grad[b * stride + q];
      for (int a2 = 0; a2 < dim; ++a2) {
        double f = 0.0;
        for (int b = 0; b < dim; ++b) f += G[sumfac::sym_index<dim>(a2, b)] * g[b];
        grad[a2 * stride + q] = f;
      }
    });
    team.team_barrier();
    for (int b = 0; b < dim; ++b) integrate_add(team, grad + b * stride, b, y, tmp);
  }

  /// The column j of A_cell into w.column (w.u is overwritten).
  KOKKOS_INLINE_FUNCTION void element_column(const Team& team, const Work& w, int j) const {
    Kokkos::parallel_for(Kokkos::TeamThreadRange(team, n_cell_dofs()),
                         [&](int i) { w.u[i] = i == j ? 1.0 : 0.0; });
    team.team_barrier();
    apply_cell(team, w.X, w.u, w.column, w.s);
  }

  /// Adds A x (mode 0) or diag(A) (mode 1) of the cells of batches b0 .. b1 - 1, each of comps
  /// components of n DoFs, into out; atomically where batches running at once may share nodes.
  template <bool atomic, class XView>
  KOKKOS_INLINE_FUNCTION void add_batches(const Team& team, int b0, int b1, const XView& x,
                                          double* out, long n, int comps, int mode) const {
    const Work w = work(team);
    for (int b = b0; b < b1; ++b)
      for (int lane = 0, lanes = lattice.active_lanes(b); lane < lanes; ++lane) {
        int c[3] = {0, 0, 0};
        lattice.batch_cell(b, c);
        c[0] += lane;
        add_cell<atomic>(team, w, c, x, out, n, comps, mode);
      }
  }

  /// add_batches() for the cell at lattice cell coordinates c.
  template <bool atomic, class XView>
  KOKKOS_INLINE_FUNCTION void add_cell(const Team& team, const Work& w, const int* c,
                                       const XView& x, double* out, long n, int comps,
                                       int mode) const {
    const int nd = n_cell_dofs();
    cell_setup(team, c, w.X, w.dof);
    for (int comp = 0; comp < comps; ++comp) {
      double* dst = out + comp * n;
      if (mode == 0) {
        Kokkos::parallel_for(Kokkos::TeamThreadRange(team, nd),
                             [&](int i) { w.u[i] = w.dof[i] < 0 ? 0.0 : x(comp * n + w.dof[i]); });
        team.team_barrier();
        apply_cell(team, w.X, w.u, w.y, w.s);
      } else {
        for (int j = 0; j < nd; ++j) {  // the diagonal: unit vectors
          element_column(team, w, j);
          Kokkos::single(Kokkos::PerTeam(team), [&]() { w.y[j] = w.column[j]; });
        }
        team.team_barrier();
      }
      Kokkos::parallel_for(Kokkos::TeamThreadRange(team, nd), [&](int i) {
        if (w.dof[i] < 0) return;
        if constexpr (atomic)
          Kokkos::atomic_add(dst + w.dof[i], w.y[i]);
        else
          dst[w.dof[i]] += w.y[i];
      });
      team.team_barrier();
    }
  }

  KOKKOS_INLINE_FUNCTION double point_weight(int q) const {
    double w = 1.0;
    for (int d = 0; d < dim; ++d, q /= n_q) w *= weights(q % n_q);
    return w;
  }

  /// The cell's node coordinates into X [d * n_cell_dofs + i], its DoF numbers into dof (-1
  /// where constrained).
  KOKKOS_INLINE_FUNCTION void cell_setup(const Team& team, const int* c, double* X,
                                         long* dof) const {
    const int nd = n_cell_dofs();
    const long n_nodes = lattice.n_nodes();
    Kokkos::parallel_for(Kokkos::TeamThreadRange(team, nd), [&](int i) {
      int node[3] = {0, 0, 0};
      cell_node(c, i, node);
      const long idx = lattice.node_index(node);
      for (int d = 0; d < dim; ++d) X[d * nd + i] = coordinates(d * n_nodes + idx);
      dof[i] = lattice.constrained(node) ? -1 : lattice.dof_index(node);
    });
    team.team_barrier();
  }

  /// Lattice node of local node i of the cell at cell coordinates c.
  KOKKOS_INLINE_FUNCTION void cell_node(const int* c, int i, int* node) const {
    for (int d = 0; d < dim; ++d, i /= n_p) node[d] = c[d] * lattice.degree + i % n_p;
  }
};

/// The kernel for degree `degree` on `lattice` with node coordinates `coordinates`
/// (QkSpace::coordinates()) and n_q points of `rule` per direction; sizes are checked by the
/// caller.
template <int dim, class ExecSpace>
GenericCellKernel<dim, ExecSpace> make_generic_cell_kernel(
    const sumfac::QkLattice<dim>& lattice,
    const Kokkos::View<const double*, typename ExecSpace::memory_space>& coordinates,
    OperatorKind kind, int degree, int n_q, sumfac::QuadratureKind rule_kind) {
  using Mem = typename ExecSpace::memory_space;
  const auto nodes = sumfac::gauss_lobatto(degree + 1).points;
  const auto rule = rule_kind == sumfac::QuadratureKind::gauss_lobatto ? sumfac::gauss_lobatto(n_q)
                                                                       : sumfac::gauss(n_q);
  GenericCellKernel<dim, ExecSpace> g;
  g.lattice = lattice;
  g.kind = kind;
  g.n_p = degree + 1;
  g.n_q = n_q;
  g.values = to_view<Mem>(sumfac::lagrange_values(nodes, rule.points), "amphora::generic::values");
  g.derivatives = to_view<Mem>(sumfac::lagrange_derivatives(nodes, rule.points),
                               "amphora::generic::derivatives");
  g.weights = to_view<Mem>(rule.weights, "amphora::generic::weights");
  g.coordinates = coordinates;
  return g;
}

}  // namespace amphora::solvers
