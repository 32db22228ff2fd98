#pragma once
// Template definitions of MatrixFreeOperator, included by one .cpp per dimension.
#include <stdexcept>
#include <string>
#include <vector>

#include "kernels/blas1.hpp"
#include "kernels/host_vector.hpp"
#include "kernels/sumfac/quadrature_1d.hpp"
#include "kernels/sumfac/generic_cell_kernel.hpp"
#include "kernels/sumfac/team_cell_kernel.hpp"
#include "kernels/sumfac/vans_point.hpp"
#include "solvers/matrix_free/degree_dispatch.hpp"
#include "solvers/matrix_free/matrix_free_operator.hpp"

namespace amphora::solvers::matrix_free {

template <int dim, class ExecSpace>
struct MatrixFreeOperator<dim, ExecSpace>::Impl {
  using T = kernels::sumfac::Simd<kernels::sumfac::simd_width_v<ExecSpace>>;
  Kokkos::View<T*, memory_space> batch_coef, point_coef;
  // elements_impl's element matrices, kept for the next call (a recycled coarse operator's)
  mutable Kokkos::View<T*, memory_space> element_scratch;
  long batch_coef_stride = 0;
  std::shared_ptr<void> shape;    // ShapeData<n_p, n_q>
  std::shared_ptr<void> generic;  // GenericCellKernel<dim, ExecSpace, P>, where no compiled fits
  void (*apply)(const MatrixFreeOperator&, const ExecSpace&, const Vector&,
                const Vector&) = nullptr;
  void (*apply_unconstrained)(const MatrixFreeOperator&, const ExecSpace&, const Vector&,
                              const Vector&) = nullptr;
  double (*direction)(const MatrixFreeOperator&, const ExecSpace&, const Vector&, double,
                      const Vector&, const Vector&) = &direction_in_passes;
  void (*diagonal)(const MatrixFreeOperator&, const ExecSpace&, const Vector&) = nullptr;
  std::vector<double> (*elements)(const MatrixFreeOperator&, const ExecSpace&) = nullptr;

  template <class P, int n_p, int n_q>
  using Kernel = kernels::sumfac::CellOperatorKernel<dim, n_p, n_q, ExecSpace, P>;

  /// The point functor of the options' kind, with its parameters.
  template <class P>
  static P make_point(const Options& o, int degree) {
    P p;
    if constexpr (std::is_same_v<P, kernels::sumfac::ElasticityPoint<dim>>)
      p.lambda = o.lambda, p.mu = o.mu;
    if constexpr (std::is_same_v<P, kernels::sumfac::OseenPoint<dim>>) {
      p.nu = o.nu, p.alpha = o.alpha, p.gamma = o.grad_div, p.dt_inverse = o.dt_inverse;
      p.history = o.history;
      p.viscous_residual = o.viscous_residual;
      p.degree = degree;
    }
    if constexpr (std::is_same_v<P, kernels::sumfac::VansPoint<dim>>) {
      p.nu = o.nu, p.alpha = o.alpha, p.gamma = o.grad_div, p.dt_inverse = o.dt_inverse;
      p.history = o.history;
      p.viscous_residual = o.viscous_residual;
      p.model_b = o.model_b;
      p.load_only = o.load_only;
      p.degree = degree;
    }
    return p;
  }

  /// f(P{}) with the point functor of `kind`.
  template <class F>
  static void with_point(OperatorKind kind, F&& f) {
    switch (kind) {
      case OperatorKind::mass: return f(kernels::sumfac::MassPoint<dim>{});
      case OperatorKind::laplace: return f(kernels::sumfac::LaplacePoint<dim>{});
      case OperatorKind::convection: return f(kernels::sumfac::ConvectionPoint<dim>{});
      case OperatorKind::elasticity: return f(kernels::sumfac::ElasticityPoint<dim>{});
      case OperatorKind::oseen: return f(kernels::sumfac::OseenPoint<dim>{});
      case OperatorKind::vans: return f(kernels::sumfac::VansPoint<dim>{});
    }
  }

