#pragma once
// The right-hand side b_i = (f_h, phi_i) of a Q_k problem for f given at the nodes (f
// interpolated into Q_k: an O(h^(k+1)) perturbation), zero on the Dirichlet DoFs.
#include "solvers/matrix_free/matrix_free_operator.hpp"

namespace amphora::solvers::matrix_free {

template <int dim, class ExecSpace>
typename MatrixFreeOperator<dim, ExecSpace>::Vector load_vector(
    const ExecSpace& exec, const mesh::hex::QkSpace<dim, ExecSpace>& space,
    const typename MatrixFreeOperator<dim, ExecSpace>::Vector& f_nodal, GeometryMode geometry,
    int n_q) {
  typename MatrixFreeOperator<dim, ExecSpace>::Options o;
  o.kind = OperatorKind::mass;
  o.geometry = geometry;
  o.n_q = n_q;
  typename MatrixFreeOperator<dim, ExecSpace>::Vector b("amphora::load_vector", space.n_dofs());
  MatrixFreeOperator<dim, ExecSpace>(space, o).apply(exec, f_nodal, b);
  const auto cons = space.constrained_dofs();
  Kokkos::parallel_for(
      "amphora::load_vector::dirichlet",
      kernels::RangePolicy<ExecSpace>(exec, 0, static_cast<int>(cons.extent(0))),
      KOKKOS_LAMBDA(int i) { b(cons(i)) = 0.0; });
  return b;
}

}  // namespace amphora::solvers::matrix_free
