#pragma once
// The kernels of one point functor for MatrixFreeOperator: the compiled table (degree, n_q) or
// the generic fallback, and the geometry setup. Included by one file per functor
// (matrix_free_<functor>.cpp), so the functors' instances compile in parallel.
#include <stdexcept>
#include <string>

#include "solvers/matrix_free/matrix_free_operator_impl.hpp"

namespace amphora::solvers::matrix_free {

/// Whether P is one of the flow solver's functors (compiled to max_compiled_degree_flow).
template <class P>
inline constexpr bool flow_functor_v = false;
template <int dim>
inline constexpr bool flow_functor_v<kernels::sumfac::OseenPoint<dim>> = true;
template <int dim>
inline constexpr bool flow_functor_v<kernels::sumfac::ElasticityPoint<dim>> = true;

/// Highest compiled degree of functor P: all of the table for mass and Laplace (the
/// benchmarks' and solvers' operators), the flow solver's range for its functors, degree 3 for
/// the volume-averaged flow (CFD-DEM's cells are a few particles wide: low degrees),
/// max_compiled_degree_general for the others.
template <class P>
inline constexpr bool vans_functor_v = false;
template <int dim>
inline constexpr bool vans_functor_v<kernels::sumfac::VansPoint<dim>> = true;
template <class P>
inline constexpr int compiled_degree_v =
    vans_functor_v<P>                                          ? max_compiled_degree_vans
    : flow_functor_v<P>                                        ? max_compiled_degree_flow
    : P::structure == kernels::sumfac::PointStructure::general ? max_compiled_degree_general
                                                               : max_compiled_degree;

template <int dim, class ExecSpace>
template <class P>
void MatrixFreeOperator<dim, ExecSpace>::Impl::install(const MatrixFreeOperator& op, const P&,
                                                       Impl& impl) {
  const int k = op.space_->degree(), n_q = op.n_q_;
  const Options& options = op.options_;
  auto fail = [](const std::string& what) {
    throw std::invalid_argument("MatrixFreeOperator: " + what);
  };
  constexpr int max = compiled_degree_v<P>;
  constexpr bool team =
      P::n_components == 1 && P::structure != kernels::sumfac::PointStructure::general;
  if (options.team_kernel && (!team || options.geometry != GeometryMode::stored ||
                              options.generic_kernel || !compiled_kernel(k, n_q, max)))
    fail(
        "team_kernel takes the mass or Laplace operator with geometry stored at the points "
        "and a compiled kernel");
  if (options.generic_kernel || !compiled_kernel(k, n_q, max)) {
    if constexpr (P::n_components == 1 &&
                  P::structure != kernels::sumfac::PointStructure::general) {
      using K = kernels::sumfac::GenericCellKernel<dim, ExecSpace, P>;
      if (options.field.extent(0) > 0)
        fail("no compiled kernel for degree " + std::to_string(k) + " with " + std::to_string(n_q) +
             " points per direction, and the generic one does mass and constant-coefficient "
             "Laplace only");
      if (k + 1 > K::max_nodes_1d || n_q > K::max_points_1d)
        fail("degree " + std::to_string(k) + " with " + std::to_string(n_q) +
             " points per direction exceeds the generic kernel's limits (degree <= " +
             std::to_string(K::max_nodes_1d - 1) +
             ", points <= " + std::to_string(K::max_points_1d) + ")");
      impl.generic = std::make_shared<K>(kernels::sumfac::make_generic_cell_kernel<dim, ExecSpace>(
          op.space_->lattice(), op.space_->coordinates(), make_point<P>(options, k), k, n_q,
          options.quadrature));
      impl.apply = &Impl::template generic_apply<P>;
      impl.diagonal = &Impl::template generic_diagonal<P>;
      impl.elements = &Impl::template generic_elements<P>;
      return;
    } else {
      fail("no compiled kernel for degree " + std::to_string(k) + " with " + std::to_string(n_q) +
           " points per direction, and the generic one does mass and constant-coefficient "
           "Laplace only");
    }
  }
  dispatch_degree<1, max>(k, n_q, [&](auto np_c, auto nq_c) {
    constexpr int n_p = decltype(np_c)::value, nq = decltype(nq_c)::value;
    impl.shape = std::make_shared<kernels::sumfac::ShapeData<n_p, nq>>(
        kernels::sumfac::ShapeData<n_p, nq>::create(options.quadrature));
    impl.apply = &Impl::template apply_impl<P, n_p, nq>;
    impl.apply_unconstrained = &Impl::template apply_impl<P, n_p, nq, false>;
    if constexpr (P::structure != kernels::sumfac::PointStructure::general)
      impl.direction = &Impl::template direction_impl<P, n_p, nq>;
    impl.diagonal = &Impl::template diagonal_impl<P, n_p, nq>;
    impl.elements = &Impl::template elements_impl<P, n_p, nq>;
    if constexpr (team) {
      if (options.team_kernel) {
        impl.apply = &Impl::template team_apply<P, n_p, nq>;
        impl.apply_unconstrained = &Impl::template team_apply<P, n_p, nq, false>;
        impl.direction = &Impl::direction_in_passes;
      }
    }
  });
}

template <int dim, class ExecSpace>
template <class P>
void MatrixFreeOperator<dim, ExecSpace>::Impl::setup(const MatrixFreeOperator& op, Impl& impl) {
  if (impl.generic) return;
  dispatch_degree<1, compiled_degree_v<P>>(op.space_->degree(), op.n_q_, [&](auto np_c, auto nq_c) {
    setup_geometry<P, decltype(np_c)::value, decltype(nq_c)::value>(op, impl);
  });
}

}  // namespace amphora::solvers::matrix_free

/// Instances of functor template F (F<2>, F<3>) for every enabled backend.
#define AMPHORA_MF_FUNCTOR_DIM(F, dim, E)                                                         \
  template void amphora::solvers::matrix_free::MatrixFreeOperator<dim, E>::Impl::install<F<dim>>( \
      const MatrixFreeOperator<dim, E>&, const F<dim>&, MatrixFreeOperator<dim, E>::Impl&);       \
  template void amphora::solvers::matrix_free::MatrixFreeOperator<dim, E>::Impl::setup<F<dim>>(   \
      const MatrixFreeOperator<dim, E>&, MatrixFreeOperator<dim, E>::Impl&);
#define AMPHORA_MF_FUNCTOR_E(F, E) AMPHORA_MF_FUNCTOR_DIM(F, 2, E) AMPHORA_MF_FUNCTOR_DIM(F, 3, E)
#define AMPHORA_MF_FUNCTOR(F)                                \
  AMPHORA_IF_SERIAL(AMPHORA_MF_FUNCTOR_E(F, Kokkos::Serial)) \
  AMPHORA_IF_OPENMP(AMPHORA_MF_FUNCTOR_E(F, Kokkos::OpenMP)) \
  AMPHORA_IF_CUDA(AMPHORA_MF_FUNCTOR_E(F, Kokkos::Cuda))
