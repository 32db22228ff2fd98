#include "stream_bandwidth.hpp"

#include <chrono>
#include <map>

#include "kernels/spaces.hpp"

namespace amphora::perf {

double stream_triad_bandwidth(std::size_t n, int repeats) {
  static std::map<std::size_t, double> cache;
  if (auto it = cache.find(n); it != cache.end()) return it->second;
  using View = Kokkos::View<double*, kernels::DefaultMemSpace>;
  View a("amphora::stream::a", n), b("amphora::stream::b", n), c("amphora::stream::c", n);
  Kokkos::deep_copy(b, 1.0);
  Kokkos::deep_copy(c, 2.0);
  const double s = 3.0;
  double best = 0.0;
  for (int r = 0; r < repeats; ++r) {
    Kokkos::fence();
    const auto t0 = std::chrono::steady_clock::now();
    Kokkos::parallel_for(
        "amphora::perf::stream_triad", kernels::RangePolicy<kernels::DefaultExecSpace>(0, int(n)),
        KOKKOS_LAMBDA(int i) { a(i) = b(i) + s * c(i); });
    Kokkos::fence();
    const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    best = std::max(best, 24.0 * double(n) / t);
  }
  cache[n] = best;
  return best;
}

}  // namespace amphora::perf
