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
// f / R 1: a weighted average). One rank; the coarse solve reads the residual back to the host.
#include <cmath>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <Kokkos_Core.hpp>

#include "kernels/blas1.hpp"
#include "kernels/host_vector.hpp"
#include "mesh/hex/qk_space.hpp"
#include "solvers/chebyshev.hpp"
#include "solvers/dense_least_squares.hpp"
#include "solvers/matrix_free/assembly.hpp"
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
  using Space = mesh::hex::QkSpace<dim, ExecSpace>;
  using Operator = MatrixFreeOperator<dim, ExecSpace>;
  using Vector = typename Operator::Vector;
  using Smoother = ChebyshevSmoother<ExecSpace, Operator, Vector>;

  /// The levels below `fine` (which must outlive this); no operators until update().
  explicit OseenMultigrid(const Space& fine, const OseenMultigridOptions& options = {})
      : options_(options) {
    levels_.emplace_back(std::make_unique<Level>());
    levels_[0]->space = &fine;
    for (;;) {
      const Space& s = *levels_.back()->space;
      std::unique_ptr<Space> next;
      if (s.degree() > 1) {
        next = std::make_unique<Space>(s.mesh(),
                                       options.degree_by_one ? s.degree() - 1 : s.degree() / 2);
      } else {
        if ((dim + 1) * s.n_dofs() <= options.max_coarse_dofs) break;
        auto m = s.mesh();  // n cells to ceil(n / 2): odd counts coarsen too (not nested)
        for (int d = 0; d < dim; ++d) m.cells[d] = (m.cells[d] + 1) / 2;
        next = std::make_unique<Space>(m, 1);
      }
      auto level = std::make_unique<Level>();
      level->owned = std::move(next);
      level->space = level->owned.get();
      transfers_.emplace_back(*level->space, s, dim + 1, dim);
      field_transfers_.emplace_back(*level->space, s, field_components(), 0);
      levels_.push_back(std::move(level));
    }
    const ExecSpace exec;
    for (std::size_t l = 0; l < levels_.size(); ++l) {
      Level& L = *levels_[l];
      const long n = (dim + 1) * L.space->n_dofs();
      L.b = Vector("amphora::oseen_mg::b", n), L.x = Vector("amphora::oseen_mg::x", n);
      L.r = Vector("amphora::oseen_mg::r", n), L.d = Vector("amphora::oseen_mg::d", n);
      if (l == 0) continue;
      const int nf = field_components();
      L.field = Vector("amphora::oseen_mg::field", nf * L.space->n_dofs());
      L.weight = Vector("amphora::oseen_mg::weight", nf * L.space->n_dofs());
      Vector one("amphora::oseen_mg::one", nf * levels_[l - 1]->space->n_dofs());
      kernels::blas1::fill(exec, one, 1.0);
      field_transfers_[l - 1].restrict_to_coarse(exec, one, L.weight);
    }
  }

  /// Rediscretises every level for the fine operator `A` (its options: coefficients and
  /// advecting velocity); sets the smoothers and factors the coarsest operator.
  void update(const ExecSpace& exec, const Operator& A) {
    // also where the time step's coefficient moved by more than 5 % (BDF1 -> BDF2: 1.5x; the
    // reused lambda_max bound has 20 % headroom)
    const double alpha = A.options().alpha;
    const bool refresh = !have_state_ || updates_ % options_.refresh_every == 0 ||
                         std::abs(alpha - alpha_) > 0.05 * std::abs(alpha_);
    ++updates_;
    have_state_ = true;
    if (refresh) alpha_ = alpha;
    for (std::size_t l = 0; l < levels_.size(); ++l) {
      Level& L = *levels_[l];
      if (l == 0) {
        L.owned_op = options_.viscous_residual
                         ? nullptr
                         : std::make_unique<Operator>(A.without_viscous_residual());
        L.op = L.owned_op ? L.owned_op.get() : &A;
      } else {
        restrict_field(exec, l, levels_[l - 1]->op->options().field);
        auto o = A.options();
        o.field = L.field;
        o.viscous_residual = o.viscous_residual && options_.viscous_residual;
        L.owned_op = L.owned_op ? std::make_unique<Operator>(*L.space, o, std::move(*L.owned_op))
                                : std::make_unique<Operator>(*L.space, o);
        L.op = L.owned_op.get();
      }
      if (l + 1 == levels_.size() && dense_coarse()) break;
      if (refresh) {
        L.op->compute_diagonal(exec, L.d);
        kernels::blas1::reciprocal(exec, L.d);
      }
      if (!refresh && L.smoother) {  // the kept interval and diagonal, in its vectors
        L.smoother->reuse(*L.op, L.upper);
        continue;
      }
      ChebyshevOptions so = options_.smoother;
      if (!refresh) so.lambda_max_bound = L.upper;
      if (L.smoother)
        L.smoother->refresh(exec, *L.op, so);
      else
        L.smoother = std::make_unique<Smoother>(exec, *L.op, L.d, so);
      L.upper = L.smoother->upper();
    }
    if (dense_coarse()) {
      coarse_ = std::make_unique<DenseLeastSquares>(assemble(exec, *levels_.back()->op));
      if (coarse_host_.extent(0) != levels_.back()->b.extent(0))
        coarse_host_ = HostVector("amphora::oseen_mg::coarse_host", levels_.back()->b.extent(0));
    }
  }

  /// What later updates reuse: the update count, alpha, and each smoothed level's interval end and
  /// inverse diagonal (empty before the first update).
  std::vector<double> state() const {
    if (!have_state_) return {};
    std::vector<double> out{static_cast<double>(updates_), alpha_};
    // The levels set_state fills: every one but a dense coarse level. (Not "those with a
    // smoother": a restored multigrid has none until its next update, and its checkpoint must
    // still fit.)
    for (std::size_t l = 0; l < levels_.size(); ++l) {
      if (l + 1 == levels_.size() && dense_coarse()) break;
      const Level& L = *levels_[l];
      const auto d = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), L.d);
      out.push_back(L.upper);
      out.insert(out.end(), d.data(), d.data() + d.extent(0));
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
      const std::size_t n = L.d.extent(0);
      if (at + 1 + n > s.size())
        throw std::invalid_argument("OseenMultigrid: the saved state does not fit these levels");
      L.upper = s[at];
      Kokkos::deep_copy(L.d, kernels::to_view<typename ExecSpace::memory_space>(
                                 std::vector<double>(s.begin() + at + 1, s.begin() + at + 1 + n)));
      at += 1 + n;
    }
    if (at != s.size())
      throw std::invalid_argument("OseenMultigrid: the saved state does not fit these levels");
  }

  /// Called with true before and false after each coarse solve (empty: none), so that a
  /// caller's timer can split a V-cycle into its smoothing and its coarse solve.
  void set_coarse_hook(std::function<void(bool)> hook) { coarse_hook_ = std::move(hook); }

  /// z = one V-cycle applied to r.
  void apply(const ExecSpace& exec, const Vector& r, const Vector& z) const {
    vcycle(exec, 0, r, z);
  }

  int n_levels() const { return static_cast<int>(levels_.size()); }
  /// e.g. "Q3 16^3 -> Q1 16^3 -> Q1 8^3 | dense coarse on 2048 DoFs".
  std::string describe() const {
    std::string s;
    for (std::size_t l = 0; l < levels_.size(); ++l) {
      const Space& sp = *levels_[l]->space;
      s += (l ? " -> Q" : "Q") + std::to_string(sp.degree()) + " " +
           std::to_string(sp.mesh().cells[0]) + "^" + std::to_string(dim);
    }
    const long n = (dim + 1) * levels_.back()->space->n_dofs();
    return s + (dense_coarse() ? " | dense coarse on " : " | smoothed coarse on ") +
           std::to_string(n) + " DoFs";
  }

  // (public for CUDA: extended lambdas may not live in private member functions)

  /// Level l's field (advecting velocity, void fraction, drag): R f / R 1 (the weighted average of
  /// the finer values).
  void restrict_field(const ExecSpace& exec, std::size_t l, const Vector& finer) const {
    const Vector f = levels_[l]->field, w = levels_[l]->weight;
    field_transfers_[l - 1].restrict_to_coarse(exec, finer, f);
    Kokkos::parallel_for(
        "amphora::oseen_mg::field", kernels::RangePolicy<ExecSpace>(exec, 0, int(f.extent(0))),
        KOKKOS_LAMBDA(int i) { f(i) = w(i) != 0.0 ? f(i) / w(i) : 0.0; });
  }

 private:
  struct Level {
    std::unique_ptr<Space> owned;  // null on the finest level
    const Space* space = nullptr;
    std::unique_ptr<Operator> owned_op;
    const Operator* op = nullptr;
    Vector b, x, r, d, field, weight;  // d: the inverse diagonal
    std::unique_ptr<Smoother> smoother;
    double upper = 0.0;
  };

  int field_components() const {
    return options_.field_components < 0 ? dim : options_.field_components;
  }
  bool dense_coarse() const {
    return (dim + 1) * levels_.back()->space->n_dofs() <= options_.max_dense_dofs;
  }

  void vcycle(const ExecSpace& exec, std::size_t l, const Vector& b, const Vector& x) const {
    const Level& L = *levels_[l];
    if (l + 1 == levels_.size()) {
      if (coarse_hook_) coarse_hook_(true);
      coarse_solve(exec, b, x);
      if (coarse_hook_) coarse_hook_(false);
      return;
    }
    L.smoother->smooth(exec, b, x, true);
    L.op->apply(exec, x, L.r);
    kernels::blas1::axpby(exec, 1.0, b, -1.0, L.r);  // r = b - A x
    const Level& C = *levels_[l + 1];
    transfers_[l].restrict_to_coarse(exec, L.r, C.b);
    vcycle(exec, l + 1, C.b, C.x);
    transfers_[l].prolongate(exec, C.x, L.r);
    kernels::blas1::axpy(exec, 1.0, L.r, x);
    L.smoother->smooth(exec, b, x, false);
  }

  void coarse_solve(const ExecSpace& exec, const Vector& b, const Vector& x) const {
    const Level& L = *levels_.back();
    if (!coarse_) {
      L.smoother->smooth(exec, b, x, true);
      for (int i = 1; i < options_.coarse_smoothing; ++i) L.smoother->smooth(exec, b, x, false);
      return;
    }
    Kokkos::deep_copy(exec, coarse_host_, b);
    exec.fence();
    coarse_->solve(coarse_host_.data(), coarse_host_.data());
    Kokkos::deep_copy(exec, x, coarse_host_);
  }

  OseenMultigridOptions options_;
  std::vector<std::unique_ptr<Level>> levels_;                       // 0: finest
  std::vector<MatrixFreeTransfer<dim, ExecSpace>> transfers_;        // l: levels l+1 and l
  std::vector<MatrixFreeTransfer<dim, ExecSpace>> field_transfers_;  // the field's, free
  std::unique_ptr<DenseLeastSquares> coarse_;
  using HostVector = Kokkos::View<double*, Kokkos::HostSpace>;
  HostVector coarse_host_;
  long updates_ = 0;
  bool have_state_ = false;
  double alpha_ = 0.0;  // the operator's alpha at the last refresh
  std::function<void(bool)> coarse_hook_;
};

}  // namespace amphora::solvers::matrix_free
