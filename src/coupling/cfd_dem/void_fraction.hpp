#pragma once
// The void fraction of unresolved CFD-DEM on the flow's continuous Q_k space, particle-centred
// and smoothed by an L2 projection (Lethe's PCM with smoothing; Blais et al., J. Comput.
// Phys. 318 (2016) 201): the solid's volume is the sum of the particles' volumes at their
// centres, and eps in Q_k solves
//   (eps, v) + L^2 (grad eps, grad v) = (1, v) - sum_p V_p v(x_p)   for all v in Q_k,
// no boundary condition (the natural one). With v = 1: the integral of 1 - eps is the
// particles' volume, exactly; eps is continuous in time as particles cross cells, and L of
// about two diameters spreads a particle over its neighbourhood. Or quadrature-centred (QCM,
// quadrature_centred.hpp, 3D): the solid's volume is taken at the quadrature points from each
// particle's overlap with a reference sphere there, and (1, v) - (solid, v) is projected the
// same way. Bounded (as Lethe offers): eps minimises the projection's quadratic form within
// [lower, upper] (solvers/mprgp.hpp), and no longer holds the particles' volume exactly where a
// bound is active. Cartesian cells only.
#include <array>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <Kokkos_Core.hpp>

#include "kernels/blas1.hpp"
#include "coupling/cfd_dem/particle_mesh.hpp"
#include "coupling/cfd_dem/quadrature_centred.hpp"
#include "kernels/sumfac/qk_point_basis.hpp"
#include "kernels/sumfac/quadrature_1d.hpp"
#include "mesh/hex/distributed_qk_space.hpp"
#include "mesh/hex/qk_space.hpp"
#include "solvers/chebyshev.hpp"
#include "solvers/conjugate_gradient.hpp"
#include "solvers/mprgp.hpp"
#include "solvers/matrix_free/matrix_free_operator.hpp"

namespace amphora::coupling::cfd_dem {

enum class VoidFractionMethod { pcm, qcm };

struct VoidFractionOptions {
  VoidFractionMethod method = VoidFractionMethod::pcm;
  double smoothing_length = 0.0;                 ///< L of the projection (0: plain L2 projection)
  double qcm_radius = 0.0;                       ///< QCM's reference sphere (0: a cell's volume)
  double tolerance = 1e-13;                      ///< CG, relative
  bool bounded = false;                          ///< eps within [lower_bound, upper_bound]
  double lower_bound = 0.36, upper_bound = 1.0;  ///< Lethe's defaults
};

/// -V_p of particle i as spread reads a force, (i, 0): a sphere's (dim 3) or disc's volume.
template <int dim, class Radii>
struct NegativeVolume {
  Radii radius;
  KOKKOS_INLINE_FUNCTION double operator()(int i, int) const {
    const double r = radius(i);
    return dim == 3 ? -4.0 / 3.0 * M_PI * r * r * r : -M_PI * r * r;
  }
};

/// MPRGP's reductions over the ranks of a split space, `owned` entries here. (At namespace
/// scope: CUDA's extended lambdas may not take private member types as template arguments.)
struct RanksOfSlabs {
  const Communicator* comm;
  long owned;
  double sum(double v) const { return comm->sum(v); }
  double min(double v) const { return comm->min(v); }
};

template <int dim, class ExecSpace>
class VoidFraction {
 public:
  using Space = mesh::hex::QkSpace<dim, ExecSpace>;
  using DistributedSpace = mesh::hex::DistributedQkSpace<dim, ExecSpace>;
  using Mem = typename ExecSpace::memory_space;
  using Vector = Kokkos::View<double*, Mem>;
  using Points = Kokkos::View<double* [3], Kokkos::LayoutRight, Mem>;
  using Operator = solvers::matrix_free::MatrixFreeOperator<dim, ExecSpace>;

  /// On the whole box of `space` (one rank). Throws std::invalid_argument for curved cells, a
  /// negative length or QCM in 2D.
  VoidFraction(const Space& space, const VoidFractionOptions& options)
      : own_(std::make_unique<DistributedSpace>(space.mesh(), space.degree(),
                                                Communicator(MPI_COMM_SELF))),
        slabs_(own_.get()),
        options_(options),
        length_(options.smoothing_length) {
    setup();
  }
  /// On this rank's slab of `slabs` (which must outlive this): eps's owned entries and ghost
  /// layer, its projection a CG over the ranks. Collective.
  VoidFraction(const DistributedSpace& slabs, const VoidFractionOptions& options)
      : slabs_(&slabs), options_(options), length_(options.smoothing_length) {
    setup();
  }
  // The operators point at the slab's space: no copies, no moves.
  VoidFraction(const VoidFraction&) = delete;
  VoidFraction& operator=(const VoidFraction&) = delete;

