#pragma once
// Geometric multigrid V-cycle for the coupled, stabilised Oseen operator (velocity and
// pressure blocked, MatrixFreeOperator with OperatorKind::oseen), as the preconditioner of
// GMRES: p-multigrid on the same cells (degree halved down to 1), then h-multigrid on Q1
// (n cells to ceil(n / 2) while the level is larger than max_coarse_dofs; odd counts through
// the non-nested lattice interpolation), the matrix-free transfers on every component (the
// velocity's Dirichlet DoFs zeroed, the pressure free), Chebyshev around the coupled point Jacobi
// as the smoother with lambda_max from power iterations (the operator is not symmetric; Lethe's
// matrix-free solver, Blais et al., smooths the same way), and a dense least-squares solve of the
// assembled coarsest operator (singular where the pressure is fixed only up to a constant). Each
// level's operator is the fine one's, rediscretised with the advecting velocity restricted to it (R
// f / R 1: a weighted average). Distributed over the slabs of the fine DistributedQkSpace as
// MatrixFreeMultigrid is (every level keeps the fine slabs; on several ranks h-coarsening stops
// where a slab boundary would fall inside a coarse cell); the coarse solve gathers the residual
// on the host of every rank, which all solve the whole coarse system alike.
#include <cmath>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <Kokkos_Core.hpp>

#include "kernels/blas1.hpp"
#include "kernels/host_vector.hpp"
#include "mesh/hex/distributed_qk_space.hpp"
#include "mesh/hex/qk_space.hpp"
#include "solvers/chebyshev.hpp"
#include "solvers/dense_least_squares.hpp"
#include "solvers/matrix_free/assembly.hpp"
#include "solvers/matrix_free/distributed_operator.hpp"
#include "solvers/matrix_free/matrix_free_operator.hpp"
#include "solvers/matrix_free/transfer.hpp"

namespace amphora::solvers::matrix_free {

struct OseenMultigridOptions {
  ChebyshevOptions smoother{4, 5.0, 20, 0.0, true};
  /// Stop h-coarsening at or below this many DoFs (all components).
  long max_coarse_dofs = 1000;
  /// Above this many coarsest DoFs, the coarse "solve" is coarse_smoothing smoother sweeps.
  long max_dense_dofs = 4000;
  int coarse_smoothing = 8;
  /// Each level's diagonal and lambda_max are computed on the first update and again every
  /// this many; in between the smoothers keep them (the operator changes little from one step
  /// to the next, and its diagonal costs a cell application per cell DoF). state() and
  /// set_state() carry them through checkpoints, so restarts repeat runs bit for bit.
  int refresh_every = 10;
  /// Whether the levels' operators, the finest included, keep -nu lap u in the strong residual
  /// of the stabilisation (when the fine operator has it). false: the smoothers skip the second
  /// derivatives while GMRES still applies the full operator (Lethe's `mg enable hessians in
  /// jacobian = false`).
  bool viscous_residual = true;
  /// p-coarsening: degree k to k - 1 (true) or to k / 2.
  bool degree_by_one = true;
  /// Components of the fine operator's field, restricted to every level: dim (the advecting
  /// velocity) or, for VANS, dim + 2 (with the void fraction and the implicit drag).
  int field_components = -1;  ///< -1: dim
};

template <int dim, class ExecSpace>
class OseenMultigrid {
 public:
  using Space = mesh::hex::DistributedQkSpace<dim, ExecSpace>;
  using Operator = DistributedOperator<dim, ExecSpace>;
  using Local = MatrixFreeOperator<dim, ExecSpace>;
  using Vector = typename Operator::Vector;
  using Smoother = ChebyshevSmoother<ExecSpace, Operator, Vector, typename Space::InnerProduct>;

  /// The levels below `fine` (which must outlive this); no operators until update().
  explicit OseenMultigrid(const Space& fine, const OseenMultigridOptions& options = {})
      : options_(options) {
    levels_.emplace_back(std::make_unique<Level>());
    levels_[0]->space = &fine;
    for (;;) {
      const Space& s = *levels_.back()->space;
      std::unique_ptr<Space> next = coarser(s);
      if (!next) break;
      auto level = std::make_unique<Level>();
      level->owned = std::move(next);
      level->space = level->owned.get();
      transfers_.emplace_back(level->space->local(), s.local(), dim + 1, dim);
      field_transfers_.emplace_back(level->space->local(), s.local(), field_components(), 0);
      levels_.push_back(std::move(level));
    }
    const ExecSpace exec;
    for (std::size_t l = 0; l < levels_.size(); ++l) allocate(exec, l);
    const Space& cs = *levels_.back()->space;
    if (dense_coarse() && cs.communicator().size() > 1)
      whole_ = std::make_unique<mesh::hex::QkSpace<dim, ExecSpace>>(cs.global_mesh(), 1);
  }

