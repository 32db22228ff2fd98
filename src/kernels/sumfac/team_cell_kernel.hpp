#pragma once
// A team schedule of the matrix-free cell loop, meant for GPUs: the threads of a team share the
// sum-factorisation sweeps of a few cells through team scratch, one output entry or quadrature
// point per thread, where CellOperatorKernel gives each thread a whole cell and its arrays (on a
// GPU, kilobytes of local memory per thread). Scalar point functors of the mass and Laplace
// structure with their coefficients stored at the points (GeometryMode::stored); gradients by
// the collocation derivative at the points, as in CellOperatorKernel. The layout (a thread per
// point, the 1D matrices in shared memory) follows the GPU kernels of Swirydowicz et al., Int.
// J. High Perform. Comput. Appl. 33(4), 2019, and Kronbichler & Ljungkvist, ACM Trans. Parallel
// Comput. 6(1), 2019. Sums are added atomically on every space.
#include <cstddef>

#include <Kokkos_Core.hpp>

#include "kernels/sumfac/point_functors.hpp"
#include "kernels/sumfac/qk_lattice.hpp"
#include "kernels/sumfac/shape_data.hpp"
#include "kernels/sumfac/simd.hpp"
#include "kernels/sumfac/tensor_product_evaluator.hpp"

namespace amphora::kernels::sumfac {

template <int dim, int n_p, int n_q, class ExecSpace, class Point>
struct TeamCellKernel {
  static_assert(Point::n_components == 1 && Point::structure != PointStructure::general,
                "the team kernel takes scalar functors of the mass or Laplace structure");
  using Mem = typename ExecSpace::memory_space;
  using Policy = Kokkos::TeamPolicy<ExecSpace>;
  using Team = typename Policy::member_type;
  using Scratch =
      Kokkos::View<double*, typename ExecSpace::scratch_memory_space, Kokkos::MemoryUnmanaged>;
  static constexpr int n_dofs = ipow(n_p, dim), n_points = ipow(n_q, dim);
  /// Lanes of the batches the stored coefficients are laid out in (CellOperatorKernel's W).
  static constexpr int W = simd_width_v<ExecSpace>;
  static constexpr bool grads = Point::reads_gradients || Point::writes_gradients;
  /// Point-sized work arrays of a cell besides its values at the points: the gradients, the
  /// values written, and at least two for the interpolation sweeps (which use the first two).
  static constexpr int n_work_raw = (grads ? dim : 0) + (Point::writes_values ? 1 : 0);
  static constexpr int n_work = n_work_raw < 2 ? 2 : n_work_raw;
  static constexpr int per_cell = n_dofs + (1 + n_work) * n_points;
  static constexpr int n_matrix = n_q * n_p + n_q * n_q;

  QkLattice<dim> lattice;
  Point point;
  double values[n_q * n_p] = {};      ///< l_i(x_q) at [q * n_p + i]
  double derivative[n_q * n_q] = {};  ///< d/dx of the points' Lagrange basis: [q * n_q + r]
  bool collocated = false;            ///< points on the nodes: values is the identity
  /// The functor's coefficients, [batch][coef][point][lane] (CellOperatorKernel::point_coef).
  Kokkos::View<const double*, Mem> point_coef;
  int constrained_components = 1 << 20;  ///< as CellOperatorKernel's
  int cells_per_team = 1;

  static TeamCellKernel create(const ShapeData<n_p, n_q>& shape) {
    TeamCellKernel k;
    shape.values.to_dense(k.values);
    shape.derivative.to_dense(k.derivative);
    k.collocated = shape.collocated;
    return k;
  }

  /// Cell slots of the lattice: W per batch, lanes past a row's end empty.
  KOKKOS_INLINE_FUNCTION long n_slots() const { return static_cast<long>(lattice.n_batches()) * W; }
  static std::size_t scratch_bytes(int cells) {
    return Scratch::shmem_size(n_matrix + cells * per_cell);
  }

  /// dst += A src on every cell, `components` blocked copies of the operator, with
  /// `team_size` threads per team (0: 1 on host spaces, else enough for a few cells' points).
  void apply(const ExecSpace& exec, const double* src, double* dst, int components,
             int team_size = 0) const {
    TeamCellKernel k = *this;
    if (team_size <= 0) team_size = runs_on_host_v<ExecSpace> ? 1 : device_team_size();
    if (!runs_on_host_v<ExecSpace>) k.cells_per_team = cells_for(team_size);
    const long teams = (n_slots() + k.cells_per_team - 1) / k.cells_per_team;
    Policy policy(exec, static_cast<int>(teams), team_size);
    policy.set_scratch_size(0, Kokkos::PerTeam(scratch_bytes(k.cells_per_team)));
    Kokkos::parallel_for(
        "amphora::TeamCellKernel::apply", policy,
        KOKKOS_LAMBDA(const Team& team) { k.apply_team(team, src, dst, components); });
  }
  /// Threads for cells_for(threads) cells of n_points each: at most 256, whole warps.
  static int device_team_size() {
    const int cells = n_points >= 256 ? 1 : 256 / n_points;
    const int threads = cells * n_points < 256 ? cells * n_points : 256;
    return (threads + 31) / 32 * 32;
  }
  /// Cells a team of `threads` takes: as many as give each thread about one point, within 40 kB
  /// of scratch (under the 48 kB a GPU block may take without opting in).
  static int cells_for(int threads) {
    int cells = threads / n_points > 1 ? threads / n_points : 1;
    while (cells > 1 && scratch_bytes(cells) > 40000) --cells;
    return cells;
  }