  template <class P, int n_p, int n_q>
  static Kernel<P, n_p, n_q> kernel(const MatrixFreeOperator& op) {
    Kernel<P, n_p, n_q> k;
    k.lattice = op.space_->lattice();
    k.shape = *static_cast<const kernels::sumfac::ShapeData<n_p, n_q>*>(op.impl_->shape.get());
    k.point = make_point<P>(op.options_, op.space_->degree());
    k.mode = op.options_.geometry;
    k.n_coef = coefficient_count<P>(op.options_);
    k.batch_coef = op.impl_->batch_coef;
    k.batch_coef_stride = op.impl_->batch_coef_stride;
    k.point_coef = op.impl_->point_coef;
    k.coordinates = op.space_->coordinates();
    k.field = op.options_.field;
    k.constrained_components = op.constrained_components_;
    k.affine_cells = op.space_->mesh().affine();
    return k;
  }

  static kernels::sumfac::FirstTouchZero<dim> first_touch_zero(const MatrixFreeOperator& op,
                                                               const Vector& y) {
    return kernels::sumfac::FirstTouchZero<dim>{op.space_->lattice(), y.data(),
                                                op.options_.components};
  }

  /// Coefficients kept per cell or point: the functor's (the Cartesian Laplace: the diagonal).
  template <class P>
  static int coefficient_count(const Options& o) {
    if (o.geometry == GeometryMode::cartesian &&
        P::structure == kernels::sumfac::PointStructure::laplace)
      return dim;
    return P::n_coefficients;
  }

  /// y = A x; unconstrained: without Dirichlet rows and columns.
  template <class P, int n_p, int n_q, bool constrained = true>
  static void apply_impl(const MatrixFreeOperator& op, const ExecSpace& exec, const Vector& x,
                         const Vector& y) {
    auto k = kernel<P, n_p, n_q>(op);
    if (!constrained) k.constrained_components = 0;
    const double* src = x.data();
    double* dst = y.data();
    const int comps = op.options_.components;
    constexpr bool atomic = !kernels::runs_on_host_v<ExecSpace>;
    if (atomic) kernels::blas1::fill(exec, y, 0.0);
    const auto zero = first_touch_zero(op, y);
    kernels::sumfac::for_each_batch_coloured(
        exec, k.lattice, "amphora::MatrixFreeOperator::apply", zero,
        KOKKOS_LAMBDA(int b0, int b1) { k.template apply_row<atomic>(src, dst, comps, b0, b1); });
    if (constrained) copy_constrained(op, exec, x, y);
  }

  template <class P, int n_p, int n_q>
  using TeamKernel = kernels::sumfac::TeamCellKernel<dim, n_p, n_q, ExecSpace, P>;

  /// The team schedule's kernel of this operator (Options::team_kernel).
  template <class P, int n_p, int n_q>
  static TeamKernel<P, n_p, n_q> team_kernel(const MatrixFreeOperator& op) {
    auto k = TeamKernel<P, n_p, n_q>::create(
        *static_cast<const kernels::sumfac::ShapeData<n_p, n_q>*>(op.impl_->shape.get()));
    k.lattice = op.space_->lattice();
    k.point = make_point<P>(op.options_, op.space_->degree());
    const auto& c = op.impl_->point_coef;
    k.point_coef = Kokkos::View<const double*, memory_space, Kokkos::MemoryUnmanaged>(
        reinterpret_cast<const double*>(c.data()), c.extent(0) * sizeof(T) / sizeof(double));
    k.constrained_components = op.constrained_components_;
    return k;
  }

  /// apply_impl through the team schedule.
  template <class P, int n_p, int n_q, bool constrained = true>
  static void team_apply(const MatrixFreeOperator& op, const ExecSpace& exec, const Vector& x,
                         const Vector& y) {
    auto k = team_kernel<P, n_p, n_q>(op);
    if (!constrained) k.constrained_components = 0;
    kernels::blas1::fill(exec, y, 0.0);
    k.apply(exec, x.data(), y.data(), op.options_.components, op.options_.team_size);
    if (constrained) copy_constrained(op, exec, x, y);
  }

  /// apply_direction as three passes: the update, the application, the product.
  static double direction_in_passes(const MatrixFreeOperator& op, const ExecSpace& exec,
                                    const Vector& z, double beta, const Vector& p,
                                    const Vector& q) {
    return solvers::direction_in_passes(exec, op, z, beta, p, q, LocalInnerProduct());
  }

