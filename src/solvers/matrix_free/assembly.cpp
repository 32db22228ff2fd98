#include "solvers/matrix_free/assembly.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace amphora::solvers::matrix_free {

template <int dim, class ExecSpace>
CsrMatrix assemble(const ExecSpace& exec, const MatrixFreeOperator<dim, ExecSpace>& op) {
  const auto& space = op.space();
  const auto& lat = space.lattice();
  const int k = lat.degree, np = k + 1;
  const int comps = op.options().components, constrained = op.constrained_components();
  int nd = 1;
  for (int d = 0; d < dim; ++d) nd *= np;
  const std::vector<double> elements = op.element_matrices(exec);
  const long n_dofs = lat.n_dofs(), n = comps * n_dofs;
  const long n_cells = space.mesh().n_cells();
  // element matrices of the functor's components (m = fc nd), repeated for blocked copies
  const int m = static_cast<int>(std::lround(std::sqrt(double(elements.size()) / n_cells)));
  const int fc = m / nd;
  // rows of (col, value), merged per row
  std::vector<std::vector<std::pair<int, double>>> rows(n);
  std::vector<long> dof(m);
  for (long c = 0; c < n_cells; ++c) {
    int cell[3] = {0, 0, 0};
    long rest = c;
    for (int d = 0; d < dim; ++d)
      cell[d] = static_cast<int>(rest % lat.cells[d]), rest /= lat.cells[d];
    const double* e = elements.data() + c * m * m;  // [j][i]: column j
    for (int block = 0; block < comps; block += fc) {
      for (int j = 0; j < nd; ++j) {
        int ijk[3] = {0, 0, 0}, r = j;
        for (int d = 0; d < dim; ++d) ijk[d] = cell[d] * k + r % np, r /= np;
        for (int f = 0; f < fc; ++f) {
          const int comp = block + f;
          dof[f * nd + j] =
              comp < constrained && lat.constrained(ijk) ? -1 : comp * n_dofs + lat.dof_index(ijk);
        }
      }
      for (int j = 0; j < m; ++j)
        for (int i = 0; i < m; ++i)
          if (dof[i] >= 0 && dof[j] >= 0)
            rows[dof[i]].emplace_back(static_cast<int>(dof[j]), e[j * m + i]);
    }
  }
  auto cons = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), space.constrained_dofs());
  for (int comp = 0; comp < constrained; ++comp)
    for (std::size_t i = 0; i < cons.extent(0); ++i) {
      const int r = static_cast<int>(comp * n_dofs + cons(i));
      rows[r].emplace_back(r, 1.0);
    }
  CsrMatrix A;
  A.n = n;
  A.row_ptr.assign(n + 1, 0);
  for (long i = 0; i < n; ++i) {
    auto& row = rows[i];
    std::sort(row.begin(), row.end(),
              [](const auto& a, const auto& b) { return a.first < b.first; });
    for (std::size_t e = 0; e < row.size(); ++e) {
      if (e > 0 && row[e].first == A.cols.back()) {
        A.values.back() += row[e].second;
      } else {
        A.cols.push_back(row[e].first);
        A.values.push_back(row[e].second);
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
