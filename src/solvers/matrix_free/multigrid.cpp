#include "solvers/matrix_free/multigrid.hpp"

#include <sstream>
#include <stdexcept>

#include "kernels/blas1.hpp"
#include "solvers/matrix_free/assembly.hpp"

namespace amphora::solvers::matrix_free {

// A named namespace and a free function: CUDA's extended lambdas may not be defined in a
// constructor (nor in the lambdas inside one) or in an anonymous namespace.
namespace multigrid_detail {
/// start(i) from DoF i's global number alone (eigenvalue_start_entry).
template <class ExecSpace, class Global, class Vector>
void start_from_global_numbers(const ExecSpace& exec, const Global& global, const Vector& start) {
  Kokkos::parallel_for(
      "amphora::mg::start_vector",
      kernels::RangePolicy<ExecSpace>(exec, 0, static_cast<int>(start.extent(0))),
      KOKKOS_LAMBDA(int i) {
        start(i) = eigenvalue_start_entry(static_cast<unsigned>(global(i)));
      });
}
}  // namespace multigrid_detail

template <int dim, class ExecSpace>
struct MatrixFreeMultigrid<dim, ExecSpace>::Level {
  std::unique_ptr<Space> space;  // owned (coarse levels), null on the finest
  std::unique_ptr<Operator> owned;
  const Operator* op = nullptr;
  Vector inverse_diagonal, b, x, r;
  std::unique_ptr<ChebyshevSmoother<ExecSpace, Operator, Vector, typename Space::InnerProduct>>
      smoother;
};

template <int dim, class ExecSpace>
MatrixFreeMultigrid<dim, ExecSpace>::MatrixFreeMultigrid(const ExecSpace& exec,
                                                         const Operator& fine,
                                                         const MultigridOptions& options) {
  const auto& fo = fine.local().options();
  if (fo.kind != OperatorKind::laplace || fo.components != 1 || fo.field.extent(0) > 0)
    throw std::invalid_argument("MatrixFreeMultigrid: scalar constant-coefficient Laplace only");
  auto add_level = [&](std::unique_ptr<Space> space, const Operator* op) {
    auto L = std::make_unique<Level>();
    L->space = std::move(space);
    if (!op) {
      typename Operator::Local::Options o;
      o.kind = OperatorKind::laplace;
      o.geometry =
          L->space->global_mesh().cartesian() ? GeometryMode::cartesian : GeometryMode::stored;
      L->owned = std::make_unique<Operator>(*L->space, o);
      op = L->owned.get();
    }
    L->op = op;
    const Space& sp = op->space();
    const long n = op->size();
    L->inverse_diagonal = Vector("amphora::mg::inverse_diagonal", n);
    L->b = Vector("amphora::mg::b", n);
    L->x = Vector("amphora::mg::x", n);
    L->r = Vector("amphora::mg::r", n);
    op->compute_diagonal(exec, L->inverse_diagonal);
    const Vector d = L->inverse_diagonal;
    // The eigenvalue estimate starts from a vector of the global DoF numbers: the same
    // lambda_max, so the same smoother, on any rank count.
    const auto global = sp.global_indices();
    const Vector start("amphora::mg::start", n);
    kernels::blas1::reciprocal(exec, d);
    multigrid_detail::start_from_global_numbers(exec, global, start);
    L->smoother = std::make_unique<
        ChebyshevSmoother<ExecSpace, Operator, Vector, typename Space::InnerProduct>>(
        exec, *op, d, options.smoother, sp.inner_product(), start);
    levels_.push_back(std::move(L));
  };
  add_level(nullptr, &fine);
  // p-levels: halve the degree down to 1
  int degree = fine.space().degree();
  while (degree > 1) {
    degree /= 2;
    add_level(levels_.back()->op->space().with_degree(degree), nullptr);
  }
  // h-levels on Q1, while every slab keeps whole coarse cells
  for (;;) {
    const Space& current = levels_.back()->op->space();
    if (current.n_global() <= options.max_coarse_dofs || !current.can_coarsen()) break;
    add_level(current.coarsened(1), nullptr);
  }
  for (std::size_t l = 0; l + 1 < levels_.size(); ++l)
    transfers_.emplace_back(levels_[l + 1]->op->space().local(), levels_[l]->op->space().local());

  // Coarse solver: BoomerAMG on the coarsest operator of the whole box, on every rank.
  const Space& cs = levels_.back()->op->space();
  const mesh::hex::QkSpace<dim, ExecSpace> whole(cs.global_mesh(), 1);
  const MatrixFreeOperator<dim, ExecSpace> whole_op(whole, levels_.back()->op->local().options());
  coarse_ = std::make_unique<BoomerAMG>(assemble(exec, whole_op), options.coarse_amg);
  coarse_b_.assign(whole.n_dofs(), 0.0);
  coarse_x_.assign(whole.n_dofs(), 0.0);
  std::vector<long> owned(cs.n_owned());
  coarse_local_global_.resize(cs.n_local());
  for (long i = 0; i < cs.n_local(); ++i) {
    coarse_local_global_[i] = cs.global_index(i);
    if (i < cs.n_owned()) owned[i] = coarse_local_global_[i];
  }
  coarse_owned_global_ = cs.communicator().allgatherv(owned);
}

template <int dim, class ExecSpace>
MatrixFreeMultigrid<dim, ExecSpace>::~MatrixFreeMultigrid() = default;

template <int dim, class ExecSpace>
void MatrixFreeMultigrid<dim, ExecSpace>::apply(const ExecSpace& exec, const Vector& r,
                                                const Vector& z) const {
  vcycle(exec, 0, r, z);
}

template <int dim, class ExecSpace>
void MatrixFreeMultigrid<dim, ExecSpace>::vcycle(const ExecSpace& exec, std::size_t l,
                                                 const Vector& b, const Vector& x) const {
  const Level& L = *levels_[l];
  const Space& fine = L.op->space();
  if (l + 1 == levels_.size()) {
    auto bh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), b);
    const std::vector<double> mine(bh.data(), bh.data() + fine.n_owned());
    const std::vector<double> all = fine.communicator().allgatherv(mine);
    for (std::size_t k = 0; k < all.size(); ++k) coarse_b_[coarse_owned_global_[k]] = all[k];
    coarse_->vcycle(coarse_b_.data(), coarse_x_.data());
    auto xh = Kokkos::create_mirror_view(x);
    for (std::size_t i = 0; i < coarse_local_global_.size(); ++i)
      xh(i) = coarse_x_[coarse_local_global_[i]];
    Kokkos::deep_copy(x, xh);
    return;
  }
  const Level& C = *levels_[l + 1];
  const Space& coarse = C.op->space();
  L.smoother->smooth(exec, b, x, true);
  L.op->apply(exec, x, L.r);
  kernels::blas1::axpby(exec, 1.0, b, -1.0, L.r);  // r = b - A x
  fine.update_ghosts(exec, L.r);
  transfers_[l].restrict_to_coarse(exec, L.r, C.b);
  coarse.compress_add(exec, C.b);
  vcycle(exec, l + 1, C.b, C.x);
  coarse.update_ghosts(exec, C.x);
  transfers_[l].prolongate(exec, C.x, L.r);
  fine.compress_add(exec, L.r);
  kernels::blas1::axpy(exec, 1.0, L.r, x);
  L.smoother->smooth(exec, b, x, false);
}

template <int dim, class ExecSpace>
std::string MatrixFreeMultigrid<dim, ExecSpace>::describe() const {
  std::ostringstream s;
  for (std::size_t l = 0; l < levels_.size(); ++l) {
    const auto& sp = levels_[l]->op->space();
    s << (l ? " -> " : "") << "Q" << sp.degree() << " ";
    for (int d = 0; d < dim; ++d) s << (d ? "x" : "") << sp.global_mesh().cells[d];
  }
  s << " | coarse: BoomerAMG V-cycle on " << coarse_x_.size() << " DoFs";
  return s.str();
}

template class MatrixFreeMultigrid<2, kernels::DefaultExecSpace>;
template class MatrixFreeMultigrid<3, kernels::DefaultExecSpace>;
#if defined(KOKKOS_ENABLE_SERIAL) && defined(KOKKOS_ENABLE_OPENMP)
template class MatrixFreeMultigrid<2, Kokkos::Serial>;
template class MatrixFreeMultigrid<3, Kokkos::Serial>;
#endif

}  // namespace amphora::solvers::matrix_free
