#include "solvers/matrix_free/assembly.hpp"

#include <algorithm>
#include <stdexcept>
#include <utility>

namespace amphora::solvers::matrix_free {

template <int dim, class ExecSpace>
CsrMatrix assemble(const ExecSpace& exec, const MatrixFreeOperator<dim, ExecSpace>& op) {
  if (op.options().components != 1) throw std::invalid_argument("assemble: scalar operators only");
  const auto& space = op.space();
  const auto& lat = space.lattice();
  const int k = lat.degree, np = k + 1;
  int nd = 1;
  for (int d = 0; d < dim; ++d) nd *= np;
  const std::vector<double> elements = op.element_matrices(exec);
  const long n = lat.n_dofs();
  const long n_cells = space.mesh().n_cells();
  // rows of (col, value), merged per row
  std::vector<std::vector<std::pair<int, double>>> rows(n);
  std::vector<long> dof(nd);
  for (long c = 0; c < n_cells; ++c) {
    int cell[3] = {0, 0, 0};
    long rest = c;
    for (int d = 0; d < dim; ++d)
      cell[d] = static_cast<int>(rest % lat.cells[d]), rest /= lat.cells[d];
    for (int j = 0; j < nd; ++j) {
      int ijk[3] = {0, 0, 0}, r = j;
      for (int d = 0; d < dim; ++d) ijk[d] = cell[d] * k + r % np, r /= np;
      dof[j] = lat.constrained(ijk) ? -1 : lat.dof_index(ijk);
    }
    const double* e = elements.data() + c * nd * nd;  // [j][i]: column j
    for (int j = 0; j < nd; ++j)
      for (int i = 0; i < nd; ++i)
        if (dof[i] >= 0 && dof[j] >= 0)
          rows[dof[i]].emplace_back(static_cast<int>(dof[j]), e[j * nd + i]);
  }
  auto cons = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), space.constrained_dofs());
  for (std::size_t i = 0; i < cons.extent(0); ++i)
    rows[cons(i)].emplace_back(static_cast<int>(cons(i)), 1.0);
  CsrMatrix A;
  A.n = n;
  A.row_ptr.assign(n + 1, 0);
  for (long i = 0; i < n; ++i) {
    auto& row = rows[i];
    std::sort(row.begin(), row.end(),
              [](const auto& a, const auto& b) { return a.first < b.first; });
    for (std::size_t m = 0; m < row.size(); ++m) {
      if (m > 0 && row[m].first == A.cols.back()) {
        A.values.back() += row[m].second;
      } else {
        A.cols.push_back(row[m].first);
        A.values.push_back(row[m].second);
      }
    }
    A.row_ptr[i + 1] = static_cast<long>(A.cols.size());
    std::vector<std::pair<int, double>>().swap(row);
  }
  return A;
}

#define AMPHORA_ASSEMBLE(E)                                                     \
  template CsrMatrix assemble<2, E>(const E&, const MatrixFreeOperator<2, E>&); \
  template CsrMatrix assemble<3, E>(const E&, const MatrixFreeOperator<3, E>&);
AMPHORA_IF_SERIAL(AMPHORA_ASSEMBLE(Kokkos::Serial))
AMPHORA_IF_OPENMP(AMPHORA_ASSEMBLE(Kokkos::OpenMP))
AMPHORA_IF_CUDA(AMPHORA_ASSEMBLE(Kokkos::Cuda))

}  // namespace amphora::solvers::matrix_free
