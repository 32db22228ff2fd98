#include "physics/advection_diffusion_1d/advection_diffusion_1d.hpp"

#include <cmath>
#include <stdexcept>

#include "kernels/reductions.hpp"
#include "kernels/stencil_1d.hpp"
#include "mesh/box_decomposition.hpp"

namespace amphora::physics::advection_diffusion_1d {

// A named namespace and a free function: CUDA's extended lambdas may not be defined in a
// constructor or in an anonymous namespace.
namespace initial_detail {
/// u(s) = the exact solution at point s of grid cg at time t.
template <class ExecSpace, class View>
void fill_exact(const ExecSpace& exec, const View& u, const ManufacturedWave& exact,
                const mesh::ComponentGrid1D& grid, double t) {
  const ManufacturedWave ex = exact;
  const mesh::ComponentGrid1D cg = grid;
  Kokkos::parallel_for(
      "amphora::AdvectionDiffusion1D::initial", kernels::RangePolicy<ExecSpace>(exec, 0, cg.size),
      KOKKOS_LAMBDA(int s) { u(s) = ex.value(cg.x0 + s * cg.dx, t); });
}
}  // namespace initial_detail

ParamTable parameter_table() {
  return {
      "advection_diffusion_1d",
      "u_t + a u_x = nu u_xx + f on (0,1), two overlapping grids, manufactured solution",
      {
          real_param("a", 1.0, "m/s", "advection speed"),
          real_param("nu", 0.05, "m^2/s", above(0.0),
                     "diffusivity (> 0: the centred scheme needs it)"),
          int_param("cells", 40, at_least(8) & at_most(1 << 24),
                    "grid-1 cells per unit length (h1 = 1/cells)"),
          real_param("interface", 0.5, "m", above(0.2) & below(0.8), "right end of grid 1 (x_b)"),
          real_param("overlap", 1.5, "1", above(0.0) & at_most(2.0),
                     "overlap width x_b - x_a in grid-1 cells"),
          real_param("spacing_ratio", 1.3, "1", at_least(0.5) & at_most(2.0),
                     "grid-2 spacing over grid-1 spacing"),
          real_param("amplitude", 1.0, "1", "manufactured solution amplitude A"),
          real_param("offset", 0.5, "1", "manufactured solution offset B"),
          real_param("wavenumber", 6.0, "1/m", "manufactured solution wavenumber k"),
          real_param("frequency", 2.0, "1/s", "manufactured solution angular frequency omega"),
          real_param("decay", 0.5, "1/s", at_least(0.0), "manufactured solution decay rate gamma"),
      }};
}

template <class ExecSpace>
AdvectionDiffusion1D<ExecSpace>::AdvectionDiffusion1D(const Parameters& p, const Communicator& comm,
                                                      const ExecSpace& exec)
    : comm_(comm),
      exec_(exec),
      exact_{p.real("a"),          p.real("nu"),        p.real("amplitude"), p.real("offset"),
             p.real("wavenumber"), p.real("frequency"), p.real("decay")},
      grid_(static_cast<int>(p.integer("cells")), p.real("interface"), p.real("overlap"),
            p.real("spacing_ratio")) {
  if (comm_.size() > kGrids) {
    throw mesh::DecompositionError(
        "more ranks (" + std::to_string(comm_.size()) + ") than blocks (" + std::to_string(kGrids) +
        "): each component grid of the overlapping grid lives on one rank");
  }
  for (int g = 0; g < kGrids; ++g) {
    if (!owns(g)) continue;
    const mesh::ComponentGrid1D cg = grid_.grid(g);
    u_[g] = View(std::string("amphora::AdvectionDiffusion1D::u_") + block_name(g), cg.size);
    u_new_[g] = View(std::string("amphora::AdvectionDiffusion1D::u_new_") + block_name(g), cg.size);
    initial_detail::fill_exact(exec_, u_[g], exact_, cg, 0.0);
  }
  apply_boundary_conditions(0.0);
  exec_.fence();
}

template <class ExecSpace>
double AdvectionDiffusion1D<ExecSpace>::stable_dt() const {
  const double h = std::min(grid_.grid(0).dx, grid_.grid(1).dx);
  return kernels::stencil::advection_diffusion_ftcs_dt_limit(exact_.a, exact_.nu, h);
}

template <class ExecSpace>
void AdvectionDiffusion1D<ExecSpace>::apply_boundary_conditions(double t) {
  const ManufacturedWave ex = exact_;
  if (owns(0)) {  // Dirichlet u(0, t) = g0(t)
    const View u = u_[0];
    Kokkos::parallel_for(
        "amphora::AdvectionDiffusion1D::dirichlet", kernels::RangePolicy<ExecSpace>(exec_, 0, 1),
        KOKKOS_LAMBDA(int) { u(0) = ex.value(0.0, t); });
  }
  if (owns(1)) {  // Neumann D0 u = g1(t) at x = 1 fixes the ghost point
    const View u = u_[1];
    const mesh::ComponentGrid1D cg = grid_.grid(1);
    const int b = cg.last - 1;
    Kokkos::parallel_for(
        "amphora::AdvectionDiffusion1D::neumann", kernels::RangePolicy<ExecSpace>(exec_, 0, 1),
        KOKKOS_LAMBDA(int) { u(b + 1) = u(b - 1) + 2.0 * cg.dx * ex.derivative(1.0, t); });
  }
}

template <class ExecSpace>
void AdvectionDiffusion1D<ExecSpace>::interpolate() {
  // p = U_{N1+1} = wa0 q + wa1 V_0 + wa2 V_1,  q = V_{-1} = wb0 U_{N1-1} + wb1 U_N1 + wb2 p.
  // The donors live on different ranks: each rank contributes the ones it owns to a sum
  // (adding exact zeros, so the result is the same bits on 1 and 2 ranks).
  const mesh::QuadraticInterpolation& ia = grid_.interpolation(0);
  const mesh::QuadraticInterpolation& ib = grid_.interpolation(1);
  double donors[4] = {0.0, 0.0, 0.0, 0.0};  // U_{N1-1}, U_N1, V_0, V_1
  if (owns(0)) {
    auto u = Kokkos::subview(u_[0], Kokkos::make_pair(ib.donor_first, ib.donor_first + 2));
    auto h = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), u);
    donors[0] = h(0);
    donors[1] = h(1);
  }
  if (owns(1)) {
    auto v = Kokkos::subview(u_[1], Kokkos::make_pair(ia.donor_first + 1, ia.donor_first + 3));
    auto h = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), v);
    donors[2] = h(0);
    donors[3] = h(1);
  }
  if (comm_.size() > 1) MPI_Allreduce(MPI_IN_PLACE, donors, 4, MPI_DOUBLE, MPI_SUM, comm_.get());
  const double rq = ib.w[0] * donors[0] + ib.w[1] * donors[1];
  const double rp = ia.w[1] * donors[2] + ia.w[2] * donors[3];
  const double det = 1.0 - ia.w[0] * ib.w[2];
  const double p = (rp + ia.w[0] * rq) / det;
  const double q = rq + ib.w[2] * p;
  if (owns(0)) Kokkos::deep_copy(exec_, Kokkos::subview(u_[0], ia.target), p);
  if (owns(1)) Kokkos::deep_copy(exec_, Kokkos::subview(u_[1], ib.target), q);
}