  /// eps of the particles in rows [0, n) (centres x, radii r: this rank's own), its ghost
  /// layer updated; returns what CG did. QCM also reads the ghost rows [n, rows) (another
  /// rank's particles near the slab; own periodic images among them, told by their positions
  /// in `placed` when the ghosts were made (empty: x), are skipped along the directions with
  /// `own_images`: QuadratureCentred::load). Collective.
  solvers::SolverResult compute(const ExecSpace& exec, const Points& x, const Vector& radius, int n,
                                const Vector& eps, int rows = -1,
                                const std::array<bool, 3>& own_images = {true, true, true},
                                const Points& placed = Points()) const {
    const Vector b = rhs_;  // kept, like CG's work vectors: no allocation in a time step
    kernels::blas1::fill(exec, b, 0.0);
    if (qcm_) {
      const int unseen = qcm_->load(exec, x, radius, n, rows < 0 ? n : rows, own_images, placed, b);
      const long long all = slabs_->communicator().sum(static_cast<long long>(unseen));
      if (all > 0)
        throw std::runtime_error("void fraction (qcm): " + std::to_string(all) +
                                 " particle(s) share no volume with any reference sphere; raise "
                                 "qcm_radius");
    } else {
      deposit(exec, x, radius, n, b);
    }
    slabs_->compress_add(exec, b, 1, 0);
    kernels::blas1::axpy(exec, 1.0, mass_one_, b);
    solvers::SolverControl control;
    control.relative_tolerance = options_.tolerance;
    control.max_iterations = 2000;
    auto r = solvers::conjugate_gradient(exec, *this, b, eps, control,
                                         solvers::JacobiPreconditioner<Vector>{inverse_diagonal_},
                                         slabs_->inner_product(), cg_work_);
    if (options_.bounded && r.converged) bound(exec, b, eps, control, r);
    slabs_->update_ghosts(exec, eps);
    return r;
  }

  /// The last bounded computation's steps and nodes at each bound.
  const solvers::BoxResult& bounds() const { return bounds_; }

  /// The integral of a Q_k field over the box (its owned entries; collective).
  double integral(const ExecSpace& exec, const Vector& f) const {
    return slabs_->dot(exec, mass_one_, f);
  }

  const kernels::sumfac::QkPointBasis<dim>& basis() const { return basis_; }
  /// The integral of each basis function (the lumped mass; positive at every node, the ghost
  /// layer included).
  const Vector& basis_integrals() const { return mass_one_; }
  const DistributedSpace& slabs() const { return *slabs_; }

  /// y = (M + L^2 K) x (what CG applies; x's ghost layer updated first, y's owned entries
  /// summed over the ranks).
  void apply(const ExecSpace& exec, const Vector& x, const Vector& y) const {
    slabs_->update_ghosts(exec, x);
    laplace_->apply(exec, x, work_);
    mass_->apply(exec, x, y);
    kernels::blas1::axpy(exec, length_ * length_, work_, y);
    slabs_->compress_add(exec, y, 1, 0);
  }

  /// b -= V_p phi_j(x_p) for the first n particles (atomic: the sums' order, and so the last
  /// bits, follow the threads), this rank's partial sums.
  void deposit(const ExecSpace& exec, const Points& x, const Vector& radius, int n,
               const Vector& b) const {
    spread(exec, basis_, NegativeVolume<dim, Vector>{radius}, 1, x, n, b);
  }

 public:  // (CUDA: extended lambdas may not live in private member functions)
  /// 2 / (1.2 lambda_max) of the projection (Lanczos, as the Chebyshev smoother estimates it,
  /// from a start vector of global DoF numbers: the same on every rank count).
  double projected_gradient_step() const {
    const ExecSpace exec;
    const long n = slabs_->n_local();
    Vector ones("amphora::cfd_dem::ones", n), start("amphora::cfd_dem::start", n);
    kernels::blas1::fill(exec, ones, 1.0);
    const auto global = slabs_->global_indices();
    Kokkos::parallel_for(
        "amphora::cfd_dem::lanczos_start", kernels::RangePolicy<ExecSpace>(exec, 0, int(n)),
        KOKKOS_LAMBDA(int i) {
          start(i) = solvers::eigenvalue_start_entry(static_cast<unsigned>(global(i)));
        });
    using Inner = decltype(slabs_->inner_product());
    const solvers::ChebyshevSmoother<ExecSpace, VoidFraction, Vector, Inner> lanczos(
        exec, *this, ones, {}, slabs_->inner_product(), start);
    return 2.0 / lanczos.upper();
  }