  /// Rediscretises every level for the fine operator `A` (its options: coefficients and
  /// advecting velocity, whose ghost layer must hold the owners' values); sets the smoothers
  /// and factors the coarsest operator. A must outlive the V-cycles that follow.
  void update(const ExecSpace& exec, const Operator& A) {
    // also where the time step's coefficient moved by more than 5 % (BDF1 -> BDF2: 1.5x; the
    // reused lambda_max bound has 20 % headroom)
    const double alpha = A.local().options().alpha;
    const bool refresh = !have_state_ || updates_ % options_.refresh_every == 0 ||
                         std::abs(alpha - alpha_) > 0.05 * std::abs(alpha_);
    ++updates_;
    have_state_ = true;
    if (refresh) alpha_ = alpha;
    for (std::size_t l = 0; l < levels_.size(); ++l) {
      rediscretise(exec, l, A);
      if (l + 1 == levels_.size() && dense_coarse()) break;
      update_smoother(exec, *levels_[l], refresh);
    }
    if (dense_coarse()) {
      coarse_ = std::make_unique<DenseLeastSquares>(assemble(exec, coarse_operator()));
      coarse_whole_.assign((dim + 1) * levels_.back()->n_global, 0.0);
    }
  }

  /// What later updates reuse: the update count, alpha, and each smoothed level's interval end and
  /// inverse diagonal in global DoF order (so a checkpoint restarts on any rank count with the
  /// same levels); empty before the first update. Collective.
  std::vector<double> state() const {
    if (!have_state_) return {};
    std::vector<double> out{static_cast<double>(updates_), alpha_};
    // The levels set_state fills: every one but a dense coarse level. (Not "those with a
    // smoother": a restored multigrid has none until its next update, and its checkpoint must
    // still fit.)
    for (std::size_t l = 0; l < levels_.size(); ++l) {
      if (l + 1 == levels_.size() && dense_coarse()) break;
      const Level& L = *levels_[l];
      const std::vector<double> d = L.space->gather(L.d, dim + 1);
      out.push_back(L.upper);
      out.insert(out.end(), d.begin(), d.end());
    }
    return out;
  }
  /// Restores state() (of a multigrid on the same levels); empty: the next update refreshes.
  void set_state(const std::vector<double>& s) {
    have_state_ = !s.empty();
    if (s.empty()) return;
    std::size_t at = 2;
    updates_ = static_cast<long>(s[0]), alpha_ = s[1];
    for (std::size_t l = 0; l < levels_.size(); ++l) {
      Level& L = *levels_[l];
      if (l + 1 == levels_.size() && dense_coarse()) break;
      const std::size_t n = (dim + 1) * L.n_global;
      if (at + 1 + n > s.size())
        throw std::invalid_argument("OseenMultigrid: the saved state does not fit these levels");
      L.upper = s[at];
      L.space->scatter(std::vector<double>(s.begin() + at + 1, s.begin() + at + 1 + n), L.d,
                       dim + 1);
      at += 1 + n;
    }
    if (at != s.size())
      throw std::invalid_argument("OseenMultigrid: the saved state does not fit these levels");
  }

  /// Called with true before and false after each coarse solve (empty: none), so that a
  /// caller's timer can split a V-cycle into its smoothing and its coarse solve.
  void set_coarse_hook(std::function<void(bool)> hook) { coarse_hook_ = std::move(hook); }

  /// z = one V-cycle applied to r (owned entries; z's ghost layer is not meaningful).
  void apply(const ExecSpace& exec, const Vector& r, const Vector& z) const {
    vcycle(exec, 0, r, z);
  }

  int n_levels() const { return static_cast<int>(levels_.size()); }
  /// e.g. "Q3 16^3 -> Q1 16^3 -> Q1 8^3 | dense coarse on 2048 DoFs" (cells of the whole box).
  std::string describe() const {
    std::string s;
    for (std::size_t l = 0; l < levels_.size(); ++l) {
      const Space& sp = *levels_[l]->space;
      s += (l ? " -> Q" : "Q") + std::to_string(sp.degree()) + " " +
           std::to_string(sp.global_mesh().cells[0]) + "^" + std::to_string(dim);
    }
    const long n = (dim + 1) * levels_.back()->n_global;
    return s + (dense_coarse() ? " | dense coarse on " : " | smoothed coarse on ") +
           std::to_string(n) + " DoFs";
  }

  // (public for CUDA: extended lambdas may not live in private member functions)

