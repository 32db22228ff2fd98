// The one main of every amphora benchmark: MPI and Kokkos up, and the build and run
// configuration recorded in Google Benchmark's context so every JSON result says what made it.
#include <benchmark/benchmark.h>

#include "io/build_info.hpp"
#include "base/environment.hpp"

#include <cstdio>

int main(int argc, char** argv) {
  amphora::Environment env(argc, argv);
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  if (rank != 0 && !std::freopen("/dev/null", "w", stdout)) return 1;  // one report per run
  for (const auto& [key, value] : amphora::io::build_info())
    benchmark::AddCustomContext(key, value);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