  /// One team's cells: slots first .. first + cells_per_team - 1.
  KOKKOS_INLINE_FUNCTION void apply_team(const Team& team, const double* src, double* dst,
                                         int components) const {
    double* const base = Scratch(team.team_scratch(0), n_matrix + cells_per_team * per_cell).data();
    double* const V = base;
    double* const D = base + n_q * n_p;
    Kokkos::parallel_for(Kokkos::TeamThreadRange(team, n_matrix), [&](int i) {
      base[i] = i < n_q * n_p ? values[i] : derivative[i - n_q * n_p];
    });
    const long first = static_cast<long>(team.league_rank()) * cells_per_team;
    double* const cells = base + n_matrix;
    const long n = lattice.n_dofs();
    for (int comp = 0; comp < components; ++comp) {
      const bool constrained = comp < constrained_components;
      team.team_barrier();
      gather(team, first, src + comp * n, constrained, cells);
      team.team_barrier();
      bool at_nodes = false;
      if constexpr (n_p == n_q) at_nodes = collocated;
      const int a = at_nodes ? 0 : n_dofs;  // offset of the values at the points in a cell
      if (!at_nodes) interpolate(team, V, cells);
      points(team, D, first, a, cells);
      team.team_barrier();
      integrate_points(team, D, a, cells);
      team.team_barrier();
      if (!at_nodes) integrate_values(team, V, cells);
      scatter(team, first, dst + comp * n, constrained, cells);
    }
  }

  // --- one cell slot --------------------------------------------------------------------
  /// Lattice cell of slot s, false for an empty lane.
  KOKKOS_INLINE_FUNCTION bool slot_cell(long s, int* c) const {
    const int b = static_cast<int>(s / W), lane = static_cast<int>(s % W);
    if (b >= lattice.n_batches()) return false;
    lattice.batch_cell(b, c);
    if (lane >= lattice.active_lanes_at(c)) return false;
    c[0] += lane;
    return true;
  }
  /// Lattice node of local node i of cell c.
  KOKKOS_INLINE_FUNCTION void cell_node(const int* c, int i, int* node) const {
    for (int d = 0; d < dim; ++d, i /= n_p) node[d] = c[d] * lattice.degree + i % n_p;
  }

  KOKKOS_INLINE_FUNCTION void gather(const Team& team, long first, const double* src,
                                     bool constrained, double* cells) const {
    Kokkos::parallel_for(Kokkos::TeamThreadRange(team, cells_per_team * n_dofs), [&](int m) {
      const int slot = m / n_dofs, i = m % n_dofs;
      int c[3] = {0, 0, 0}, node[3] = {0, 0, 0};
      double v = 0.0;
      if (slot_cell(first + slot, c)) {
        cell_node(c, i, node);
        if (!(constrained && lattice.constrained(node))) v = src[lattice.dof_index(node)];
      }
      cells[slot * per_cell + i] = v;
    });
  }
  KOKKOS_INLINE_FUNCTION void scatter(const Team& team, long first, double* dst, bool constrained,
                                      const double* cells) const {
    Kokkos::parallel_for(Kokkos::TeamThreadRange(team, cells_per_team * n_dofs), [&](int m) {
      const int slot = m / n_dofs, i = m % n_dofs;
      int c[3] = {0, 0, 0}, node[3] = {0, 0, 0};
      if (!slot_cell(first + slot, c)) return;
      cell_node(c, i, node);
      if (constrained && lattice.constrained(node)) return;
      Kokkos::atomic_add(dst + lattice.dof_index(node), cells[slot * per_cell + i]);
    });
  }

  /// Cell arrays: [0, n_dofs) nodal, then the values at the points (a), then the work arrays.
  KOKKOS_INLINE_FUNCTION static double* work(double* cells, int slot, int w) {
    return cells + slot * per_cell + n_dofs + (1 + w) * n_points;
  }

