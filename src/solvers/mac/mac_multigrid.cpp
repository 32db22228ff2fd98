#include "solvers/mac/mac_multigrid.hpp"

#include <mpi.h>

#include <algorithm>
#include <sstream>
#include <stdexcept>

namespace amphora::solvers::mac {

namespace {
/// Halvings until n is odd.
int halvings(int n) {
  int l = 0;
  while (n > 0 && n % 2 == 0) n /= 2, ++l;
  return l;
}

bool all_ranks(MPI_Comm comm, bool local) {
  int in = local ? 1 : 0, out = 0;
  MPI_Allreduce(&in, &out, 1, MPI_INT, MPI_MIN, comm);
  return out == 1;
}
}  // namespace

std::string multigrid_size_error(const kernels::mac::MacGrid& g, long max_coarse_cells) {
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

template <class ExecSpace>
MacMultigrid<ExecSpace>::MacMultigrid(const ExecSpace& exec, const Stencil& A,
                                      const MacMultigridOptions& options,
                                      const mesh::mac::MacBlock& block)
    : options_(options), halo_(block) {
  const MPI_Comm comm = block.comm;
  // every rank decides together, so none is left waiting in an exchange
  const std::string error = multigrid_size_error(A.grid, options.max_coarse_cells);
  if (!all_ranks(comm, error.empty()))
    throw std::invalid_argument(
        error.empty() ? "multigrid: another rank's block cannot be coarsened" : error);
  fine_ = A;
  // Down to blocks of at most 64 cells, or as far as the dimensions stay even (coarsened in
  // double, then stored in single precision); a block's first cell stays on the coarse grid.
  Stencil level = A;
  complete_block_stencil(exec, halo_, static_cast<const Stencil*>(nullptr), level);
  levels_.push_back(kernels::mac::convert_stencil<float>(exec, level));
  const auto& lower = block.global_lower;
  parity_.push_back((lower[0] + lower[2]) & 1);
  for (int shift = 1;; ++shift) {
    const kernels::mac::MacGrid& g = level.grid;
    const bool local = g.nx % 2 == 0 && g.ny % 2 == 0 && g.nz % 2 == 0 && g.cells() > 64 &&
                       lower[0] % (1 << shift) == 0 && lower[2] % (1 << shift) == 0;
    if (!all_ranks(comm, local)) break;
    Stencil coarse = kernels::mac::coarsen_stencil(exec, level);
    complete_block_stencil(exec, halo_, &level, coarse);
    level = coarse;
    levels_.push_back(kernels::mac::convert_stencil<float>(exec, level));
    parity_.push_back(((lower[0] >> shift) + (lower[2] >> shift)) & 1);
  }
  for (const LevelStencil& S : levels_) {
    const long n = S.grid.padded_size();
    regions_.push_back("amphora::mac_mg level " + std::to_string(regions_.size()) + " (" +
                       std::to_string(S.grid.nx) + "x" + std::to_string(S.grid.ny) + "x" +
                       std::to_string(S.grid.nz) + ")");
    x_.emplace_back("amphora::mac_mg::x", n);  // zero, ghost entries stay zero on one block
    b_.emplace_back("amphora::mac_mg::b", n);
    r_.emplace_back("amphora::mac_mg::r", n);
  }
  exec.fence();
  setup_coarse_solve(level);
}

template <class ExecSpace, class MemSpace>
void complete_block_stencil(const ExecSpace& exec, const mesh::mac::LatticeGhostExchange& halo,
                            const kernels::mac::PoissonStencil<MemSpace>* fine,
                            kernels::mac::PoissonStencil<MemSpace>& level) {
  const MPI_Comm comm = halo.block().comm;
  int any = level.any_solid ? 1 : 0, global_any = 0;
  MPI_Allreduce(&any, &global_any, 1, MPI_INT, MPI_MAX, comm);
  if (!halo.block().split()) return;  // one block: the coefficients are complete
  const kernels::mac::MacGrid& g = level.grid;
  const bool level_set = level.phi.extent(0) > 0;
  // a coarse level: the ghost cells' + faces are this block's - faces, then the diagonal at
  // the block faces (the caller exchanged the finest level's conductances), with a level set
  // from the ghost cells' level set and whether they are unknowns, after which the faces towards
  // cells that are not unknowns are zero on both sides
  if (fine) {
    halo.exchange(exec, g, level.cx);
    halo.exchange(exec, g, level.cz);
    if (level_set) {
      halo.exchange(exec, g, level.diag);
      halo.exchange(exec, g, level.solid);
      halo.exchange(exec, g, level.phi);
    }
    kernels::mac::coarse_diagonal(exec, *fine, level, 0, true);
    if (level_set) {
      halo.exchange(exec, g, level.cx);
      halo.exchange(exec, g, level.cz);
    }
  } else if (level_set) {
    halo.exchange(exec, g, level.phi);  // the finest level's, for the first coarsening
  }
  halo.exchange(exec, g, level.diag);
  halo.exchange(exec, g, level.inverse_diag);
  halo.exchange(exec, g, level.solid);
  // the extension into solids must run on every rank when it runs on one (it exchanges)
  level.any_solid = global_any != 0;
  kernels::mac::compute_solid_shares(exec, level);
  halo.exchange(exec, g, level.solid_share);
}

template <class ExecSpace>
auto MacMultigrid<ExecSpace>::coarsest_rows(const Stencil& coarsest) const
    -> kernels::host_mirror_t<Kokkos::View<double*, MemSpace>> {
  // this block's rows (diagonal, x, y, z couplings) packed on the device: one copy to the host
  const auto cells = coarse_cells_;
  const auto d = coarsest.diag;
  const auto cx = coarsest.cx, cy = coarsest.cy, cz = coarsest.cz;
  Kokkos::View<double*, MemSpace> packed("amphora::mac_mg::coarse_rows", 4 * cells.extent(0));
  Kokkos::parallel_for(
      "amphora::mac_mg::coarse_rows", kernels::RangePolicy<ExecSpace>(0, int(cells.extent(0))),
      KOKKOS_LAMBDA(int m) {
        const int c = cells(m);
        packed(4 * m) = d(c), packed(4 * m + 1) = cx(c), packed(4 * m + 2) = cy(c);
        packed(4 * m + 3) = cz(c);
      });
  const auto rows = Kokkos::create_mirror_view(packed);
  Kokkos::deep_copy(rows, packed);  // a host build copies the View onto itself: counted there too
  return rows;
}

template <class ExecSpace>
void MacMultigrid<ExecSpace>::setup_coarse_solve(const Stencil& coarsest) {
  const mesh::mac::MacBlock& block = halo_.block();
  const MPI_Comm comm = block.comm;
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  const kernels::mac::MacGrid g = coarsest.grid;
  const int shift = levels() - 1;
  // the blocks of the coarsest grid: lower corner and extents
  const int mine[6] = {
      block.global_lower[0] >> shift, 0, block.global_lower[2] >> shift, g.nx, g.ny, g.nz};
  std::vector<int> boxes(6 * ranks);
  MPI_Allgather(mine, 6, MPI_INT, boxes.data(), 6, MPI_INT, comm);
  kernels::mac::MacGrid whole{0, 0, 0, g.h, g.origin};
  counts_.assign(ranks, 0);
  displacements_.assign(ranks, 0);
  for (int r = 0; r < ranks; ++r) {
    const int* b = &boxes[6 * r];
    whole.nx = std::max(whole.nx, b[0] + b[3]);
    whole.ny = std::max(whole.ny, b[1] + b[4]);
    whole.nz = std::max(whole.nz, b[2] + b[5]);
    counts_[r] = b[3] * b[4] * b[5];
    if (r > 0) displacements_[r] = displacements_[r - 1] + counts_[r - 1];
  }
  my_offset_ = displacements_[rank];
  const int total = displacements_[ranks - 1] + counts_[ranks - 1];
  gathered_index_.resize(total);
  for (int r = 0; r < ranks; ++r) {
    const int* b = &boxes[6 * r];
    int m = displacements_[r];
    for (int k = 0; k < b[5]; ++k)
      for (int j = 0; j < b[4]; ++j)
        for (int i = 0; i < b[3]; ++i)
          gathered_index_[m++] = whole.index(b[0] + i, b[1] + j, b[2] + k);
  }
  // this block's cells, and its rows of the matrix, gathered into the whole coarsest grid
  std::vector<int> cells;
  cells.reserve(counts_[rank]);
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) cells.push_back(g.index(i, j, k));
  coarse_cells_ = kernels::to_view<MemSpace>(cells, "amphora::mac_mg::coarse_cells");
  const auto rows = coarsest_rows(coarsest);
  std::vector<int> counts4(ranks), displacements4(ranks);
  for (int r = 0; r < ranks; ++r)
    counts4[r] = 4 * counts_[r], displacements4[r] = 4 * displacements_[r];
  std::vector<double> all_rows(4 * static_cast<std::size_t>(total));
  MPI_Allgatherv(rows.data(), counts4[rank], MPI_DOUBLE, all_rows.data(), counts4.data(),
                 displacements4.data(), MPI_DOUBLE, comm);
  std::vector<double> wd(whole.padded_size(), 0.0);
  std::vector<float> wx(whole.padded_size(), 0.0f), wy(whole.padded_size(), 0.0f),
      wz(whole.padded_size(), 0.0f);
  for (int m = 0; m < total; ++m) {
    const int c = gathered_index_[m];
    wd[c] = all_rows[4 * m], wx[c] = float(all_rows[4 * m + 1]), wy[c] = float(all_rows[4 * m + 2]),
    wz[c] = float(all_rows[4 * m + 3]);
  }
  coarse_ = std::make_unique<CoarseCholesky>(
      stencil_to_csr(whole, wd.data(), wx.data(), wy.data(), wz.data(), coarse_numbering_));
  coarse_local_ = Kokkos::View<float*, MemSpace>("amphora::mac_mg::coarse_local", cells.size());
  coarse_send_ = Kokkos::create_mirror_view(coarse_local_);  // local itself on a host build
  coarse_gathered_.resize(total);
  coarse_lattice_.assign(whole.padded_size(), 0.0);
  coarse_rhs_.resize(coarse_numbering_.size());
}

template <class ExecSpace>
void MacMultigrid<ExecSpace>::apply(const ExecSpace& exec, const Vector& r, const Vector& z) const {
  const LevelVector b = b_[0], x = x_[0];
  Kokkos::parallel_for(
      "amphora::mac_mg::to_single",
      kernels::RangePolicy<ExecSpace>(exec, 0, static_cast<int>(r.extent(0))),
      KOKKOS_LAMBDA(int c) { b(c) = static_cast<float>(r(c)); });
  vcycle(exec, 0);
  Kokkos::parallel_for(
      "amphora::mac_mg::to_double",
      kernels::RangePolicy<ExecSpace>(exec, 0, static_cast<int>(z.extent(0))),
      KOKKOS_LAMBDA(int c) { z(c) = x(c); });
}

template <class ExecSpace>
void MacMultigrid<ExecSpace>::coarse_solve(const ExecSpace& exec) const {
  // gather the right-hand side of every block, solve the whole coarsest grid, keep this block's
  const int l = levels() - 1;
  const LevelVector b = b_[l], x = x_[l];
  const auto cells = coarse_cells_;
  const auto local = coarse_local_;
  const int n = static_cast<int>(cells.extent(0));
  Kokkos::parallel_for(
      "amphora::mac_mg::coarse_pack", kernels::RangePolicy<ExecSpace>(exec, 0, n),
      KOKKOS_LAMBDA(int m) { local(m) = b(cells(m)); });
  const auto host = coarse_send_;
  Kokkos::deep_copy(exec, host, local);
  exec.fence();
  MPI_Allgatherv(coarse_send_.data(), n, MPI_FLOAT, coarse_gathered_.data(), counts_.data(),
                 displacements_.data(), MPI_FLOAT, halo_.block().comm);
  for (std::size_t m = 0; m < gathered_index_.size(); ++m)
    coarse_lattice_[gathered_index_[m]] = coarse_gathered_[m];
  const auto& fluid = coarse_numbering_.cell;
  for (std::size_t u = 0; u < fluid.size(); ++u) coarse_rhs_[u] = coarse_lattice_[fluid[u]];
  coarse_->solve(coarse_rhs_.data(), coarse_rhs_.data());
  std::fill(coarse_lattice_.begin(), coarse_lattice_.end(), 0.0);
  for (std::size_t u = 0; u < fluid.size(); ++u) coarse_lattice_[fluid[u]] = coarse_rhs_[u];
  for (int m = 0; m < n; ++m)
    host(m) = static_cast<float>(coarse_lattice_[gathered_index_[my_offset_ + m]]);
  Kokkos::deep_copy(exec, local, host);
  kernels::blas1::fill(exec, x, 0.0f);
  Kokkos::parallel_for(
      "amphora::mac_mg::coarse_unpack", kernels::RangePolicy<ExecSpace>(exec, 0, n),
      KOKKOS_LAMBDA(int m) { x(cells(m)) = local(m); });
}

template <class ExecSpace>
void MacMultigrid<ExecSpace>::smooth(const ExecSpace& exec, int l, int first_colour) const {
  const LevelStencil& A = levels_[l];
  for (int half = 0; half < 2; ++half) {
    sync(exec, l, x_[l]);
    const int colour = half == 0 ? first_colour : 1 - first_colour;
    kernels::mac::red_black_gauss_seidel(exec, A, b_[l], x_[l], colour ^ parity_[l]);
  }
}

template <class ExecSpace>
void MacMultigrid<ExecSpace>::smooth_steps(const ExecSpace& exec, int l, int first_colour,
                                           int steps) const {
  if (!halo_.block().split() && levels_[l].grid.cells() <= options_.team_smoothing_cells) {
    kernels::mac::red_black_gauss_seidel_team(exec, levels_[l], b_[l], x_[l],
                                              first_colour ^ parity_[l], steps, options_.team_size);
    return;
  }
  for (int s = 0; s < steps; ++s) smooth(exec, l, first_colour);
}

template <class ExecSpace>
double MacMultigrid<ExecSpace>::bytes_per_application() const {
  double bytes = 24.0 * static_cast<double>(fine_.grid.padded_size());
  for (int l = 0; l + 1 < levels(); ++l) {
    const double n = static_cast<double>(levels_[l].grid.padded_size());
    const double nc = static_cast<double>(levels_[l + 1].grid.padded_size());
    const int nu = options_.smoothing_steps << l;
    bytes += 4.0 * n + 4.0 * nu * 28.0 * n + 28.0 * n    // fill, smoothing, residual
             + 4.0 * n + 4.0 * nc + 4.0 * nc + 8.0 * n;  // restriction, prolongation
  }
  return bytes;
}

template <class ExecSpace>
void MacMultigrid<ExecSpace>::vcycle(const ExecSpace& exec, int l) const {
  if (l + 1 == levels()) {
    Kokkos::Profiling::pushRegion(regions_[l]);
    coarse_solve(exec);
    Kokkos::Profiling::popRegion();
    return;
  }
  const LevelStencil &A = levels_[l], &C = levels_[l + 1];
  const LevelVector x = x_[l];
  const int nu = options_.smoothing_steps << l;
  Kokkos::Profiling::pushRegion(regions_[l]);  // a kernel profile's level (kernel_profile.hpp)
  kernels::blas1::fill(exec, x, 0.0f);
  smooth_steps(exec, l, 0, nu);
  // restriction R = E^T P^T: the fine residual's ghosts feed P^T, the coarse ghosts E^T
  sync(exec, l, x);
  kernels::mac::residual(exec, A, b_[l], x, r_[l]);
  sync(exec, l, r_[l]);
  kernels::mac::restrict_to_coarse(exec, A, C, r_[l], b_[l + 1]);
  if (C.any_solid) {
    sync(exec, l + 1, b_[l + 1]);
    kernels::mac::gather_from_solids(exec, C, b_[l + 1]);
  }
  Kokkos::Profiling::popRegion();
  vcycle(exec, l + 1);
  Kokkos::Profiling::pushRegion(regions_[l]);
  // prolongation P E
  sync(exec, l + 1, x_[l + 1]);
  if (C.any_solid) {
    kernels::mac::extend_into_solids(exec, C, x_[l + 1]);
    sync(exec, l + 1, x_[l + 1]);
  }
  kernels::mac::prolongate_add(exec, C, A, x_[l + 1], x);
  smooth_steps(exec, l, 1, nu);
  Kokkos::Profiling::popRegion();
}

template class MacMultigrid<kernels::DefaultExecSpace>;
template void complete_block_stencil(
    const kernels::DefaultExecSpace&, const mesh::mac::LatticeGhostExchange&,
    const kernels::mac::PoissonStencil<kernels::DefaultExecSpace::memory_space>*,
    kernels::mac::PoissonStencil<kernels::DefaultExecSpace::memory_space>&);
#if defined(KOKKOS_ENABLE_SERIAL) && defined(KOKKOS_ENABLE_OPENMP)
template class MacMultigrid<Kokkos::Serial>;
template void complete_block_stencil(
    const Kokkos::Serial&, const mesh::mac::LatticeGhostExchange&,
    const kernels::mac::PoissonStencil<Kokkos::Serial::memory_space>*,
    kernels::mac::PoissonStencil<Kokkos::Serial::memory_space>&);
#endif

}  // namespace amphora::solvers::mac
