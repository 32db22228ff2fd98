#pragma once
// A matrix-free operator on a DistributedQkSpace: the rank's slab operator between the ghost
// update of x and the compression of y, so y = A x holds on every owned DoF as on one rank.
// x's ghost layer is overwritten with the owners' values (x is otherwise unchanged); y's ghost
// layer holds this rank's partial sums afterwards and is not meaningful.
#include <utility>

#include "mesh/hex/distributed_qk_space.hpp"
#include "solvers/conjugate_gradient.hpp"
#include "solvers/matrix_free/matrix_free_operator.hpp"

namespace amphora::solvers::matrix_free {

template <int dim, class ExecSpace>
class DistributedOperator {
 public:
  using Space = mesh::hex::DistributedQkSpace<dim, ExecSpace>;
  using Local = MatrixFreeOperator<dim, ExecSpace>;
  using Vector = typename Local::Vector;

  DistributedOperator(const Space& space, const typename Local::Options& options)
      : space_(&space), local_(space.local(), options) {}
  /// The slab operator `local` (on space.local(), sharing its coefficients) as a distributed one.
  DistributedOperator(const Space& space, Local local) : space_(&space), local_(std::move(local)) {}
  /// As the first, in the device arrays of `recycled` (MatrixFreeOperator's recycling constructor).
  DistributedOperator(const Space& space, const typename Local::Options& options,
                      DistributedOperator&& recycled)
      : space_(&space), local_(space.local(), options, std::move(recycled.local_)) {}

  /// This operator without -nu lap u in the stabilisation's residual (Oseen, VANS), sharing
  /// the stored coefficients: MatrixFreeOperator::without_viscous_residual.
  DistributedOperator without_viscous_residual() const {
    DistributedOperator c = *this;
    c.local_ = local_.without_viscous_residual();
    return c;
  }

  void apply(const ExecSpace& exec, const Vector& x, const Vector& y) const {
    space_->update_ghosts(exec, x, components());
    local_.apply(exec, x, y);
    space_->compress_add(exec, y, components(), local_.constrained_components());
  }
  /// CG's direction step (MatrixFreeOperator::apply_direction): p = z + beta p, q = A p, returns
  /// p.q summed over the ranks. In one sweep over the cells on a single rank; on several, in
  /// passes around the ghost exchanges.
  double apply_direction(const ExecSpace& exec, const Vector& z, double beta, const Vector& p,
                         const Vector& q, const typename Space::InnerProduct& dot) const {
    if (space_->communicator().size() == 1 && space_->n_owned() == space_->n_local())
      return local_.apply_direction(exec, z, beta, p, q);
    return direction_in_passes(exec, *this, z, beta, p, q, dot);
  }
  /// The diagonal on owned DoFs (constrained rows: 1).
  void compute_diagonal(const ExecSpace& exec, const Vector& diagonal) const {
    local_.compute_diagonal(exec, diagonal);
    space_->compress_add(exec, diagonal, components(), local_.constrained_components());
  }

  const Space& space() const { return *space_; }
  const Local& local() const { return local_; }
  int components() const { return local_.options().components; }
  /// Entries of a rank's vectors (owned and ghost layer).
  long size() const { return local_.size(); }

 private:
  const Space* space_;
  Local local_;
};

}  // namespace amphora::solvers::matrix_free
