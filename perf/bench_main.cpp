// The one main of every amphora benchmark: MPI and Kokkos up, and the build and run
// configuration recorded in Google Benchmark's context so every JSON result says what made it.
// AMPHORA_KERNEL_PROFILE=FILE times every kernel of rank 0 (kernels/kernel_profile.hpp: fenced,
// so the benchmarks' own figures are then not the ones to report) and writes the table as CSV.
#include <benchmark/benchmark.h>

#include "io/build_info.hpp"
#include "base/environment.hpp"

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <memory>

#include "kernels/kernel_profile.hpp"

int main(int argc, char** argv) {
  amphora::Environment env(argc, argv);
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  if (rank != 0 && !std::freopen("/dev/null", "w", stdout)) return 1;  // one report per run
  for (const auto& [key, value] : amphora::io::build_info())
    benchmark::AddCustomContext(key, value);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  const char* profile_file = std::getenv("AMPHORA_KERNEL_PROFILE");
  std::unique_ptr<amphora::kernels::KernelProfile> profile;
  if (profile_file && *profile_file && rank == 0)
    profile = std::make_unique<amphora::kernels::KernelProfile>();
  benchmark::RunSpecifiedBenchmarks();
  if (profile) {
    std::ofstream out(profile_file);
    amphora::kernels::write_kernel_profile_csv(out, *profile);
    if (!out) std::cerr << "AMPHORA_KERNEL_PROFILE: cannot write " << profile_file << "\n";
  }
  benchmark::Shutdown();
  return 0;
}