  /// Level l's field (advecting velocity, void fraction, drag): R f / R 1 (the weighted average of
  /// the finer values, whose ghost layer holds the owners' values), its ghost layer updated.
  void restrict_field(const ExecSpace& exec, std::size_t l, const Vector& finer) const {
    const Level& L = *levels_[l];
    const Vector f = L.field, w = L.weight;
    field_transfers_[l - 1].restrict_to_coarse(exec, finer, f);
    L.space->compress_add(exec, f, field_components(), 0);
    Kokkos::parallel_for(
        "amphora::oseen_mg::field", kernels::RangePolicy<ExecSpace>(exec, 0, int(f.extent(0))),
        KOKKOS_LAMBDA(int i) { f(i) = w(i) != 0.0 ? f(i) / w(i) : 0.0; });
    L.space->update_ghosts(exec, f, field_components());
  }

 private:
  struct Level {
    std::unique_ptr<Space> owned;  // null on the finest level
    const Space* space = nullptr;
    long n_global = 0;                        // DoFs of the whole box, per component
    std::unique_ptr<Operator> owned_op;       // null on the finest level unless it drops the
    const Operator* op = nullptr;             // viscous residual
    Vector b, x, r, d, field, weight, start;  // d: the inverse diagonal
    std::unique_ptr<Smoother> smoother;
    double upper = 0.0;
  };

  int field_components() const {
    return options_.field_components < 0 ? dim : options_.field_components;
  }
  bool dense_coarse() const {
    return (dim + 1) * levels_.back()->n_global <= options_.max_dense_dofs;
  }

  /// The level below s, or null: Q_k to Q_(k-1) (or k / 2), then Q1 on half the cells while the
  /// level is larger than max_coarse_dofs. On several ranks h-coarsening stops where a slab
  /// boundary or a cell count is odd (can_coarsen); one rank takes n to ceil(n / 2).
  std::unique_ptr<Space> coarser(const Space& s) const {
    if (s.degree() > 1)
      return s.with_degree(options_.degree_by_one ? s.degree() - 1 : s.degree() / 2);
    if ((dim + 1) * s.n_global() <= options_.max_coarse_dofs) return nullptr;
    if (s.can_coarsen()) return s.coarsened(1);
    if (s.communicator().size() > 1) return nullptr;
    auto m = s.global_mesh();  // odd counts coarsen too (not nested)
    for (int d = 0; d < dim; ++d) m.cells[d] = (m.cells[d] + 1) / 2;
    return std::make_unique<Space>(m, 1, s.communicator());
  }

  /// Level l's vectors, its field's weight R 1 and the power iterations' start vector.
  void allocate(const ExecSpace& exec, std::size_t l) {
    Level& L = *levels_[l];
    const Space& sp = *L.space;
    L.n_global = sp.n_global();
    const long n = (dim + 1) * sp.n_local();
    L.b = Vector("amphora::oseen_mg::b", n), L.x = Vector("amphora::oseen_mg::x", n);
    L.r = Vector("amphora::oseen_mg::r", n), L.d = Vector("amphora::oseen_mg::d", n);
    // The start depends on the global DoF numbers alone: the same lambda_max on any rank count
    // (on one rank, the vector ChebyshevSmoother starts from by default).
    std::vector<double> start(n);
    for (long i = 0; i < sp.n_local(); ++i) {
      const long g = sp.global_index(i);
      for (int c = 0; c <= dim; ++c)
        start[c * sp.n_local() + i] =
            eigenvalue_start_entry(static_cast<unsigned>(c * L.n_global + g));
    }
    L.start = kernels::to_view<typename ExecSpace::memory_space>(start);
    if (l == 0) return;
    const int nf = field_components();
    L.field = Vector("amphora::oseen_mg::field", nf * sp.n_local());
    L.weight = Vector("amphora::oseen_mg::weight", nf * sp.n_local());
    Vector one("amphora::oseen_mg::one", nf * levels_[l - 1]->space->n_local());
    kernels::blas1::fill(exec, one, 1.0);
    field_transfers_[l - 1].restrict_to_coarse(exec, one, L.weight);
    sp.compress_add(exec, L.weight, nf, 0);
    sp.update_ghosts(exec, L.weight, nf);
  }

  /// Level l's operator for the fine operator A: A itself (less the viscous residual if so
  /// chosen) on the finest level, below it A's options with the field restricted.
  void rediscretise(const ExecSpace& exec, std::size_t l, const Operator& A) {
    Level& L = *levels_[l];
    if (l == 0) {  // A itself: a copy would share A's arrays, which A's owner recycles
      L.owned_op = options_.viscous_residual
                       ? nullptr
                       : std::make_unique<Operator>(A.without_viscous_residual());
      L.op = L.owned_op ? L.owned_op.get() : &A;
      return;
    }
    restrict_field(exec, l, levels_[l - 1]->op->local().options().field);
    auto o = A.local().options();
    o.field = L.field;
    o.viscous_residual = o.viscous_residual && options_.viscous_residual;
    L.owned_op = L.owned_op ? std::make_unique<Operator>(*L.space, o, std::move(*L.owned_op))
                            : std::make_unique<Operator>(*L.space, o);
    L.op = L.owned_op.get();
  }