  /// apply_direction in one sweep (host spaces, no periodic wrap along the rows or slabs): the
  /// update where a row first reads p, the row's share of p.q where it last writes q.
  template <class P, int n_p, int n_q>
  static double direction_impl(const MatrixFreeOperator& op, const ExecSpace& exec, const Vector& z,
                               double beta, const Vector& p, const Vector& q) {
    constexpr bool host = kernels::runs_on_host_v<ExecSpace>;
    if constexpr (!host) {
      return direction_in_passes(op, exec, z, beta, p, q);
    } else {  // (discarded on devices: the partial sums are read on the host)
      const auto k = kernel<P, n_p, n_q>(op);
      if (!k.lattice.last_touch_ranges()) return direction_in_passes(op, exec, z, beta, p, q);
      const int comps = op.options_.components;
      const int rows = k.lattice.n_slabs() * k.lattice.rows_per_slab();
      Kokkos::View<double*, memory_space> partial(
          Kokkos::view_alloc(Kokkos::WithoutInitializing,
                             "amphora::MatrixFreeOperator::partial_dots"),
          rows);
      double* pp = p.data();
      double* qq = q.data();
      // row by row: batch by batch (the work interleaved with the cells') was 2x slower at p = 1,
      // where a batch's part of its lines is a few cache lines, and no faster at p = 3 and 6
      kernels::sumfac::for_each_batch_coloured(
          exec, k.lattice, "amphora::MatrixFreeOperator::apply_direction",
          kernels::sumfac::FirstTouchDirection<dim>{k.lattice, z.data(), pp, qq, beta, comps},
          KOKKOS_LAMBDA(int b0, int b1) { k.template apply_row<false>(pp, qq, comps, b0, b1); },
          kernels::sumfac::LastTouchDot<dim>{k.lattice, pp, qq, partial.data(), comps});
      // Constrained rows become q = p. The rows' sums took the loop's q there (zero, or what a
      // fast batch added into a Dirichlet lane, as apply leaves to copy_constrained): corrected.
      const auto cons = op.space_->constrained_dofs();
      const long n = op.space_->n_dofs();
      const int nc = static_cast<int>(cons.extent(0));
      double constrained = 0.0;
      Kokkos::parallel_reduce(
          "amphora::MatrixFreeOperator::constrained_rows",
          kernels::RangePolicy<ExecSpace>(exec, 0, nc * op.constrained_components_),
          KOKKOS_LAMBDA(int m, double& acc) {
            const long i = (m / nc) * n + cons(m % nc);
            acc += p(i) * (p(i) - q(i));
            q(i) = p(i);
          },
          constrained);
      exec.fence();
      double pq = 0.0;
      for (int r = 0; r < rows; ++r) pq += partial(r);
      return pq + constrained;
    }
  }