 private:
  /// eps within the bounds, from the unbounded solution in eps (kept where it lies within
  /// them); r takes MPRGP's steps and whether it converged.
  void bound(const ExecSpace& exec, const Vector& b, const Vector& eps,
             const solvers::SolverControl& control, solvers::SolverResult& r) const {
    solvers::BoxControl c;
    c.lower = options_.lower_bound;
    c.upper = options_.upper_bound;
    c.relative_tolerance = control.relative_tolerance;
    c.max_iterations = control.max_iterations;
    c.step = step_;
    const RanksOfSlabs ranks{&slabs_->communicator(), slabs_->n_owned()};
    bounds_ = solvers::BoxResult();
    bounds_.converged = true;
    if (solvers::inside_box(exec, eps, c, ranks)) return;  // the unbounded eps, bit for bit
    bounds_ = solvers::mprgp(exec, *this, b, eps, c, ranks, box_work_);
    r.iterations += bounds_.iterations;
    r.converged = bounds_.converged;
  }

  void setup() {
    const Space& space = slabs_->local();
    if (!space.mesh().cartesian())
      throw std::invalid_argument("void fraction: curved cells are not supported (Cartesian only)");
    if (!(length_ >= 0))
      throw std::invalid_argument("void fraction: smoothing length must be >= 0");
    if (options_.bounded &&
        !(options_.lower_bound > 0.0 && options_.lower_bound < options_.upper_bound &&
          options_.upper_bound <= 1.0))
      throw std::invalid_argument("void fraction: bounds must satisfy 0 < lower < upper <= 1");
    basis_ = point_basis(space.mesh(), space.lattice());
    make_operators();
    if (options_.method == VoidFractionMethod::qcm) {
      if constexpr (dim == 3) {
        const Space whole(slabs_->global_mesh(), space.degree());
        qcm_ = std::make_unique<QuadratureCentred<ExecSpace>>(
            point_basis(whole.mesh(), whole.lattice()), basis_, slabs_->first_cell(),
            options_.qcm_radius);
      } else {
        throw std::invalid_argument("void fraction: qcm is 3D only");
      }
    }
  }

  kernels::sumfac::QkPointBasis<dim> point_basis(
      const mesh::hex::StructuredHexMesh<dim>& mesh,
      const kernels::sumfac::QkLattice<dim>& lattice) const {
    kernels::sumfac::QkPointBasis<dim> b;
    b.lattice = lattice;
    for (int d = 0; d < dim; ++d) {
      b.lower[d] = mesh.lower[d];
      b.h[d] = (mesh.upper[d] - mesh.lower[d]) / mesh.cells[d];
    }
    const auto gl = kernels::sumfac::gauss_lobatto(lattice.degree + 1);
    for (int a = 0; a <= lattice.degree; ++a) b.nodes[a] = gl.points[a];
    return b;
  }

  void make_operators() {
    const Space& space = slabs_->local();
    typename Operator::Options o;
    o.constrained_components = 0;  // no boundary condition: the natural one
    o.kind = solvers::matrix_free::OperatorKind::mass;
    mass_ = std::make_unique<Operator>(space, o);
    o.kind = solvers::matrix_free::OperatorKind::laplace;
    laplace_ = std::make_unique<Operator>(space, o);
    const ExecSpace exec;
    const long n = space.n_dofs();
    work_ = Vector("amphora::cfd_dem::void_fraction_work", n);
    mass_one_ = Vector("amphora::cfd_dem::mass_one", n);
    rhs_ = Vector("amphora::cfd_dem::void_fraction_rhs", n);
    inverse_diagonal_ = Vector("amphora::cfd_dem::void_fraction_diagonal", n);
    kernels::blas1::fill(exec, work_, 1.0);
    mass_->apply(exec, work_, mass_one_);
    slabs_->compress_add(exec, mass_one_, 1, 0);
    slabs_->update_ghosts(exec, mass_one_);
    mass_->compute_diagonal(exec, inverse_diagonal_);
    laplace_->compute_diagonal(exec, work_);
    kernels::blas1::axpy(exec, length_ * length_, work_, inverse_diagonal_);
    slabs_->compress_add(exec, inverse_diagonal_, 1, 0);
    kernels::blas1::reciprocal(exec, inverse_diagonal_);
    if (options_.bounded) step_ = projected_gradient_step();
  }

  std::unique_ptr<DistributedSpace> own_;  // the one-rank split of a whole-box space
  const DistributedSpace* slabs_;
  VoidFractionOptions options_;
  double length_;
  std::unique_ptr<QuadratureCentred<ExecSpace>> qcm_;
  kernels::sumfac::QkPointBasis<dim> basis_;
  std::unique_ptr<Operator> mass_, laplace_;
  Vector mass_one_, inverse_diagonal_, work_, rhs_;
  mutable solvers::CgWorkspace<Vector> cg_work_;
  double step_ = 0.0;  // MPRGP's projected-gradient step
  mutable solvers::BoxWorkspace<Vector> box_work_;
  mutable solvers::BoxResult bounds_;
};

}  // namespace amphora::coupling::cfd_dem
