// The MAC water step's kernels besides the pressure solve (perf/mac_pressure.cpp), in cells
// per second on an n^3 grid: a pool filling the lower 60 % of the box, a smooth swirl of
// velocity (at most 1 m/s), CFL 1.
//
// WaterKernels/kind/n: 0 semi-Lagrangian advection of one face component, 1 of the level set,
// 2 conservative upwind advection of one face component (every column one tall cell), 3 one
// level-set reinitialisation step, 4 one velocity extrapolation layer (all faces unknown but
// those next to the water).
//
// WaterStep/optical_depth/n: one whole time step of the water_mac module (the splash of
// scenes/water_splash.toml at n^3, after 5 steps of settling), uniform (0) or on tall cells;
// counters: cells per second, sub-steps per step.
#include <benchmark/benchmark.h>

#include <cmath>
#include <string>
#include <vector>

#include "kernels/host_vector.hpp"
#include "kernels/mac/level_set.hpp"
#include "kernels/mac/projection.hpp"
#include "kernels/mac/tall_cell_advection.hpp"
#include "physics/water_mac/water_mac.hpp"

namespace {

using Exec = amphora::kernels::DefaultExecSpace;
using Mem = Exec::memory_space;
using Vector = Kokkos::View<double*, Mem>;
namespace kernels = amphora::kernels;
namespace mac = amphora::kernels::mac;

struct Pool {
  kernels::mac::MacGrid grid;
  Vector phi, u, v, w, out;
  Kokkos::View<kernels::mac::MacCellType*, Mem> type;
  Kokkos::View<std::uint8_t*, Mem> mark;
  explicit Pool(int n) : grid{n, n, n, 1.0 / n, {0.0, 0.0, 0.0}} {
    const long size = grid.padded_size();
    std::vector<double> p(size, 0.0), f[3];
    std::vector<kernels::mac::MacCellType> t(size, kernels::mac::MacCellType::air);
    for (auto& c : f) c.assign(size, 0.0);
    const double pi = amphora::kernels::math::pi;
    for (int k = 0; k < n; ++k)
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          const auto x = grid.cell_centre(i, j, k);
          const int c = grid.index(i, j, k);
          p[c] = x[1] - 0.6;
          t[c] = p[c] < 0 ? kernels::mac::MacCellType::fluid : kernels::mac::MacCellType::air;
          // a divergence-free swirl in x-y, a gentle drift in z
          f[0][c] = std::sin(pi * x[0]) * std::cos(pi * x[1]);
          f[1][c] = -std::cos(pi * x[0]) * std::sin(pi * x[1]);
          f[2][c] = 0.2 * std::sin(2 * pi * x[0]);
        }
    phi = amphora::kernels::to_view<Mem>(p), u = amphora::kernels::to_view<Mem>(f[0]),
    v = amphora::kernels::to_view<Mem>(f[1]);
    w = amphora::kernels::to_view<Mem>(f[2]);
    out = Vector("out", size);
    type = amphora::kernels::to_view<Mem>(t);
    mark = Kokkos::View<std::uint8_t*, Mem>("mark", size);
  }
};

void WaterKernels(benchmark::State& state) {
  const int kind = static_cast<int>(state.range(0)), n = static_cast<int>(state.range(1));
  Pool pool(n);
  const Exec exec;
  const kernels::mac::MacGrid& g = pool.grid;
  // every column uniform, or (kind 2) every column one tall cell
  kernels::mac::TallCellColumns<Mem> columns(g);
  if (kind == 2) Kokkos::deep_copy(columns.band, g.ny);
  const double dt = g.h / 1.0, reach = 1e30;
  for (auto _ : state) {
    switch (kind) {
      case 0:
      case 2:
        mac::advect(exec, columns, mac::Staggering::x, pool.u, pool.out, pool.u, pool.v, pool.w, dt,
                    pool.phi, reach);
        break;
      case 1:
        mac::advect(exec, columns, mac::Staggering::centre, pool.phi, pool.out, pool.u, pool.v,
                    pool.w, dt, pool.phi, reach);
        break;
      case 3: mac::reinitialise_step(exec, g, pool.phi, pool.phi, pool.out); break;
      case 4:
        state.PauseTiming();
        mac::mark_fluid_faces(exec, g, 0, pool.type, pool.mark);
        exec.fence();
        state.ResumeTiming();
        mac::extrapolate_layer(exec, g, 0, pool.type, pool.u, pool.mark, 2);
        break;
    }
    exec.fence();
  }
  state.counters["cells_per_s"] =
      benchmark::Counter(double(g.cells()), benchmark::Counter::kIsIterationInvariantRate);
  static const char* names[] = {"semi-Lagrangian face component", "semi-Lagrangian level set",
                                "conservative upwind face component (tall cells)",
                                "reinitialisation step", "extrapolation layer"};
  state.SetLabel(names[kind]);
}
BENCHMARK(WaterKernels)
    ->ArgsProduct({{0, 1, 2, 3, 4}, {64, 128}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void WaterStep(benchmark::State& state) {
  const int depth = static_cast<int>(state.range(0)), n = static_cast<int>(state.range(1));
  namespace wm = amphora::physics::water_mac;
  amphora::Parameters p(wm::parameter_table());
  p.set("scene", std::string("splash"));
  for (const char* key : {"cells_x", "cells_y", "cells_z"}) p.set(key, std::int64_t(n));
  p.set("length_x", 1.0);
  p.set("drop_height", 0.78);
  p.set("terrain_base", 0.05);
  p.set("terrain_amplitude", 0.04);
  p.set("optical_depth", std::int64_t(depth));
  auto m = wm::create(p, amphora::Communicator());
  const double dt = 0.01;
  double t = 0.0;
  for (int s = 0; s < 5; ++s, t += dt) m->advance(t, dt);
  double substeps = 0;
  auto count = [&] {
    for (const auto& [k, v] : m->diagnostics(t))
      if (k == "substeps") return v;
    return 0.0;
  };
  const double before = count();
  for (auto _ : state) {
    m->advance(t, dt);
    t += dt;
  }
  substeps = count() - before;
  state.counters["cells_per_s"] =
      benchmark::Counter(double(n) * n * n, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["substeps_per_step"] = substeps / double(state.iterations());
  state.SetLabel(depth == 0 ? "uniform" : "tall cells");
}
BENCHMARK(WaterStep)
    ->ArgsProduct({{0, 8}, {64}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(10);

}  // namespace
