#pragma once
// Matrix-free grid transfer between nested continuous Q_k spaces on structured boxes:
// p-transfer (same cells, degree k_c < k_f) and h-transfer (Q1 on a mesh and on its uniform
// refinement, which is Q2 on the coarse cells with the same numbering: Gauss–Lobatto nodes of
// Q2 are the midpoints). Prolongation interpolates the coarse polynomial on each coarse cell;
// restriction is its transpose. Cell by cell, shared fine nodes are weighted by 1/(number of
// cells sharing them), which makes the sum over cells the global operator exactly: a coarse
// basis function that is non-zero at a fine node is supported on every cell holding the node.
// Q1 on n cells and on ceil(n / 2) (odd n: not nested) interpolate on the node lattice instead
// (kernels::sumfac::LatticeInterpolation).
#include <memory>

#include <Kokkos_Core.hpp>

#include "mesh/hex/qk_space.hpp"

namespace amphora::solvers::matrix_free {

template <int dim, class ExecSpace>
class MatrixFreeTransfer {
 public:
  using Vector = Kokkos::View<double*, typename ExecSpace::memory_space>;
  using Space = mesh::hex::QkSpace<dim, ExecSpace>;

  /// `fine` has the cells of `coarse` and a higher degree (p), or twice the cells per
  /// direction or n where the coarse has ceil(n / 2), both of degree 1 (h). Throws otherwise.
  /// Degree pairs compiled: k_f <= 2 k_c
  /// + 1. `components` blocked copies; the leading `constrained_components` of them (-1: all)
  /// take the spaces' Dirichlet constraints (Oseen: the velocity, not the pressure).
  MatrixFreeTransfer(const Space& coarse, const Space& fine, int components = 1,
                     int constrained_components = -1);

  /// fine = P coarse (constrained fine DoFs: 0).
  void prolongate(const ExecSpace& exec, const Vector& coarse, const Vector& fine) const;
  /// coarse = P^T fine (constrained coarse DoFs: 0).
  void restrict_to_coarse(const ExecSpace& exec, const Vector& fine, const Vector& coarse) const;

 public:  // (CUDA: extended lambdas may not live in private member functions)
  struct Impl;

 private:
  std::shared_ptr<const Impl> impl_;
};

}  // namespace amphora::solvers::matrix_free
