#pragma once
// The generic fallback of the matrix-free operators: scalar point functors without a field
// (point_functors.hpp: mass, constant-coefficient Laplace) for any degree and number of
// quadrature points the compiled table lacks, by the same sum factorisation with run-time
// sizes, one cell at a time, geometry from the node coordinates (isoparametric, as
// GeometryMode::on_the_fly). Slower than the compiled kernels (no unrolling, no SIMD across
// cells) and meant for what they do not cover, e.g. a rule with degree + 3 points. Sizes up to
// n_p <= max_nodes_1d, n_q <= max_points_1d. One team per cell batch shares each sweep; its
// arrays are team scratch (Work), so a GPU launch needs no per-thread arrays sized for the
// largest degree.
#include <Kokkos_Core.hpp>

#include "kernels/host_vector.hpp"
#include "kernels/sumfac/point_functors.hpp"
#include "kernels/sumfac/point_geometry.hpp"
#include "kernels/sumfac/quadrature_1d.hpp"
#include "kernels/sumfac/qk_lattice.hpp"
#include "kernels/sumfac/shape_data.hpp"

namespace amphora::kernels::sumfac {

template <int dim, class ExecSpace, class Point>
struct GenericCellKernel {
  static_assert(Point::n_components == 1, "the generic kernel takes scalar point functors");
  static constexpr int max_nodes_1d = 9, max_points_1d = 12;
  using Mem = typename ExecSpace::memory_space;
  using Team = typename Kokkos::TeamPolicy<ExecSpace>::member_type;
  using DoubleScratch =
      Kokkos::View<double*, typename ExecSpace::scratch_memory_space, Kokkos::MemoryUnmanaged>;
  using LongScratch =
      Kokkos::View<long*, typename ExecSpace::scratch_memory_space, Kokkos::MemoryUnmanaged>;

  QkLattice<dim> lattice;
  Point point;
  int n_p = 2, n_q = 2;
  Kokkos::View<const double*, Mem> values, derivatives;  // [q * n_p + i] at the points
  Kokkos::View<const double*, Mem> weights;              // n_q, sum 1 on [0, 1]
  Kokkos::View<const double*, Mem> coordinates;          // QkSpace::coordinates()

  KOKKOS_INLINE_FUNCTION int n_cell_dofs() const { return power(n_p); }
  /// Length of a point tensor, and of every intermediate of a sweep: max(n_p, n_q)^dim.
  KOKKOS_INLINE_FUNCTION int tensor_size() const { return power(n_p < n_q ? n_q : n_p); }
  KOKKOS_INLINE_FUNCTION static int power(int n) { return dim == 3 ? n * n * n : n * n; }

  /// A team's working arrays: the cell's node coordinates X [d * n_cell_dofs + i], its DoF
  /// numbers (-1 where constrained), nodal in/out vectors u, y, column and the sweep scratch s
  /// (apply_cell's tmp, values, dim gradients and dim x dim Jacobian entries).
  /// They live in level-1 team scratch, sized for this n_p and n_q: in 3D with n_p = 9, n_q = 12
  /// about 200 KB, far more than a GPU thread's registers or local memory should hold.
  struct Work {
    double *X, *u, *y, *column, *s;
    long* dof;
  };
  KOKKOS_INLINE_FUNCTION int work_doubles() const {
    return (dim + 3) * n_cell_dofs() + (2 + dim + dim * dim) * tensor_size();
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
    double* val = s + stride;
    double* grad = val + stride;        // dim blocks
    double* geo = grad + dim * stride;  // dim * dim blocks: J[a][b] = d x_a / d xi_b
    const int nq = power(n_q), nd = n_cell_dofs();
    Kokkos::parallel_for(Kokkos::TeamThreadRange(team, nd), [&](int i) { y[i] = 0.0; });
    for (int a = 0; a < dim; ++a)
      for (int b = 0; b < dim; ++b)
        evaluate(team, X + a * nd, b, geo + (a * dim + b) * stride, tmp);
    if (Point::reads_values) evaluate(team, u, -1, val, tmp);
    if (Point::reads_gradients)
      for (int b = 0; b < dim; ++b) evaluate(team, u, b, grad + b * stride, tmp);
    Kokkos::parallel_for(Kokkos::TeamThreadRange(team, nq), [&](int q) {
      double J[dim * dim], c[Point::n_coefficients], v[1] = {0.0}, g[dim], v_out[1], g_out[dim];
      for (int e = 0; e < dim * dim; ++e) J[e] = geo[e * stride + q];
      point.coefficients(J, point_weight(q), static_cast<const double*>(nullptr), c);
      if (Point::reads_values) v[0] = val[q];
      for (int b = 0; b < dim; ++b) g[b] = Point::reads_gradients ? grad[b * stride + q] : 0.0;
      point.at_point(PointCoefficients<double>{c, 1}, v, g, v_out, g_out);
      if (Point::writes_values) val[q] = v_out[0];
      if (Point::writes_gradients)
        for (int b = 0; b < dim; ++b) grad[b * stride + q] = g_out[b];
    });
    team.team_barrier();
    if (Point::writes_values) integrate_add(team, val, -1, y, tmp);
    if (Point::writes_gradients)
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
template <int dim, class ExecSpace, class Point>
GenericCellKernel<dim, ExecSpace, Point> make_generic_cell_kernel(
    const QkLattice<dim>& lattice,
    const Kokkos::View<const double*, typename ExecSpace::memory_space>& coordinates,
    const Point& point, int degree, int n_q, QuadratureKind rule_kind) {
  using Mem = typename ExecSpace::memory_space;
  const auto nodes = gauss_lobatto(degree + 1).points;
  const auto rule = rule_kind == QuadratureKind::gauss_lobatto ? gauss_lobatto(n_q) : gauss(n_q);
  GenericCellKernel<dim, ExecSpace, Point> g;
  g.lattice = lattice;
  g.point = point;
  g.n_p = degree + 1;
  g.n_q = n_q;
  g.values = to_view<Mem>(lagrange_values(nodes, rule.points), "amphora::generic::values");
  g.derivatives =
      to_view<Mem>(lagrange_derivatives(nodes, rule.points), "amphora::generic::derivatives");
  g.weights = to_view<Mem>(rule.weights, "amphora::generic::weights");
  g.coordinates = coordinates;
  return g;
}

}  // namespace amphora::kernels::sumfac
