#pragma once
// A Q_k space distributed over MPI ranks: the box's cells are split along the last direction
// (z in 3D, y in 2D) into one slab per rank, and each rank holds a QkSpace on its slab. The node
// layer two neighbouring slabs share is owned by the upper slab (in a periodic direction, rank 0
// owns the layer the last rank wraps onto), so a rank's owned DoFs are the prefix
// [0, n_owned()) of its local numbering (the lattice runs x fastest, the split direction
// slowest) and the copy of the shared top layer is its ghost layer.
//
// A matrix-free operator applies on a rank's slab as it would on the whole box (interface
// faces are natural, i.e. Neumann, so cells add their partial sums there); update_ghosts()
// before and compress_add() after complete it, as deal.II's LinearAlgebra::distributed::Vector
// does (update_ghost_values / compress(add)). Vectors with several components are blocked per
// component (QkSpace's layout), each block distributed the same way.
#include <memory>
#include <vector>

#include <Kokkos_Core.hpp>

#include "mesh/box_decomposition.hpp"
#include "base/communicator.hpp"
#include "mesh/hex/qk_space.hpp"

namespace amphora::mesh::hex {

template <int dim, class ExecSpace>
class DistributedQkSpace {
 public:
  using memory_space = typename ExecSpace::memory_space;
  using Vector = Kokkos::View<double*, memory_space>;
  using Space = QkSpace<dim, ExecSpace>;

  /// Splits `global` over the ranks of `comm` by the foundation's BoxDecomposition, along the
  /// last direction only (DecompositionError for more ranks than cells there).
  DistributedQkSpace(const StructuredHexMesh<dim>& global, int degree, const Communicator& comm);
  /// This rank's slab given: cells [first_cell, end_cell) along the last direction (the slabs
  /// of the ranks, in rank order, must tile the box).
  DistributedQkSpace(const StructuredHexMesh<dim>& global, int degree, const Communicator& comm,
                     int first_cell, int end_cell);

  /// True on every rank if every cell count of the box and every slab boundary is even, so
  /// coarsened() keeps each coarse cell on the rank of its children. Collective.
  bool can_coarsen() const;
  /// The same partition of the box with half the cells per direction (degree 1..8 as given).
  std::unique_ptr<DistributedQkSpace> coarsened(int degree) const;
  /// The same partition at another degree.
  std::unique_ptr<DistributedQkSpace> with_degree(int degree) const;

  const Space& local() const { return *local_; }
  const StructuredHexMesh<dim>& global_mesh() const { return global_; }
  const Communicator& communicator() const { return comm_; }
  int degree() const { return local_->degree(); }
  /// This rank's slab along the last direction: cells [first_cell(), end_cell()).
  int first_cell() const { return first_cell_; }
  int end_cell() const { return end_cell_; }
  /// DoFs of the local numbering (owned, then the ghost layer), per component.
  long n_local() const { return local_->n_dofs(); }
  /// DoFs this rank owns: the prefix [0, n_owned()) of the local numbering, per component.
  long n_owned() const { return n_owned_; }
  /// DoFs of the whole box, per component.
  long n_global() const;
  /// Global DoF number (of the undistributed QkSpace on the whole box) of local DoF i (host).
  long global_index(long i) const;
  /// global_index() of every local DoF (owned and ghost layer).
  Kokkos::View<long*, memory_space> global_indices() const;

  /// Copies the owners' values into this rank's ghost layer of x. Collective.
  void update_ghosts(const ExecSpace& exec, const Vector& x, int components = 1) const;
  /// Adds this rank's partial sums on its ghost layer to the owner's entries (only where the
  /// DoF is free: a constrained row is the identity on every rank holding it). Only the first
  /// `constrained` components take the constraints (-1: all), as the Oseen operator's velocity
  /// does and its pressure does not. The ghost layer is left as it was. Collective.
  void compress_add(const ExecSpace& exec, const Vector& y, int components = 1,
                    int constrained = -1) const;
  /// The whole box's vector in the global DoF order of each component block (blocked as a
  /// QkSpace on the whole box), on every rank, from the owned entries: the owned parts in rank
  /// order are that order. Host; for small coarse problems and checkpoints. Collective.
  std::vector<double> gather(const Vector& x, int components = 1) const;
  /// This rank's local entries (owned and ghost layer, blocked) of a whole-box vector in
  /// gather()'s order (host).
  std::vector<double> local_entries(const std::vector<double>& whole, int components = 1) const;
  /// x = local_entries(whole), on the device.
  void scatter(const std::vector<double>& whole, const Vector& x, int components = 1) const;
  /// Sum over ranks of the owned entries' products. Collective.
  double dot(const ExecSpace& exec, const Vector& x, const Vector& y, int components = 1) const;
  /// x += a p, r -= a q on owned entries; returns the sum over ranks of r.r there. Collective.
  double fused_cg_update(const ExecSpace& exec, double alpha, const Vector& p, const Vector& q,
                         const Vector& x, const Vector& r, int components = 1) const;

  /// The inner product the Krylov solvers take (conjugate_gradient's `Inner`).
  struct InnerProduct {
    const DistributedQkSpace* space;
    int components = 1;
    double operator()(const ExecSpace& exec, const Vector& x, const Vector& y) const {
      return space->dot(exec, x, y, components);
    }
    static constexpr bool fuses_cg_update = true;
    /// CG's x += a p, r -= a q on the owned entries in one pass; returns r.r over all ranks.
    /// (Ghost layers are left stale: an operator application updates them first.)
    template <class E, class V>
    double fused_update(const E& exec, double alpha, const V& p, const V& q, const V& x,
                        const V& r) const {
      return space->fused_cg_update(exec, alpha, p, q, x, r, components);
    }
  };
  InnerProduct inner_product(int components = 1) const { return InnerProduct{this, components}; }

 private:
  DistributedQkSpace(const StructuredHexMesh<dim>& global, int degree, const Communicator& comm,
                     const Box& slab);
  /// Entries of component c this rank owns, in a blocked vector.
  Kokkos::pair<long, long> owned(int c) const { return {c * n_local(), c * n_local() + n_owned_}; }

  StructuredHexMesh<dim> global_;
  Communicator comm_;
  std::unique_ptr<Space> local_;
  int first_cell_ = 0, end_cell_ = 0;
  long layer_ = 0;  // DoFs per node layer of the last direction
  long n_owned_ = 0;
  int prev_ = -1;       // rank holding our bottom layer as its ghosts, or MPI_PROC_NULL
  int next_ = -1;       // rank owning our top layer, or MPI_PROC_NULL (we own it)
  Vector free_bottom_;  // 1 on free DoFs of the bottom layer, 0 on constrained ones
  Vector received_;     // compress_add's receive buffer (one layer)
};

}  // namespace amphora::mesh::hex