template <class ExecSpace>
void AdvectionDiffusion1D<ExecSpace>::advance(double t, double dt) {
  for (int g = 0; g < kGrids; ++g) {
    if (!owns(g)) continue;
    const mesh::ComponentGrid1D& cg = grid_.grid(g);
    kernels::stencil::advection_diffusion_ftcs(exec_, u_[g], u_new_[g], cg.first, cg.last, cg.x0,
                                               cg.dx, exact_.a, exact_.nu, t, dt, exact_);
    // Points outside [first, last) (boundary, ghost, interpolation) are all set below.
    std::swap(u_[g], u_new_[g]);
  }
  apply_boundary_conditions(t + dt);
  exec_.fence();
  interpolate();
  exec_.fence();
}

template <class ExecSpace>
long long AdvectionDiffusion1D<ExecSpace>::work_per_step() const {
  return grid_.grid(0).last - grid_.grid(0).first + grid_.grid(1).last - grid_.grid(1).first;
}

template <class ExecSpace>
double AdvectionDiffusion1D<ExecSpace>::max_error(double t) const {
  double err = 0.0;
  const ManufacturedWave ex = exact_;
  for (int g = 0; g < kGrids; ++g) {
    if (!owns(g)) continue;
    const mesh::ComponentGrid1D cg = grid_.grid(g);
    const View u = u_[g];
    const int end = g == 0 ? cg.size : cg.last;  // grid 2's ghost carries no solution value
    double e = 0.0;
    Kokkos::parallel_reduce(
        "amphora::AdvectionDiffusion1D::max_error", kernels::RangePolicy<ExecSpace>(exec_, 0, end),
        KOKKOS_LAMBDA(int s, double& acc) {
          acc = kernels::math::max(acc, kernels::math::abs(u(s) - ex.value(cg.x0 + s * cg.dx, t)));
        },
        Kokkos::Max<double>(e));
    err = std::max(err, e);
  }
  return comm_.max(err);
}