  /// The level's inverse diagonal and Chebyshev interval: computed on a refresh, else kept.
  void update_smoother(const ExecSpace& exec, Level& L, bool refresh) {
    if (refresh) {
      L.op->compute_diagonal(exec, L.d);
      L.space->update_ghosts(exec, L.d, dim + 1);
      kernels::blas1::reciprocal(exec, L.d);
    }
    if (!refresh && L.smoother) {  // the kept interval and diagonal, in its vectors
      L.smoother->reuse(*L.op, L.upper);
      return;
    }
    ChebyshevOptions so = options_.smoother;
    if (!refresh) so.lambda_max_bound = L.upper;
    const auto inner = L.space->inner_product(dim + 1);
    if (L.smoother)
      L.smoother->refresh(exec, *L.op, so, inner, L.start);
    else
      L.smoother = std::make_unique<Smoother>(exec, *L.op, L.d, so, inner, L.start);
    L.upper = L.smoother->upper();
  }

  /// The coarsest operator on the whole box: this rank's on one rank; on several, rebuilt on
  /// the whole coarse box from the gathered field, identically on every rank.
  Local coarse_operator() const {
    const Level& C = *levels_.back();
    if (!whole_) return C.op->local();
    auto o = C.op->local().options();
    o.field = kernels::to_view<typename ExecSpace::memory_space>(
        C.space->gather(C.field, field_components()));
    return Local(*whole_, o);
  }

  void vcycle(const ExecSpace& exec, std::size_t l, const Vector& b, const Vector& x) const {
    const Level& L = *levels_[l];
    if (l + 1 == levels_.size()) {
      if (coarse_hook_) coarse_hook_(true);
      coarse_solve(exec, b, x);
      if (coarse_hook_) coarse_hook_(false);
      return;
    }
    const Level& C = *levels_[l + 1];
    L.smoother->smooth(exec, b, x, true);
    L.op->apply(exec, x, L.r);
    kernels::blas1::axpby(exec, 1.0, b, -1.0, L.r);  // r = b - A x
    L.space->update_ghosts(exec, L.r, dim + 1);
    transfers_[l].restrict_to_coarse(exec, L.r, C.b);
    C.space->compress_add(exec, C.b, dim + 1, dim);
    vcycle(exec, l + 1, C.b, C.x);
    C.space->update_ghosts(exec, C.x, dim + 1);
    transfers_[l].prolongate(exec, C.x, L.r);
    L.space->compress_add(exec, L.r, dim + 1, dim);
    kernels::blas1::axpy(exec, 1.0, L.r, x);
    L.smoother->smooth(exec, b, x, false);
  }

  /// The coarsest level: the dense least-squares solve of the whole box's system (gathered on
  /// every rank, which all solve it alike), or smoother sweeps.
  void coarse_solve(const ExecSpace& exec, const Vector& b, const Vector& x) const {
    const Level& L = *levels_.back();
    if (!coarse_) {
      L.smoother->smooth(exec, b, x, true);
      for (int i = 1; i < options_.coarse_smoothing; ++i) L.smoother->smooth(exec, b, x, false);
      return;
    }
    exec.fence();
    coarse_whole_ = L.space->gather(b, dim + 1);
    coarse_->solve(coarse_whole_.data(), coarse_whole_.data());
    L.space->scatter(coarse_whole_, x, dim + 1);
  }

  OseenMultigridOptions options_;
  std::vector<std::unique_ptr<Level>> levels_;                       // 0: finest
  std::vector<MatrixFreeTransfer<dim, ExecSpace>> transfers_;        // l: levels l+1 and l
  std::vector<MatrixFreeTransfer<dim, ExecSpace>> field_transfers_;  // the field's, free
  std::unique_ptr<mesh::hex::QkSpace<dim, ExecSpace>> whole_;  // several ranks: the coarse box
  std::unique_ptr<DenseLeastSquares> coarse_;
  mutable std::vector<double> coarse_whole_;
  long updates_ = 0;
  bool have_state_ = false;
  double alpha_ = 0.0;  // the operator's alpha at the last refresh
  std::function<void(bool)> coarse_hook_;
};

}  // namespace amphora::solvers::matrix_free
