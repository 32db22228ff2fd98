// Rates of the 1D kernels (BLAS-1 axpy and dot, the centred advection-diffusion step) and
// their fraction of the STREAM triad bandwidth measured in this executable.
#include <benchmark/benchmark.h>

#include <chrono>

#include "kernels/blas1.hpp"
#include "kernels/stencil_1d.hpp"
#include "stream_bandwidth.hpp"

namespace {

using amphora::kernels::DefaultExecSpace;
using View = Kokkos::View<double*, amphora::kernels::DefaultMemSpace>;

struct Source {
  KOKKOS_INLINE_FUNCTION double operator()(double x, double t) const { return x * t; }
};

template <class Kernel>
void run(benchmark::State& state, double bytes_per_entry, Kernel kernel) {
  const int n = static_cast<int>(state.range(0));
  View x("x", n), y("y", n);
  Kokkos::deep_copy(x, 1.0);
  Kokkos::deep_copy(y, 2.0);
  const DefaultExecSpace exec;
  const double stream = amphora::perf::stream_triad_bandwidth();  // measured before timing
  double seconds = 0.0;
  for (auto _ : state) {
    exec.fence();
    const auto t0 = std::chrono::steady_clock::now();
    kernel(exec, n, x, y);
    exec.fence();
    const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    state.SetIterationTime(t);
    seconds += t;
  }
  const double bytes_per_second = bytes_per_entry * n * double(state.iterations()) / seconds;
  state.counters["entries"] = benchmark::Counter(n, benchmark::Counter::kIsIterationInvariantRate,
                                                 benchmark::Counter::OneK::kIs1000);
  state.counters["bandwidth"] = benchmark::Counter(bytes_per_second, benchmark::Counter::kDefaults,
                                                   benchmark::Counter::OneK::kIs1000);
  state.counters["stream"] =
      benchmark::Counter(stream, benchmark::Counter::kDefaults, benchmark::Counter::OneK::kIs1000);
  state.counters["fraction_of_stream"] = bytes_per_second / stream;
}

void Axpy(benchmark::State& state) {
  run(state, 24.0, [](const DefaultExecSpace& e, int, View x, View y) {
    amphora::kernels::blas1::axpy(e, 1e-3, x, y);
  });
}

void Dot(benchmark::State& state) {
  run(state, 16.0, [](const DefaultExecSpace& e, int, View x, View y) {
    benchmark::DoNotOptimize(amphora::kernels::blas1::dot(e, x, y));
  });
}

void AdvectionDiffusionStep(benchmark::State& state) {
  run(state, 16.0, [](const DefaultExecSpace& e, int n, View x, View y) {
    amphora::kernels::stencil::advection_diffusion_ftcs(e, x, y, 1, n - 1, 0.0, 1.0 / n, 1.0, 0.05,
                                                        0.0, 1e-6, Source{});
  });
}

}  // namespace

BENCHMARK(Axpy)
    ->UseManualTime()
    ->Unit(benchmark::kMicrosecond)
    ->Arg(1 << 10)
    ->Arg(1 << 16)
    ->Arg(1 << 22)
    ->Arg(1 << 25);
BENCHMARK(Dot)
    ->UseManualTime()
    ->Unit(benchmark::kMicrosecond)
    ->Arg(1 << 10)
    ->Arg(1 << 16)
    ->Arg(1 << 22)
    ->Arg(1 << 25);
BENCHMARK(AdvectionDiffusionStep)
    ->UseManualTime()
    ->Unit(benchmark::kMicrosecond)
    ->Arg(1 << 10)
    ->Arg(1 << 16)
    ->Arg(1 << 22)
    ->Arg(1 << 25);
