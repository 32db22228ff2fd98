#include "base/environment.hpp"

#include <Kokkos_Core.hpp>

#include <cstdio>
#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <vector>

#ifdef KOKKOS_ENABLE_CUDA
#include <cuda_runtime_api.h>
#endif

namespace amphora {
namespace {
/// A CUDA build started where no GPU is visible says so in one line and exits 1 (Kokkos would
/// abort with a core dump).
void require_visible_device() {
#ifdef KOKKOS_ENABLE_CUDA
  int n = 0;
  const cudaError_t e = cudaGetDeviceCount(&n);
  if (e != cudaSuccess || n == 0) {
    std::fprintf(stderr,
                 "amphora: this build runs its kernels on CUDA, but no GPU is visible (%s)\n",
                 e != cudaSuccess ? cudaGetErrorString(e) : "no device");
    std::exit(1);
  }
#endif
}
}  // namespace

struct Environment::KokkosGuard {
  KokkosGuard(int& argc, char** argv) : guard(argc, argv) {}
  Kokkos::ScopeGuard guard;
};

/// Kokkos answers --help with its own text and warns about thread binding. For --help, --version
/// or a bare subcommand the help flag is hidden from Kokkos (its own stays under --kokkos-help)
/// and its warnings are off, so the application's text is all that is printed.
void Environment::start_kokkos(int& argc, char**& argv) {
  static char hidden[] = "--amphora-help", quiet[] = "--kokkos-disable-warnings";
  std::vector<char*> args, help;
  for (int i = 0; i < argc; ++i) {
    const bool is_help = std::strcmp(argv[i], "--help") == 0 || std::strcmp(argv[i], "-h") == 0;
    if (is_help) help.push_back(argv[i]);
    args.push_back(is_help ? hidden : argv[i]);
  }
  const bool asks =
      argc == 2 || !help.empty() || std::find_if(argv, argv + argc, [](const char* a) {
                                      return std::strcmp(a, "--version") == 0;
                                    }) != argv + argc;
  if (asks) args.push_back(quiet);
  int n = static_cast<int>(args.size());
  args.push_back(nullptr);
  char** kargv = args.data();
  kokkos_ = std::make_unique<KokkosGuard>(n, kargv);
  int out = 0, next_help = 0;
  for (int i = 0; i < n; ++i) {  // what Kokkos left, the hidden flags restored
    if (kargv[i] == quiet) continue;
    argv[out++] = kargv[i] == hidden ? help[next_help++] : kargv[i];
  }
  argc = out;
}

Environment::Environment(int& argc, char**& argv) {
  require_visible_device();
  int initialized = 0;
  MPI_Initialized(&initialized);
  if (!initialized) {
    int provided = 0;
    // Only the thread that called MPI_Init talks to MPI; OpenMP threads never do.
    MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
    owns_mpi_ = true;
  }
  start_kokkos(argc, argv);
}

Environment::~Environment() {
  kokkos_.reset();
  if (owns_mpi_) {
    int finalized = 0;
    MPI_Finalized(&finalized);
    if (!finalized) MPI_Finalize();
  }
}

}  // namespace amphora
