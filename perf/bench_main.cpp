// The one main of every amphora benchmark: MPI and Kokkos up, and the build and run
// configuration recorded in Google Benchmark's context so every JSON result says what made it.
#include <benchmark/benchmark.h>

#include "io/build_info.hpp"
#include "mesh/environment.hpp"

int main(int argc, char** argv) {
  amphora::Environment env(argc, argv);
  for (const auto& [key, value] : amphora::build_info()) benchmark::AddCustomContext(key, value);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