  // The generic fallback (generic_cell_kernel.hpp): one team per cell batch, its cells one at
  // a time. mode 0: y = A x; 1: y = diag(A); on host spaces batches run coloured.
  template <class P>
  static void generic_impl(const MatrixFreeOperator& op, const ExecSpace& exec, const Vector& x,
                           const Vector& y, int mode) {
    using K = kernels::sumfac::GenericCellKernel<dim, ExecSpace, P>;
    const K k = *static_cast<const K*>(op.impl_->generic.get());
    const int comps = op.options_.components;
    const long n = op.space_->n_dofs();
    constexpr bool atomic = !kernels::runs_on_host_v<ExecSpace>;
    kernels::blas1::fill(exec, y, 0.0);
    double* out = y.data();
    kernels::sumfac::for_each_batch_team(
        exec, k.lattice, "amphora::MatrixFreeOperator::generic", k.scratch_bytes(),
        KOKKOS_LAMBDA(const typename K::Team& team, int b0, int b1) {
          k.template add_batches<atomic>(team, b0, b1, x, out, n, comps, mode);
        });
    if (mode == 0)
      copy_constrained(op, exec, x, y);
    else
      copy_constrained(op, exec, Vector(), y, 1.0);
  }
  template <class P>
  static void generic_apply(const MatrixFreeOperator& op, const ExecSpace& exec, const Vector& x,
                            const Vector& y) {
    generic_impl<P>(op, exec, x, y, 0);
  }
  template <class P>
  static void generic_diagonal(const MatrixFreeOperator& op, const ExecSpace& exec,
                               const Vector& d) {
    generic_impl<P>(op, exec, Vector(), d, 1);
  }
  template <class P>
  static std::vector<double> generic_elements(const MatrixFreeOperator& op, const ExecSpace& exec) {
    using K = kernels::sumfac::GenericCellKernel<dim, ExecSpace, P>;
    using Policy = Kokkos::TeamPolicy<ExecSpace>;
    const K k = *static_cast<const K*>(op.impl_->generic.get());
    const int nd = k.n_cell_dofs();
    int nc = 1;
    for (int d = 0; d < dim; ++d) nc *= k.lattice.cells[d];
    Kokkos::View<double*, memory_space> out("amphora::MatrixFreeOperator::generic_elements",
                                            static_cast<std::size_t>(nc) * nd * nd);
    const bool host = kernels::runs_on_host_v<ExecSpace>;
    Policy policy = host ? Policy(exec, nc, 1) : Policy(exec, nc, Kokkos::AUTO);
    policy.set_scratch_size(1, Kokkos::PerTeam(k.scratch_bytes()));
    Kokkos::parallel_for(
        "amphora::MatrixFreeOperator::generic_elements", policy,
        KOKKOS_LAMBDA(const typename K::Team& team) {
          const int cell = team.league_rank();
          int c[3] = {0, 0, 0};
          for (int d = 0, r = cell; d < dim; ++d)
            c[d] = r % k.lattice.cells[d], r /= k.lattice.cells[d];
          const typename K::Work w = k.work(team);
          k.cell_setup(team, c, w.X, w.dof);
          for (int j = 0; j < nd; ++j) {
            k.element_column(team, w, j);
            const std::size_t at = (static_cast<std::size_t>(cell) * nd + j) * nd;
            Kokkos::parallel_for(Kokkos::TeamThreadRange(team, nd),
                                 [&](int i) { out(at + i) = w.column[i]; });
            team.team_barrier();
          }
        });
    auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), out);
    return std::vector<double>(h.data(), h.data() + h.extent(0));
  }

  template <class P, int n_p, int n_q>
  static void diagonal_impl(const MatrixFreeOperator& op, const ExecSpace& exec, const Vector& d) {
    const auto k = kernel<P, n_p, n_q>(op);
    double* dst = d.data();
    const int comps = op.options_.components;
    constexpr bool atomic = !kernels::runs_on_host_v<ExecSpace>;
    if (atomic) kernels::blas1::fill(exec, d, 0.0);
    kernels::sumfac::for_each_batch_coloured(
        exec, k.lattice, "amphora::MatrixFreeOperator::diagonal", first_touch_zero(op, d),
        KOKKOS_LAMBDA(int b) { k.template diagonal_batch<atomic>(dst, comps, b); });
    copy_constrained(op, exec, Vector(), d, 1.0);
  }

  template <class P, int n_p, int n_q>
  static std::vector<double> elements_impl(const MatrixFreeOperator& op, const ExecSpace& exec) {
    const auto k = kernel<P, n_p, n_q>(op);
    using K = Kernel<P, n_p, n_q>;
    constexpr int nd = K::n_comp * K::n_dofs;
    const int nb = k.lattice.n_batches();
    auto& kept = op.impl_->element_scratch;
    if (kept.extent(0) != static_cast<std::size_t>(nb) * nd * nd)
      kept = Kokkos::View<T*, memory_space>("amphora::MatrixFreeOperator::elements",
                                            static_cast<std::size_t>(nb) * nd * nd);
    const auto out = kept;
    Kokkos::parallel_for(
        "amphora::MatrixFreeOperator::element_matrices",
        kernels::RangePolicy<ExecSpace>(exec, 0, nb),
        KOKKOS_LAMBDA(int b) { k.element_matrix(b, out.data() + static_cast<long>(b) * nd * nd); });
    auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), out);
    const auto& lat = k.lattice;
    std::vector<double> m(static_cast<std::size_t>(op.space_->mesh().n_cells()) * nd * nd);
    for (int b = 0; b < nb; ++b) {
      int cell[3] = {0, 0, 0};
      lat.batch_cell(b, cell);
      for (int l = 0; l < lat.active_lanes(b); ++l) {
        long c = cell[dim - 1];
        for (int d = dim - 2; d >= 1; --d) c = c * lat.cells[d] + cell[d];
        c = c * lat.cells[0] + cell[0] + l;
        for (int e = 0; e < nd * nd; ++e)
          m[c * nd * nd + e] = h(static_cast<long>(b) * nd * nd + e)[l];
      }
    }
    return m;
  }

  /// Point coefficients of every batch through the on-the-fly path, kept whole (stored) or
  /// reduced to one value per cell (cartesian, affine: the metric without the weight).
  template <class P, int n_p, int n_q>
  static void setup_geometry(const MatrixFreeOperator& op, Impl& impl) {
    using K = Kernel<P, n_p, n_q>;
    const K kern = kernel<P, n_p, n_q>(op);
    const int nb = op.space_->lattice().n_batches();
    const int n_all = P::n_coefficients;
    const int n_keep = coefficient_count<P>(op.options_);
    const bool per_cell = op.options_.geometry == GeometryMode::cartesian ||
                          op.options_.geometry == GeometryMode::affine;
    const ExecSpace exec;
    if (!per_cell) {
      const std::size_t size = static_cast<std::size_t>(nb) * n_all * K::n_points;
      if (impl.point_coef.extent(0) != size)  // else a recycled operator's arrays
        impl.point_coef = Kokkos::View<T*, memory_space>(
            Kokkos::view_alloc(Kokkos::WithoutInitializing,
                               std::string("amphora::MatrixFreeOperator::point_coef")),
            size);
      const auto pc = impl.point_coef;
      Kokkos::parallel_for(
          "amphora::MatrixFreeOperator::setup_geometry",
          kernels::RangePolicy<ExecSpace>(exec, 0, nb), KOKKOS_LAMBDA(int b) {
            typename K::Scratch s;
            kern.point_coefficients(b, s);
            T* dst = pc.data() + static_cast<long>(b) * n_all * K::n_points;
            for (int i = 0; i < n_all * K::n_points; ++i) dst[i] = s.jac[i];
          });
    } else {
      Kokkos::View<T*, memory_space> bc("amphora::MatrixFreeOperator::batch_coef",
                                        static_cast<std::size_t>(nb) * n_keep);
      // only the Cartesian Laplace keeps the diagonal of its metric (so the compiler sees the
      // index below in range for every other functor)
      const bool diagonal_only =
          P::structure == kernels::sumfac::PointStructure::laplace && n_keep != n_all;
      Kokkos::parallel_for(
          "amphora::MatrixFreeOperator::setup_geometry",
          kernels::RangePolicy<ExecSpace>(exec, 0, nb), KOKKOS_LAMBDA(int b) {
            typename K::Scratch s;
            kern.point_coefficients(b, s);
            const T w0(K::Eval::weight(kern.shape, 0));
            for (int e = 0; e < n_keep; ++e) {
              const int src = diagonal_only ? kernels::sumfac::sym_index<dim>(e, e) : e;
              bc(static_cast<long>(b) * n_keep + e) = s.jac[src * K::n_points] / w0;
            }
          });
      impl.batch_coef = bc;
      impl.batch_coef_stride = n_keep;
      // Cells of one shape (a uniform box, a uniformly sheared one) share their coefficients:
      // kept once, as deal.II's MappingInfo compresses equal Jacobians, they need not be read
      // per cell (24 bytes per cell for cartesian Laplace in 3D, as much as a DoF's source and
      // destination at p = 1). Equal to 1e-12 of the largest coefficient: cell widths from node
      // coordinates differ in the last bits.
      const auto lat = op.space_->lattice();
      int differing = 0;
      Kokkos::parallel_reduce(
          "amphora::MatrixFreeOperator::uniform_geometry",
          kernels::RangePolicy<ExecSpace>(exec, 0, nb),
          KOKKOS_LAMBDA(int b, int& acc) {
            const int lanes = lat.active_lanes(b);
            double scale = 0.0;
            for (int e = 0; e < n_keep; ++e)
              scale = kernels::math::max(scale, kernels::math::abs(bc(e)[0]));
            for (int e = 0; e < n_keep; ++e)
              for (int l = 0; l < lanes; ++l)
                acc += kernels::math::abs(bc(static_cast<long>(b) * n_keep + e)[l] - bc(e)[0]) >
                       1e-12 * scale;
          },
          differing);
      if (differing == 0) {
        Kokkos::View<T*, memory_space> once("amphora::MatrixFreeOperator::batch_coef", n_keep);
        Kokkos::parallel_for(
            "amphora::MatrixFreeOperator::uniform_geometry",
            kernels::RangePolicy<ExecSpace>(exec, 0, n_keep),
            KOKKOS_LAMBDA(int e) { once(e) = T(bc(e)[0]); });
        impl.batch_coef = once;
        impl.batch_coef_stride = 0;
      }
    }
    exec.fence();
  }

  /// The kernels of functor P for the space's degree and op.n_q(): compiled, or the generic
  /// fallback (scalar functors without a field) where the table has none or it is asked for.
  /// Defined in matrix_free_operator_install.hpp, compiled in one file per functor.
  template <class P>
  static void install(const MatrixFreeOperator& op, const P& point, Impl& impl);
  /// The functor's coefficients (stored, or per cell) for op's geometry mode.
  template <class P>
  static void setup(const MatrixFreeOperator& op, Impl& impl);

  /// Constrained rows: y_i = x_i (identity rows), or y_i = value if x is empty.
  static void copy_constrained(const MatrixFreeOperator& op, const ExecSpace& exec, const Vector& x,
                               const Vector& y, double value = 0.0) {
    const auto cons = op.space_->constrained_dofs();
    const long n = op.space_->n_dofs();
    const int nc = static_cast<int>(cons.extent(0));
    const bool from_x = x.extent(0) > 0;
    for (int comp = 0; comp < op.constrained_components_; ++comp) {
      const long off = comp * n;
      Kokkos::parallel_for(
          "amphora::MatrixFreeOperator::constraints", kernels::RangePolicy<ExecSpace>(exec, 0, nc),
          KOKKOS_LAMBDA(int i) { y(off + cons(i)) = from_x ? x(off + cons(i)) : value; });
    }
  }
};

