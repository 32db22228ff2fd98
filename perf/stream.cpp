// STREAM copy and triad through Kokkos (McCalpin's kernels, bytes counted as STREAM does:
// 16 per element for copy, 24 for triad). Reports GB/s; run at 1 and 2 threads
// (scripts/bench.sh). Sizes: one in cache, the rest well beyond the last-level cache.
#include <benchmark/benchmark.h>

#include <chrono>

#include "kernels/spaces.hpp"

// A named namespace, not an anonymous one: CUDA does not support extended lambdas in
// anonymous namespaces (Kokkos issue #1547).
namespace bench_stream_cases {

using amphora::kernels::DefaultExecSpace;
using amphora::kernels::DefaultMemSpace;
using View = Kokkos::View<double*, DefaultMemSpace>;

template <class Kernel>
void run(benchmark::State& state, double bytes_per_element, Kernel kernel) {
  const int n = static_cast<int>(state.range(0));
  View a("amphora::stream::a", n), b("amphora::stream::b", n), c("amphora::stream::c", n);
  Kokkos::deep_copy(a, 0.0);
  Kokkos::deep_copy(b, 1.0);
  Kokkos::deep_copy(c, 2.0);
  for (auto _ : state) {
    Kokkos::fence();
    const auto t0 = std::chrono::steady_clock::now();
    kernel(n, a, b, c);
    Kokkos::fence();
    state.SetIterationTime(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  const double bytes = bytes_per_element * n;
  // Shown as e.g. "bandwidth=13.6G/s" (decimal giga, as STREAM reports).
  state.counters["bandwidth"] = benchmark::Counter(
      bytes, benchmark::Counter::kIsIterationInvariantRate, benchmark::Counter::OneK::kIs1000);
  state.counters["MiB"] = 3.0 * 8.0 * n / (1 << 20);
  state.counters["threads"] = DefaultExecSpace().concurrency();
}

void StreamCopy(benchmark::State& state) {
  run(state, 16.0, [](int n, View a, View b, View) {
    Kokkos::parallel_for(
        "amphora::perf::stream_copy", amphora::kernels::RangePolicy<DefaultExecSpace>(0, n),
        KOKKOS_LAMBDA(int i) { a(i) = b(i); });
  });
}

void StreamTriad(benchmark::State& state) {
  run(state, 24.0, [](int n, View a, View b, View c) {
    const double s = 3.0;
    Kokkos::parallel_for(
        "amphora::perf::stream_triad", amphora::kernels::RangePolicy<DefaultExecSpace>(0, n),
        KOKKOS_LAMBDA(int i) { a(i) = b(i) + s * c(i); });
  });
}

/// Launches/n: 1000 kernels in a row, each adding one to n entries (each depends on the last),
/// one fence at the end: what a launch costs when a solver queues many small kernels, as a
/// multigrid's coarse levels do (their grids hold 512 or 4096 cells). Reports seconds per launch.
void Launches(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0)), launches = 1000;
  View a("amphora::stream::a", n);
  for (auto _ : state) {
    Kokkos::fence();
    const auto t0 = std::chrono::steady_clock::now();
    for (int l = 0; l < launches; ++l)
      Kokkos::parallel_for(
          "amphora::perf::launch", amphora::kernels::RangePolicy<DefaultExecSpace>(0, n),
          KOKKOS_LAMBDA(int i) { a(i) += 1.0; });
    Kokkos::fence();
    state.SetIterationTime(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  state.counters["s_per_launch"] = benchmark::Counter(
      launches, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

}  // namespace bench_stream_cases
using namespace bench_stream_cases;

BENCHMARK(Launches)->UseManualTime()->Unit(benchmark::kMicrosecond)->Arg(512)->Arg(4096);

BENCHMARK(StreamCopy)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->Arg(1 << 10)
    ->Arg(1 << 20)
    ->Arg(1 << 25)
    ->Arg(1 << 26);
BENCHMARK(StreamTriad)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->Arg(1 << 10)
    ->Arg(1 << 20)
    ->Arg(1 << 25)
    ->Arg(1 << 26);
