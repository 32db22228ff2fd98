#include "solvers/matrix_free/multigrid.hpp"

#include <sstream>
#include <stdexcept>

#include "solvers/matrix_free/assembly.hpp"

namespace amphora::solvers {

template <int dim, class ExecSpace>
struct MatrixFreeMultigrid<dim, ExecSpace>::Level {
  std::unique_ptr<Space> space;       // owned (coarse levels), null on the finest
  std::unique_ptr<Operator> owned;
  const Operator* op = nullptr;
  Vector inverse_diagonal, b, x, r;
  std::unique_ptr<ChebyshevSmoother<ExecSpace, Operator, Vector>> smoother;
};

template <int dim, class ExecSpace>
MatrixFreeMultigrid<dim, ExecSpace>::MatrixFreeMultigrid(const ExecSpace& exec, const Operator& fine,
                                                         const MultigridOptions& options) {
  const auto& fo = fine.options();
  if (fo.kind != OperatorKind::laplace || fo.components != 1 || fo.field.extent(0) > 0)
    throw std::invalid_argument("MatrixFreeMultigrid: scalar constant-coefficient Laplace only");
  auto add_level = [&](std::unique_ptr<Space> space, const Operator* op) {
    auto L = std::make_unique<Level>();
    L->space = std::move(space);
    if (!op) {
      typename Operator::Options o;
      o.kind = OperatorKind::laplace;
      o.geometry = L->space->mesh().cartesian() ? GeometryMode::cartesian : GeometryMode::stored;
      L->owned = std::make_unique<Operator>(*L->space, o);
      op = L->owned.get();
    }
    L->op = op;
    const long n = op->size();
    L->inverse_diagonal = Vector("amphora::mg::inverse_diagonal", n);
    L->b = Vector("amphora::mg::b", n);
    L->x = Vector("amphora::mg::x", n);
    L->r = Vector("amphora::mg::r", n);
    op->compute_diagonal(exec, L->inverse_diagonal);
    const Vector d = L->inverse_diagonal;
    Kokkos::parallel_for("amphora::mg::invert_diagonal", RangePolicy<ExecSpace>(exec, 0, static_cast<int>(n)),
                         KOKKOS_LAMBDA(int i) { d(i) = 1.0 / d(i); });
    L->smoother = std::make_unique<ChebyshevSmoother<ExecSpace, Operator, Vector>>(exec, *op, d, options.smoother);
    levels_.push_back(std::move(L));
  };
  add_level(nullptr, &fine);
  // p-levels: halve the degree down to 1
  auto mesh = fine.space().mesh();
  int degree = fine.space().degree();
  while (degree > 1) {
    degree /= 2;
    add_level(std::make_unique<Space>(mesh, degree), nullptr);
  }
  // h-levels on Q1
  for (;;) {
    const Space& current = levels_.back()->op->space();
    if (current.n_dofs() <= options.max_coarse_dofs) break;
    bool even = true;
    for (int d = 0; d < dim; ++d) even = even && current.mesh().cells[d] % 2 == 0;
    if (!even) break;
    add_level(std::make_unique<Space>(current.mesh().coarsened(), 1), nullptr);
  }
  for (std::size_t l = 0; l + 1 < levels_.size(); ++l)
    transfers_.emplace_back(levels_[l + 1]->op->space(), levels_[l]->op->space());
  // coarse solver: BoomerAMG on the assembled coarsest operator
  coarse_ = std::make_unique<BoomerAMG>(assemble(exec, *levels_.back()->op), options.coarse_amg);
  coarse_b_.resize(levels_.back()->op->size());
  coarse_x_.resize(levels_.back()->op->size());
}

template <int dim, class ExecSpace>
MatrixFreeMultigrid<dim, ExecSpace>::~MatrixFreeMultigrid() = default;

template <int dim, class ExecSpace>
void MatrixFreeMultigrid<dim, ExecSpace>::apply(const ExecSpace& exec, const Vector& r, const Vector& z) const {
  vcycle(exec, 0, r, z);
}

template <int dim, class ExecSpace>
void MatrixFreeMultigrid<dim, ExecSpace>::vcycle(const ExecSpace& exec, std::size_t l, const Vector& b,
                                                 const Vector& x) const {
  const Level& L = *levels_[l];
  if (l + 1 == levels_.size()) {
    auto bh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), b);
    coarse_->vcycle(bh.data(), coarse_x_.data());
    auto xh = Kokkos::create_mirror_view(x);
    for (std::size_t i = 0; i < coarse_x_.size(); ++i) xh(i) = coarse_x_[i];
    Kokkos::deep_copy(x, xh);
    return;
  }
  const Level& C = *levels_[l + 1];
  L.smoother->smooth(exec, b, x, true);
  L.op->apply(exec, x, L.r);
  blas1::axpby(exec, 1.0, b, -1.0, L.r);  // r = b - A x
  transfers_[l].restrict_to_coarse(exec, L.r, C.b);
  vcycle(exec, l + 1, C.b, C.x);
  transfers_[l].prolongate(exec, C.x, L.r);
  blas1::axpy(exec, 1.0, L.r, x);
  L.smoother->smooth(exec, b, x, false);
}

template <int dim, class ExecSpace>
std::string MatrixFreeMultigrid<dim, ExecSpace>::describe() const {
  std::ostringstream s;
  for (std::size_t l = 0; l < levels_.size(); ++l) {
    const auto& sp = levels_[l]->op->space();
    s << (l ? " -> " : "") << "Q" << sp.degree() << " ";
    for (int d = 0; d < dim; ++d) s << (d ? "x" : "") << sp.mesh().cells[d];
  }
  s << " | coarse: BoomerAMG V-cycle on " << levels_.back()->op->size() << " DoFs";
  return s.str();
}

template class MatrixFreeMultigrid<2, DefaultExecSpace>;
template class MatrixFreeMultigrid<3, DefaultExecSpace>;
#if defined(KOKKOS_ENABLE_SERIAL) && defined(KOKKOS_ENABLE_OPENMP)
template class MatrixFreeMultigrid<2, Kokkos::Serial>;
template class MatrixFreeMultigrid<3, Kokkos::Serial>;
#endif

}  // namespace amphora::solvers