template <class ExecSpace>
Diagnostics AdvectionDiffusion1D<ExecSpace>::diagnostics(double t) const {
  return {{"error_max", max_error(t)}, {"alpha", grid_.alpha()}, {"beta", grid_.beta()}};
}

template <class ExecSpace>
std::vector<OutputBlock> AdvectionDiffusion1D<ExecSpace>::output(double t) const {
  std::vector<OutputBlock> blocks;
  for (int g = 0; g < kGrids; ++g) {
    if (!owns(g)) continue;
    const mesh::ComponentGrid1D& cg = grid_.grid(g);
    const int n = g == 0 ? cg.size : cg.last;
    auto h = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), u_[g]);
    OutputBlock b;
    b.name = block_name(g);
    b.y = {0.0};
    b.z = {0.0};
    std::vector<double> u(n), exact(n), error(n);
    for (int s = 0; s < n; ++s) {
      b.x.push_back(cg.x(s));
      u[s] = h(s);
      exact[s] = exact_.value(cg.x(s), t);
      error[s] = u[s] - exact[s];
    }
    b.fields = {{"u", u}, {"u_exact", exact}, {"error", error}};
    blocks.push_back(std::move(b));
  }
  return blocks;
}

template <class ExecSpace>
std::optional<NonFiniteReport> AdvectionDiffusion1D<ExecSpace>::find_nonfinite() const {
  // Report the bad value with the lowest (grid, index) over all ranks.
  long long key = -1;
  for (int g = 0; g < kGrids && key < 0; ++g) {
    if (!owns(g)) continue;
    const int i = kernels::reduce::first_nonfinite(exec_, u_[g]);
    if (i >= 0) key = g * (1LL << 40) + i;
  }
  const long long big = 1LL << 62;
  long long global = -comm_.max(key < 0 ? -big : -key);
  if (global >= big) return std::nullopt;
  NonFiniteReport r;
  const int g = static_cast<int>(global >> 40);
  r.field = "u";
  r.block = block_name(g);
  r.index = global & ((1LL << 40) - 1);
  r.x = grid_.grid(g).x(static_cast<int>(r.index));
  return r;
}

template <class ExecSpace>
std::vector<std::string> AdvectionDiffusion1D<ExecSpace>::owned_blocks() const {
  std::vector<std::string> names;
  for (int g = 0; g < kGrids; ++g)
    if (owns(g)) names.push_back(block_name(g));
  return names;
}

template <class ExecSpace>
std::vector<StateBlock> AdvectionDiffusion1D<ExecSpace>::state() const {
  std::vector<StateBlock> blocks;
  for (int g = 0; g < kGrids; ++g) {
    if (!owns(g)) continue;
    auto h = Kokkos::create_mirror_view_and_copy(kernels::HostMemSpace(), u_[g]);
    blocks.push_back({block_name(g), {{"u", std::vector<double>(h.data(), h.data() + h.size())}}});
  }
  return blocks;
}

template <class ExecSpace>
void AdvectionDiffusion1D<ExecSpace>::restore(const std::vector<StateBlock>& blocks) {
  for (int g = 0; g < kGrids; ++g) {
    if (!owns(g)) continue;
    bool found = false;
    for (const auto& b : blocks) {
      if (b.name != block_name(g)) continue;
      for (const auto& [name, data] : b.arrays) {
        if (name != "u") continue;
        if (data.size() != u_[g].extent(0)) {
          throw std::runtime_error(std::string("checkpoint block ") + block_name(g) + " has " +
                                   std::to_string(data.size()) + " values, the scene needs " +
                                   std::to_string(u_[g].extent(0)));
        }
        auto h = Kokkos::create_mirror_view(u_[g]);
        for (size_t s = 0; s < data.size(); ++s) h(s) = data[s];
        Kokkos::deep_copy(u_[g], h);
        found = true;
      }
    }
    if (!found)
      throw std::runtime_error(std::string("checkpoint lacks block ") + block_name(g) + "/u");
  }
}

AMPHORA_INSTANTIATE_ON_EXEC_SPACES(AdvectionDiffusion1D)

}  // namespace amphora::physics::advection_diffusion_1d
