#pragma once
// Geometric multigrid V-cycle as a preconditioner for a matrix-free Laplace operator on a
// structured Q_k space: p-multigrid (degree halved down to 1, on the same cells), then
// h-multigrid on Q1 (cells halved while even), Chebyshev–Jacobi smoothing on every level,
// matrix-free transfers, and BoomerAMG on the assembled coarsest Q1 operator (one V-cycle).
// Distributed over the ranks of the fine operator's DistributedQkSpace: every level keeps the
// fine level's slabs (h-coarsening stops where a slab boundary would fall inside a coarse
// cell), transfers update ghosts before and compress after, and the coarsest problem, small,
// is gathered and solved on every rank alike. One rank: no communication at all.
#include <memory>
#include <string>
#include <vector>

#include "solvers/chebyshev.hpp"
#include "solvers/hypre_boomeramg.hpp"
#include "solvers/matrix_free/distributed_operator.hpp"
#include "solvers/matrix_free/transfer.hpp"

namespace amphora::solvers::matrix_free {

struct MultigridOptions {
  ChebyshevOptions smoother;
  /// Stop h-coarsening at or below this many DoFs (or when a cell count is odd).
  long max_coarse_dofs = 5000;
  BoomerAMGOptions coarse_amg;
};

template <int dim, class ExecSpace>
class MatrixFreeMultigrid {
 public:
  using Operator = DistributedOperator<dim, ExecSpace>;
  using Vector = typename Operator::Vector;
  using Space = mesh::hex::DistributedQkSpace<dim, ExecSpace>;

  /// Levels below the (scalar, coefficient-free Laplace) operator `fine`, which must outlive this.
  MatrixFreeMultigrid(const ExecSpace& exec, const Operator& fine,
                      const MultigridOptions& options = {});
  ~MatrixFreeMultigrid();

  /// z = one V-cycle applied to r.
  void apply(const ExecSpace& exec, const Vector& r, const Vector& z) const;

  int n_levels() const { return static_cast<int>(levels_.size()); }
  /// e.g. "Q4 32^3 -> Q2 32^3 -> Q1 32^3 -> Q1 16^3 -> ... | coarse AMG on 4913 DoFs".
  std::string describe() const;

 private:
  struct Level;
  void vcycle(const ExecSpace& exec, std::size_t l, const Vector& b, const Vector& x) const;
  std::vector<std::unique_ptr<Level>> levels_;                 // 0: finest
  std::vector<MatrixFreeTransfer<dim, ExecSpace>> transfers_;  // l: between l+1 (coarse) and l
  std::unique_ptr<BoomerAMG> coarse_;  // on the whole coarsest box, on every rank
  std::vector<long>
      coarse_owned_global_;  // global numbers of every rank's owned coarse DoFs, rank order
  std::vector<long> coarse_local_global_;  // global number of each local coarse DoF
  mutable std::vector<double> coarse_b_, coarse_x_;
};

}  // namespace amphora::solvers::matrix_free
