#pragma once
// u_t + a u_x = nu u_xx + f on (0, 1) on a two-grid overlapping grid (Henshaw's 1D example,
// ../shared/seeds/000): explicit centred scheme on each component grid, Dirichlet at x = 0,
// Neumann at x = 1 through a ghost point, and implicit three-point quadratic interpolation at
// the overlap (both interpolation points solved together, a 2x2 system). Verified against a
// manufactured solution. In parallel each component grid lives on one rank (at most 2 ranks).
#include <array>
#include <memory>
#include <vector>

#include "kernels/spaces.hpp"
#include "base/communicator.hpp"
#include "mesh/overlapping_grid_1d.hpp"
#include "physics/advection_diffusion_1d/manufactured_wave.hpp"
#include "physics/module.hpp"
#include "base/parameters.hpp"

namespace amphora::physics::advection_diffusion_1d {

/// The scene table `[advection_diffusion_1d]`.
ParamTable parameter_table();

template <class ExecSpace>
class AdvectionDiffusion1D final : public Module {
 public:
  using MemSpace = typename ExecSpace::memory_space;
  using View = Kokkos::View<double*, MemSpace>;

  AdvectionDiffusion1D(const Parameters& p, const Communicator& comm,
                       const ExecSpace& exec = ExecSpace());

  std::string name() const override { return "advection_diffusion_1d"; }
  double stable_dt() const override;
  void advance(double t, double dt) override;
  long long work_per_step() const override;
  std::string work_unit() const override { return "point-steps"; }
  std::vector<OutputBlock> output(double t) const override;
  Diagnostics diagnostics(double t) const override;
  std::string error_diagnostic() const override { return "error_max"; }
  std::optional<NonFiniteReport> find_nonfinite() const override;
  std::vector<StateBlock> state() const override;
  void restore(const std::vector<StateBlock>& blocks) override;
  std::vector<std::string> owned_blocks() const override;

  /// Max-norm error against the manufactured solution at time t, over every grid point that
  /// carries a solution value (ghost excluded). Collective.
  double max_error(double t) const;
  const mesh::OverlappingGrid1D& grid() const { return grid_; }

 public:  // (CUDA: extended lambdas may not live in private member functions)
  static constexpr int kGrids = 2;
  static const char* block_name(int g) { return g == 0 ? "grid1" : "grid2"; }
  int owner(int g) const { return comm_.size() == 1 ? 0 : g; }
  bool owns(int g) const { return owner(g) == comm_.rank(); }
  void apply_boundary_conditions(double t);
  void interpolate();

 private:
  Communicator comm_;
  ExecSpace exec_;
  ManufacturedWave exact_;
  mesh::OverlappingGrid1D grid_;
  std::array<View, kGrids> u_, u_new_;  // allocated only on the owning rank
};

}  // namespace amphora::physics::advection_diffusion_1d
