#include "solvers/mac/mac_multigrid.hpp"

#include <sstream>

namespace amphora::solvers::mac {

namespace {
/// Halvings until n is odd.
int halvings(int n) {
  int l = 0;
  while (n > 0 && n % 2 == 0) n /= 2, ++l;
  return l;
}
}  // namespace

std::string multigrid_size_error(const mesh::MacGrid& g, long max_coarse_cells) {
  if (g.nx < 1 || g.ny < 1 || g.nz < 1) return "multigrid: empty grid";
  const int L = std::min({halvings(g.nx), halvings(g.ny), halvings(g.nz)});
  const long coarse = (long(g.nx) >> L) * (long(g.ny) >> L) * (long(g.nz) >> L);
  if (coarse <= max_coarse_cells) return {};
  // Name the dimension with the fewest halvings and the nearest sizes with more of them.
  const int dims[3] = {g.nx, g.ny, g.nz};
  const char* names[3] = {"nx", "ny", "nz"};
  int worst = 0;
  for (int d = 1; d < 3; ++d)
    if (halvings(dims[d]) < halvings(dims[worst])) worst = d;
  const int n = dims[worst];
  const int step = 16;  // sizes divisible by 16 coarsen four times
  const int below = std::max(step, n / step * step), above = (n / step + 1) * step;
  std::ostringstream s;
  s << "multigrid cannot coarsen the " << g.nx << "x" << g.ny << "x" << g.nz
    << " grid: it halves the grid while every dimension is even, and the coarsest grid ("
    << (g.nx >> L) << "x" << (g.ny >> L) << "x" << (g.nz >> L) << " = " << coarse
    << " cells) must have at most " << max_coarse_cells << " cells. " << names[worst] << " = " << n
    << " can be halved " << halvings(n) << " times; valid sizes are m * 2^L with small m, e.g. "
    << names[worst] << " = " << below << " or " << above;
  return s.str();
}

template class MacMultigrid<DefaultExecSpace>;
#if defined(KOKKOS_ENABLE_SERIAL) && defined(KOKKOS_ENABLE_OPENMP)
template class MacMultigrid<Kokkos::Serial>;
#endif

}  // namespace amphora::solvers::mac
