// The invertible-FEM element force kernel (kernels/solid/tet_forces.hpp) on a box of Kuhn
// tetrahedra under a smooth finite deformation: elements per second and the fraction of the
// STREAM triad bandwidth, counting the least traffic the kernel must move per element (its
// 104 bytes of element data - D_m^-1, volume, connectivity, det F - plus the node positions
// read and forces updated once each, 72 bytes per node, about 12 per element). And the
// implicit backward-Euler step (physics/solid_fem/backward_euler.hpp) from the same deformed
// box released at rest, at 20 times the explicit limit: seconds per Newton iteration and per
// CG iteration.
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>

#include "kernels/solid/tet_forces.hpp"
#include "mesh/tet/tet_mesh.hpp"
#include "physics/solid_fem/tet_solid.hpp"
#include "stream_bandwidth.hpp"

namespace {

using amphora::kernels::DefaultExecSpace;
using amphora::kernels::DefaultMemSpace;
namespace solid = amphora::kernels::solid;

/// Stretched, sheared and twisted: every element deformed differently.
amphora::mesh::tet::TetMesh deformed(amphora::mesh::tet::TetMesh mesh) {
  for (auto& p : mesh.nodes) {
    const double a = 0.4 * p[2];
    const double x = 1.2 * p[0] + 0.1 * p[1], y = 0.9 * p[1];
    p = {std::cos(a) * x - std::sin(a) * y, std::sin(a) * x + std::cos(a) * y, 0.8 * p[2]};
  }
  return mesh;
}

void TetForces(benchmark::State& state) {
  const auto model = static_cast<solid::Hyperelastic>(state.range(0));
  const int n = static_cast<int>(state.range(1));
  const auto mesh = amphora::mesh::tet::box_tet_mesh({n, n, n}, {0, 0, 0}, {1, 1, 1});
  const auto rest = amphora::mesh::tet::to_views<DefaultMemSpace>(mesh);
  const auto now = amphora::mesh::tet::to_views<DefaultMemSpace>(deformed(mesh));
  const DefaultExecSpace exec;
  const auto shapes = solid::tet_rest_shapes(exec, rest.nodes, rest.tets);
  Kokkos::View<double* [3], DefaultMemSpace> f("f", mesh.n_nodes());
  Kokkos::View<double*, DefaultMemSpace> J("J", mesh.n_tets());
  const solid::Material material{model, 1.0, 4.0, 0.25};
  const double stream = amphora::perf::stream_triad_bandwidth();  // measured before timing
  double seconds = 0.0;
  for (auto _ : state) {
    Kokkos::deep_copy(exec, f, 0.0);
    exec.fence();
    const auto t0 = std::chrono::steady_clock::now();
    solid::tet_forces(exec, material, shapes, rest.tets, now.nodes, f, J);
    exec.fence();
    const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    state.SetIterationTime(t);
    seconds += t;
  }
  const double elements = mesh.n_tets(), nodes = mesh.n_nodes();
  const double bytes = 104.0 * elements + 72.0 * nodes;
  const double bytes_per_second = bytes * double(state.iterations()) / seconds;
  state.counters["elements"] = benchmark::Counter(
      elements, benchmark::Counter::kIsIterationInvariantRate, benchmark::Counter::OneK::kIs1000);
  state.counters["bandwidth"] = benchmark::Counter(bytes_per_second, benchmark::Counter::kDefaults,
                                                   benchmark::Counter::OneK::kIs1000);
  state.counters["fraction_of_stream"] = bytes_per_second / stream;
  state.counters["tets"] = elements;
}

// Models 0 neo-Hookean, 1 corotated, 2 St Venant-Kirchhoff; 16^3 and 56^3 cubes (24,576 and
// 1,053,696 tetrahedra).
BENCHMARK(TetForces)
    ->ArgNames({"model", "cells"})
    ->ArgsProduct({{0, 1, 2}, {16, 56}})
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

void BackwardEulerStep(benchmark::State& state) {
  namespace fem = amphora::physics::solid_fem;
  const int n = static_cast<int>(state.range(0));
  const auto mesh = amphora::mesh::tet::box_tet_mesh({n, n, n}, {0, 0, 0}, {1, 1, 1});
  fem::TetSolidOptions o;
  o.material = solid::Material{solid::Hyperelastic::neo_hookean, 1.0, 4.0, 0.25};
  o.implicit = true;
  fem::TetSolid<DefaultExecSpace> s(mesh, o);
  const auto start = amphora::mesh::tet::to_views<DefaultMemSpace>(deformed(mesh));
  const double dt = 20.0 * s.stable_dt(1.0);
  double seconds = 0.0, newton = 0.0, cg = 0.0;
  for (auto _ : state) {
    Kokkos::deep_copy(s.positions(), start.nodes);
    Kokkos::deep_copy(s.velocities(), 0.0);
    Kokkos::fence();
    const auto t0 = std::chrono::steady_clock::now();
    s.step(dt);
    Kokkos::fence();
    const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    state.SetIterationTime(t);
    seconds += t;
    newton += s.newton_report().iterations;
    cg += s.newton_report().cg_iterations;
  }
  state.counters["tets"] = mesh.n_tets();
  state.counters["newton_per_step"] = newton / double(state.iterations());
  state.counters["cg_per_newton"] = cg / newton;
  state.counters["ms_per_newton"] = 1e3 * seconds / newton;
  state.counters["us_per_cg"] = 1e6 * seconds / cg;
}

BENCHMARK(BackwardEulerStep)
    ->ArgName("cells")
    ->Arg(8)
    ->Arg(24)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace
