// Partitioned fluid–structure coupling (issue 5): the cost of one time step, AMP against the
// traditional scheme (TP) and against TP with the Aitken sub-iterations it needs to stay stable.
//
// Beam/scheme/inv_ratio: the beam over an inviscid channel (160 points, 80 fluid rows, the
// test's wave and dt) at rho_h / rho = 1 / inv_ratio; scheme 0 = TP, 1 = TP-Aitken, 2 = AMP.
// TP runs at rho_h / rho = 100 only (it blows up below 0.1; its step costs the same at any
// ratio). Counter: sub-iterations per step.
// Mpve/scheme/n/inv_ratio: MP-VE (viscous channel, mu = 0.02, over an elastic solid) on n x n
// fluid cells at rho_bar / rho = 1 / inv_ratio (inv_ratio 0: the heavy solid, 1000, where TP is
// stable up to n = 160); scheme 0 = TP, 1 = TP-Aitken, 2 = AMP. Counter: sub-iterations per step.
// Time per iteration = one step (set-up and factorisations outside the timing).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "coupling/fsi/beam_channel_fsi.hpp"
#include "coupling/fsi/beam_channel_wave.hpp"
#include "coupling/fsi/mpve_partitioned.hpp"

namespace {

using namespace amphora::coupling::fsi;

/// One step per iteration; the mean sub-iterations per step as a counter.
template <class Coupled>
void time_steps(benchmark::State& state, Coupled& fsi) {
  long long subiterations = 0, steps = 0;
  for (auto _ : state) {
    fsi.step();
    subiterations += fsi.last_subiterations();
    ++steps;
  }
  state.counters["subiterations_per_step"] = double(subiterations) / double(std::max(steps, 1LL));
}

void Beam(benchmark::State& state) {
  const auto scheme = static_cast<BeamScheme>(state.range(0));
  const double rho_h =
      scheme == BeamScheme::traditional ? 100.0 : 1.0 / static_cast<double>(state.range(1));
  BeamChannelSetup s = beam_channel_wave_case(rho_h, 160, scheme);
  s.end_time = 1e9;  // the benchmark decides how many steps
  BeamChannelFsi fsi(s);
  time_steps(state, fsi);
  state.counters["rho_h_over_rho"] = rho_h;
}
BENCHMARK(Beam)
    ->Args({0, 1})
    ->Args({1, 100})
    ->Args({1, 1000})
    ->Args({2, 100})
    ->Args({2, 1000})
    ->Unit(benchmark::kMicrosecond);

void Mpve(benchmark::State& state) {
  const int n = static_cast<int>(state.range(1));
  const double rho_bar = state.range(2) == 0 ? 1000.0 : 1.0 / static_cast<double>(state.range(2));
  MpveParameters p = mpve_check_case();
  p.mu = 0.02;
  p.rho_bar = p.lambda_bar = p.mu_bar = rho_bar;
  MpveSetup s;
  s.scheme = static_cast<MpveScheme>(state.range(0));
  s.physics = p;
  s.omega = mpve_root_from_check_case(p).omega;
  s.nx = n;
  s.dt = 0.3 / n;
  MpvePartitioned fsi(s);
  time_steps(state, fsi);
  state.counters["rho_bar_over_rho"] = rho_bar;
}
BENCHMARK(Mpve)
    ->Args({0, 80, 0})
    ->Args({2, 80, 0})
    ->Args({0, 160, 0})
    ->Args({2, 160, 0})
    ->Args({1, 80, 100})
    ->Args({2, 80, 100})
    ->Args({1, 80, 1000})
    ->Args({2, 80, 1000})
    ->Unit(benchmark::kMillisecond);

}  // namespace