template <int dim, class ExecSpace>
MatrixFreeOperator<dim, ExecSpace>::MatrixFreeOperator(const Space& space, const Options& options,
                                                       MatrixFreeOperator* recycled)
    : space_(&space), options_(options) {
  const int k = space.degree();
  n_q_ = options.n_q > 0 ? options.n_q : k + 1;
  constrained_components_ =
      options.constrained_components >= 0 ? options.constrained_components
      : options.kind == OperatorKind::oseen || options.kind == OperatorKind::vans
          ? dim
          : options.components;
  const auto& mesh = space.mesh();
  auto fail = [](const std::string& what) {
    throw std::invalid_argument("MatrixFreeOperator: " + what);
  };
  if (options.components < 1) fail("components must be at least 1");
  if (constrained_components_ > options.components)
    fail("constrained_components must be -1 (default) or 0 .. components");
  if (options.geometry == GeometryMode::cartesian && !mesh.cartesian())
    fail("geometry 'cartesian' needs an undeformed box; use 'affine', 'stored' or 'on_the_fly'");
  if (options.geometry == GeometryMode::affine && !mesh.affine())
    fail("geometry 'affine' needs an affine deformation; use 'stored' or 'on_the_fly'");
  const bool per_cell =
      options.geometry == GeometryMode::cartesian || options.geometry == GeometryMode::affine;
  if (options.kind == OperatorKind::convection &&
      options.field.extent(0) != static_cast<std::size_t>(dim * space.n_dofs()))
    fail("convection needs a velocity field of dim x n_dofs entries");
  if (options.kind == OperatorKind::laplace && options.field.extent(0) > 0 &&
      options.field.extent(0) != static_cast<std::size_t>(space.n_dofs()))
    fail("the Laplace coefficient field must have n_dofs entries");
  if (per_cell && options.field.extent(0) > 0)
    fail(
        "a coefficient or velocity field varies within cells: use geometry 'stored' or "
        "'on_the_fly'");
  if (options.quadrature == kernels::sumfac::QuadratureKind::gauss_lobatto && n_q_ != k + 1)
    fail("Gauss-Lobatto quadrature is supported with n_q = degree + 1 (collocation) only");

  if (options.kind == OperatorKind::elasticity && options.components != dim)
    fail("elasticity acts on dim components: set components = " + std::to_string(dim));
  if (options.kind == OperatorKind::elasticity && per_cell)
    fail("elasticity keeps J^-1 at the points: use geometry 'stored' or 'on_the_fly'");
  if (options.kind == OperatorKind::elasticity && options.field.extent(0) > 0)
    fail("elasticity takes no field (constant Lame constants)");
  if (options.kind == OperatorKind::oseen || options.kind == OperatorKind::vans) {
    const bool vans = options.kind == OperatorKind::vans;
    const std::string name = vans ? "VANS" : "Oseen";
    if (options.components != dim + 1)
      fail(name + " acts on velocity and pressure: set components = " + std::to_string(dim + 1));
    if (per_cell) fail(name + " keeps J^-1 at the points: use geometry 'stored' or 'on_the_fly'");
    const int n_fields = vans ? dim + 2 : dim;
    if (options.field.extent(0) != static_cast<std::size_t>(n_fields * space.n_dofs()))
      fail(vans ? "VANS needs a field of (dim + 2) x n_dofs entries: advecting velocity, void "
                  "fraction, implicit drag"
                : "Oseen needs an advecting velocity field of dim x n_dofs entries (zero: Stokes)");
    if (!(options.nu > 0.0)) fail(name + " needs a positive viscosity nu");
    if (options.alpha < 0.0 || options.grad_div < 0.0 || options.dt_inverse < 0.0)
      fail(name + "'s alpha, grad_div and dt_inverse must not be negative");
  }

  std::shared_ptr<Impl> impl;
  if (recycled && may_recycle(*recycled)) {  // its arrays: setup_geometry writes into them
    impl = std::const_pointer_cast<Impl>(recycled->impl_);
    recycled->impl_.reset();
    impl->generic.reset();
  } else {
    impl = std::make_shared<Impl>();
  }
  Impl::with_point(options.kind, [&](auto point) { Impl::install(*this, point, *impl); });
  impl_ = impl;
  if (impl->generic && constrained_components_ != options.components)
    fail("the generic kernel constrains every component: constrained_components must be -1");
  if (options.geometry == GeometryMode::on_the_fly || impl->generic) return;
  Impl::with_point(options.kind,
                   [&](auto point) { Impl::template setup<decltype(point)>(*this, *impl); });
}

template <int dim, class ExecSpace>
bool MatrixFreeOperator<dim, ExecSpace>::may_recycle(const MatrixFreeOperator& other) const {
  const Options& a = options_;
  const Options& b = other.options_;
  return other.impl_ && other.impl_.use_count() == 1 && space_ == other.space_ &&
         a.kind == b.kind && a.geometry == b.geometry && a.quadrature == b.quadrature &&
         n_q_ == other.n_q_ && a.components == b.components;
}

template <int dim, class ExecSpace>
void MatrixFreeOperator<dim, ExecSpace>::apply(const ExecSpace& exec, const Vector& x,
                                               const Vector& y) const {
  impl_->apply(*this, exec, x, y);
}

template <int dim, class ExecSpace>
void MatrixFreeOperator<dim, ExecSpace>::apply_unconstrained(const ExecSpace& exec, const Vector& x,
                                                             const Vector& y) const {
  if (!impl_->apply_unconstrained)
    throw std::invalid_argument(
        "MatrixFreeOperator::apply_unconstrained: compiled kernels only (not the generic one)");
  impl_->apply_unconstrained(*this, exec, x, y);
}

template <int dim, class ExecSpace>
double MatrixFreeOperator<dim, ExecSpace>::apply_direction(const ExecSpace& exec, const Vector& z,
                                                           double beta, const Vector& p,
                                                           const Vector& q) const {
  return impl_->direction(*this, exec, z, beta, p, q);
}

template <int dim, class ExecSpace>
void MatrixFreeOperator<dim, ExecSpace>::compute_diagonal(const ExecSpace& exec,
                                                          const Vector& d) const {
  if (options_.kind == OperatorKind::convection)
    throw std::invalid_argument(
        "MatrixFreeOperator::compute_diagonal: not provided for convection (not symmetric)");
  impl_->diagonal(*this, exec, d);
}

template <int dim, class ExecSpace>
std::vector<double> MatrixFreeOperator<dim, ExecSpace>::element_matrices(
    const ExecSpace& exec) const {
  if (!impl_->elements)
    throw std::invalid_argument(
        "MatrixFreeOperator::element_matrices: not provided by the generic kernel");
  return impl_->elements(*this, exec);
}

template <int dim, class ExecSpace>
std::size_t MatrixFreeOperator<dim, ExecSpace>::geometry_bytes() const {
  std::size_t bytes =
      (impl_->batch_coef.extent(0) + impl_->point_coef.extent(0)) * sizeof(typename Impl::T);
  if (options_.geometry == GeometryMode::on_the_fly)
    bytes += space_->coordinates().extent(0) * sizeof(double);
  return bytes;
}

}  // namespace amphora::solvers::matrix_free
