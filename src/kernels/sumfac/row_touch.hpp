#pragma once
// Work on the DoFs a row of cell batches touches first or last, done by the cell loop
// (for_each_batch_coloured) just before or just after the row, while its lines are in cache:
// zeroing a destination, and CG's vector updates and inner product fused into an operator
// application (Kronbichler, Sashko & Munch 2023, "Enhancing data locality of the conjugate
// gradient method for high-order matrix-free finite-element implementations", IJHPCA 37(2),
// sec. 3).
#include "kernels/sumfac/qk_lattice.hpp"

namespace amphora::kernels::sumfac {

/// DoFs a row touches first (or last) in the cell loop's order: in each node layer of
/// [layer_first, layer_end) (along the last direction), its lines [line_first, line_end) along
/// direction 1 (the whole layer, one line, in 2D), which lie next to each other. Last touches
/// need lattice.last_touch_ranges().
struct TouchedDofs {
  int layer_first = 0, layer_end = 0, line_first = 0, line_end = 1;
  long layer = 0, line = 0;
  /// f(begin, end) for the contiguous range of lattice indices in each layer.
  AMPHORA_EXEC_CHECK_DISABLE
  template <class F>
  KOKKOS_INLINE_FUNCTION void for_each_range(const F& f) const {
    for (int l = layer_first; l < layer_end; ++l)
      f(l * layer + line_first * line, l * layer + line_end * line);
  }
};

/// The DoFs row `row` of slab `slab` touches first (or last): its slab's layers and its lines,
/// whole.
template <int dim>
KOKKOS_INLINE_FUNCTION TouchedDofs row_touch(const QkLattice<dim>& lattice, int slab, int row,
                                             bool last) {
  TouchedDofs t;
  if (last)
    lattice.slab_last_layers(slab, t.layer_first, t.layer_end);
  else
    lattice.slab_first_layers(slab, t.layer_first, t.layer_end);
  t.line = lattice.dofs[0];
  t.layer = dim == 3 ? t.line * lattice.dofs[1] : t.line;
  if constexpr (dim == 3) {
    if (last)
      lattice.row_last_layers(row, t.line_first, t.line_end);
    else
      lattice.row_first_layers(row, t.line_first, t.line_end);
  }
  return t;
}

/// Nothing to do before or after a row.
struct NoTouch {
  KOKKOS_INLINE_FUNCTION void operator()(int, int) const {}
};

/// Zeroes the nodes row `row` of slab `slab` writes first (every component), just before the
/// row's batches run, so the lines they add into are still in cache (a whole slab, zeroed at
/// once, is about 1 MB at degree 6).
template <int dim>
struct FirstTouchZero {
  QkLattice<dim> lattice;
  double* y;
  int components;
  KOKKOS_INLINE_FUNCTION void operator()(int slab, int row) const {
    const long n = lattice.n_dofs();
    for (int c = 0; c < components; ++c)
      row_touch(lattice, slab, row, false).for_each_range([&](long begin, long end) {
        for (long i = c * n + begin; i < c * n + end; ++i) y[i] = 0.0;
      });
  }
};

/// CG's new direction where a row first reads it: p = z + beta p (p = z where beta is 0, so
/// an uninitialised p is never read), and q, which the row then adds into, zeroed.
template <int dim>
struct FirstTouchDirection {
  QkLattice<dim> lattice;
  const double* z;
  double* p;
  double* q;
  double beta;
  int components;
  KOKKOS_INLINE_FUNCTION void operator()(int slab, int row) const {
    const long n = lattice.n_dofs();
    const TouchedDofs t = row_touch(lattice, slab, row, false);
    for (int c = 0; c < components; ++c)
      t.for_each_range([&](long begin, long end) {
        if (beta == 0.0)
          for (long i = c * n + begin; i < c * n + end; ++i) p[i] = z[i], q[i] = 0.0;
        else
          for (long i = c * n + begin; i < c * n + end; ++i) p[i] = z[i] + beta * p[i], q[i] = 0.0;
      });
  }
};

/// p.q over the DoFs a row writes last (q final there), into partial[slab * rows + row]: the
/// rows' sums are added in a fixed order afterwards, so the product does not depend on threads.
template <int dim>
struct LastTouchDot {
  QkLattice<dim> lattice;
  const double* p;
  const double* q;
  double* partial;
  int components;
  KOKKOS_INLINE_FUNCTION void operator()(int slab, int row) const {
    const long n = lattice.n_dofs();
    const TouchedDofs t = row_touch(lattice, slab, row, true);
    double s[8] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};  // eight sums: the loop vectorises
    for (int c = 0; c < components; ++c)
      t.for_each_range([&](long begin, long end) {
        long i = c * n + begin;
        for (; i + 8 <= c * n + end; i += 8)
          for (int m = 0; m < 8; ++m) s[m] += p[i + m] * q[i + m];
        for (int m = 0; i < c * n + end; ++i, ++m) s[m] += p[i] * q[i];
      });
    partial[slab * lattice.rows_per_slab() + row] =
        ((s[0] + s[1]) + (s[2] + s[3])) + ((s[4] + s[5]) + (s[6] + s[7]));
  }
};

}  // namespace amphora::kernels::sumfac
