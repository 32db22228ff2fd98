#pragma once
// A matrix-free finite-element operator on a Q_k space: mass, Laplace (scalar or vector,
// optionally with a variable coefficient), convection or linear elasticity, each a point functor
// (kernels/sumfac/point_functors.hpp) in the sum-factorised cell loop, with Dirichlet DoFs
// treated as identity rows (the constrained system of deal.II's MatrixFree operators).
// apply(exec, x, y) makes it usable by the Krylov solvers of src/solvers.
#include <cstddef>
#include <memory>

#include <Kokkos_Core.hpp>

#include "kernels/sumfac/shape_data.hpp"
#include "mesh/hex/qk_space.hpp"
#include "solvers/conjugate_gradient.hpp"
#include "kernels/sumfac/cell_operator_kernel.hpp"

namespace amphora::solvers::matrix_free {

/// The operators built in, one point functor each: mass (MassPoint), Laplace with an optional
/// coefficient field (LaplacePoint), convection by a velocity field (ConvectionPoint), isotropic
/// linear elasticity on dim components (ElasticityPoint), the stabilised Oseen operator of an
/// implicit flow step on dim + 1 components, velocity and pressure (OseenPoint), and its
/// volume-averaged form with a void fraction (VansPoint).
enum class OperatorKind { mass, laplace, convection, elasticity, oseen, vans };
using kernels::sumfac::GeometryMode;

template <int dim, class ExecSpace>
class MatrixFreeOperator {
 public:
  using memory_space = typename ExecSpace::memory_space;
  using Vector = Kokkos::View<double*, memory_space>;
  using Space = mesh::hex::QkSpace<dim, ExecSpace>;

  struct Options {
    OperatorKind kind = OperatorKind::laplace;
    GeometryMode geometry = GeometryMode::stored;
    kernels::sumfac::QuadratureKind quadrature = kernels::sumfac::QuadratureKind::gauss;
    int n_q = 0;  ///< points per direction; 0: degree + 1
    /// Blocked components: copies of a scalar operator (3 for the vector Laplace/mass of CEED
    /// BP2/4/6), dim for elasticity, dim + 1 for Oseen and VANS.
    int components = 1;
    double lambda = 1.0, mu = 1.0;  ///< Lame constants (elasticity)
    /// Oseen: viscosity, BDF coefficient over dt (of u), grad-div weight, 1 / dt in the SUPG/PSPG
    /// parameter (0: steady); `history`: only the terms of alpha u, alpha = 1 (the step's
    /// right-hand side from the history or a force). See kernels::sumfac::OseenPoint.
    double nu = 1.0, alpha = 0.0, grad_div = 0.0, dt_inverse = 0.0;
    bool history = false;
    /// Oseen: -nu lap u in the strong residual of the stabilisation (consistent; off: the
    /// usual simplification, O(h^2) where viscosity dominates a cell).
    bool viscous_residual = true;
    /// VANS: model B (grad p without the void fraction) instead of model A.
    bool model_b = false;
    /// VANS with `history`: only the SUPG/PSPG terms of a load density
    /// (kernels::sumfac::VansPoint).
    bool load_only = false;
    /// Components that take the space's Dirichlet constraints (the leading ones); -1: all, or
    /// for Oseen and VANS the velocity's dim (the pressure is free on every face).
    int constrained_components = -1;
    /// Use the run-time-size kernel even where a compiled one exists (it serves the pairs the
    /// table lacks on its own; mass and constant-coefficient Laplace).
    bool generic_kernel = false;
    /// Apply through the team schedule (kernels/sumfac/team_cell_kernel.hpp: a team's threads
    /// share each cell's sweeps) instead of a cell per thread: mass and Laplace with stored
    /// geometry; team_size threads per team (0: the kernel's choice).
    bool team_kernel = false;
    int team_size = 0;
    /// Laplace: coefficient a(x) as a Q_k field (n_dofs); convection and Oseen: the advecting
    /// velocity (dim blocked); VANS: the advecting velocity, the void fraction and the implicit
    /// drag (dim + 2 blocked, kernels::sumfac::VansPoint).
    Vector field;
  };

  MatrixFreeOperator(const Space& space, const Options& options)
      : MatrixFreeOperator(space, options, nullptr) {}
  /// As above, reusing the stored coefficients' arrays of `recycled` (left empty) where it has
  /// the same kind, geometry, quadrature and components and nothing else shares its data: an
  /// operator rebuilt each step with new coefficients then allocates nothing on the device.
  MatrixFreeOperator(const Space& space, const Options& options, MatrixFreeOperator&& recycled)
      : MatrixFreeOperator(space, options, &recycled) {}

  /// This operator with Options::viscous_residual off, sharing the stored coefficients (they do
  /// not depend on it): Oseen and VANS without the second derivatives, for a preconditioner.
  MatrixFreeOperator without_viscous_residual() const {
    MatrixFreeOperator c = *this;
    c.options_.viscous_residual = false;
    return c;
  }

  /// y = A x (constrained rows: y_i = x_i).
  void apply(const ExecSpace& exec, const Vector& x, const Vector& y) const;
  /// y = A x of the operator without Dirichlet rows or columns: with x holding Dirichlet values,
  /// the free rows give what they contribute (the lifting of inhomogeneous conditions).
  void apply_unconstrained(const ExecSpace& exec, const Vector& x, const Vector& y) const;
  /// CG's direction step in one sweep over the cells: p = z + beta p (p = z if beta is 0),
  /// q = A p; returns p.q over all entries. The update runs on the nodes a row of batches reads
  /// first and the product on those it writes last, while their lines are in cache
  /// (sumfac/row_touch.hpp): the three passes' 56 bytes per DoF become one sweep's 32 (z and p
  /// read, p and q written). In three passes on device spaces and across periodic wraps of the
  /// rows or slabs.
  double apply_direction(const ExecSpace& exec, const Vector& z, double beta, const Vector& p,
                         const Vector& q) const;
  /// The same as conjugate_gradient asks for it (with this rank's plain inner product).
  double apply_direction(const ExecSpace& exec, const Vector& z, double beta, const Vector& p,
                         const Vector& q, const LocalInnerProduct&) const {
    return apply_direction(exec, z, beta, p, q);
  }
  /// The diagonal of A, computed cell by cell (constrained rows: 1).
  void compute_diagonal(const ExecSpace& exec, const Vector& diagonal) const;
  /// Element matrices of every cell, host, [cell][j][i] (column j, local indices blocked by the
  /// functor's components), cell = lexicographic index; Dirichlet constraints not applied. For
  /// assembly (coarse grids, tests, comparisons).
  std::vector<double> element_matrices(const ExecSpace& exec) const;

  long size() const { return space_->n_dofs() * options_.components; }
  /// Components with identity rows at the space's constrained DoFs (Options).
  int constrained_components() const { return constrained_components_; }
  const Space& space() const { return *space_; }
  const Options& options() const { return options_; }
  int n_q() const { return n_q_; }
  /// Bytes of geometry data read by each application (coordinates for on_the_fly).
  std::size_t geometry_bytes() const;

 public:  // (CUDA: extended lambdas may not live in private member functions)
  struct Impl;

 private:
  MatrixFreeOperator(const Space& space, const Options& options, MatrixFreeOperator* recycled);
  /// Whether this operator's coefficients may be computed into other's arrays.
  bool may_recycle(const MatrixFreeOperator& other) const;

  const Space* space_;
  Options options_;
  int n_q_;
  int constrained_components_;
  std::shared_ptr<const Impl> impl_;
};

}  // namespace amphora::solvers::matrix_free