  /// One sweep along direction d of every slot's tensor, in (offset in a cell) to out: M (rows x
  /// cols, row-major; `transpose`: its transpose, cols x rows) maps extent cols to rows along d,
  /// the directions before d have extent `before_n`, those after `after_n`.
  template <int d, int rows, int cols, int before_n, int after_n, bool transpose>
  KOKKOS_INLINE_FUNCTION void sweep(const Team& team, const double* M, double* cells, int in,
                                    int out) const {
    constexpr int before = ipow(before_n, d), after = ipow(after_n, dim - 1 - d);
    constexpr int size = before * rows * after;
    Kokkos::parallel_for(Kokkos::TeamThreadRange(team, cells_per_team * size), [&](int m) {
      const int slot = m / size, o = m % size;
      const int b = o % before, r = (o / before) % rows, p = o / (before * rows);
      const double* x = cells + slot * per_cell + in + p * cols * before + b;
      double s = 0.0;
      for (int j = 0; j < cols; ++j)
        s += (transpose ? M[j * rows + r] : M[r * cols + j]) * x[j * before];
      cells[slot * per_cell + out + o] = s;
    });
    team.team_barrier();
  }
  /// The nodal values to the points: nodal -> work 0 -> work 1 -> a (2D: nodal -> work 0 -> a).
  KOKKOS_INLINE_FUNCTION void interpolate(const Team& team, const double* V, double* cells) const {
    constexpr int w0 = n_dofs + n_points, w1 = n_dofs + 2 * n_points, a = n_dofs;
    sweep<0, n_q, n_p, n_q, n_p, false>(team, V, cells, 0, w0);
    if constexpr (dim == 3) {
      sweep<1, n_q, n_p, n_q, n_p, false>(team, V, cells, w0, w1);
      sweep<2, n_q, n_p, n_q, n_p, false>(team, V, cells, w1, a);
    } else {
      sweep<1, n_q, n_p, n_q, n_p, false>(team, V, cells, w0, a);
    }
  }
  /// The transpose: a -> work 0 (-> work 1) -> nodal.
  KOKKOS_INLINE_FUNCTION void integrate_values(const Team& team, const double* V,
                                               double* cells) const {
    constexpr int w0 = n_dofs + n_points, w1 = n_dofs + 2 * n_points, a = n_dofs;
    sweep<0, n_p, n_q, n_p, n_q, true>(team, V, cells, a, w0);
    if constexpr (dim == 3) {
      sweep<1, n_p, n_q, n_p, n_q, true>(team, V, cells, w0, w1);
      sweep<2, n_p, n_q, n_p, n_q, true>(team, V, cells, w1, 0);
    } else {
      sweep<1, n_p, n_q, n_p, n_q, true>(team, V, cells, w0, 0);
    }
  }

  /// At every point: the value and reference gradient (collocation derivative of the values at
  /// offset a), the functor with the point's stored coefficients, its integrands into the work
  /// arrays (gradients 0 .. dim - 1, then the value).
  KOKKOS_INLINE_FUNCTION void points(const Team& team, const double* D, long first, int a,
                                     double* cells) const {
    Kokkos::parallel_for(Kokkos::TeamThreadRange(team, cells_per_team * n_points), [&](int m) {
      const int slot = m / n_points, q = m % n_points;
      const double* u = cells + slot * per_cell + a;
      double v[1] = {u[q]}, g[dim], v_out[1] = {0.0}, g_out[dim];
      for (int e = 0, stride = 1; e < dim; ++e, stride *= n_q) {
        const int i = (q / stride) % n_q;
        double s = 0.0;
        if constexpr (grads)
          for (int r = 0; r < n_q; ++r) s += D[i * n_q + r] * u[q + (r - i) * stride];
        g[e] = s, g_out[e] = 0.0;
      }
      int c[3];
      const long id = first + slot;
      if (slot_cell(id, c)) {
        const long b = id / W, lane = id % W;
        const PointCoefficients<double> pc{
            point_coef.data() + (b * Point::n_coefficients * n_points + q) * W + lane,
            static_cast<long>(n_points) * W};
        point.at_point(pc, v, g, v_out, g_out);
      }
      if constexpr (grads)
        for (int e = 0; e < dim; ++e) work(cells, slot, e)[q] = g_out[e];
      if constexpr (Point::writes_values) work(cells, slot, grads ? dim : 0)[q] = v_out[0];
    });
  }
  /// The integrands tested against the basis at the points: the values written plus the
  /// transposed collocation derivative of each gradient integrand, into the values at a.
  KOKKOS_INLINE_FUNCTION void integrate_points(const Team& team, const double* D, int a,
                                               double* cells) const {
    Kokkos::parallel_for(Kokkos::TeamThreadRange(team, cells_per_team * n_points), [&](int m) {
      const int slot = m / n_points, q = m % n_points;
      double s = 0.0;
      if constexpr (Point::writes_values) s = work(cells, slot, grads ? dim : 0)[q];
      if constexpr (grads)
        for (int e = 0, stride = 1; e < dim; ++e, stride *= n_q) {
          const int i = (q / stride) % n_q;
          const double* g = work(cells, slot, e);
          for (int r = 0; r < n_q; ++r) s += D[r * n_q + i] * g[q + (r - i) * stride];
        }
      cells[slot * per_cell + a + q] = s;
    });
  }
};

}  // namespace amphora::kernels::sumfac
