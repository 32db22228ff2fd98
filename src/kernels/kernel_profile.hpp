#pragma once
// Times every Kokkos kernel by label through the Kokkos Tools begin/end hooks (parallel_for,
// parallel_reduce, parallel_scan). Each kernel is fenced before and after, so its time is its
// launch plus its run, serialised: a profile of where a run's time goes, not a benchmark (the
// fences remove the overlap of one launch with the previous kernel's run). What the kernels do
// not cover (host work, copies, MPI) is the profile's wall time less their sum. A kernel is
// counted apart in each Kokkos::Profiling region it runs in (the innermost one), so a solver can
// name, say, its multigrid levels.
#include <iosfwd>
#include <string>
#include <vector>

namespace amphora::kernels {

struct KernelTime {
  std::string region;  ///< the innermost Kokkos::Profiling region it ran in (empty: none)
  std::string label;
  long long calls = 0;
  double seconds = 0.0;      ///< all calls
  double min_seconds = 0.0;  ///< the shortest call: a floor set by the launch on a device
};

/// While one of these lives, every kernel is timed (one at a time: a second throws
/// std::logic_error). A tool library's own callbacks, if one was loaded, are still called.
class KernelProfile {
 public:
  KernelProfile();
  ~KernelProfile();
  KernelProfile(const KernelProfile&) = delete;
  KernelProfile& operator=(const KernelProfile&) = delete;

  /// Every (region, label) timed since the start or the last reset, the longest total first.
  std::vector<KernelTime> kernels() const;
  /// Wall seconds since the start or the last reset.
  double seconds() const;
  void reset();
};

/// CSV with a header: region, label, calls, seconds, mean_us, min_us, share (of the wall time); a
/// last row "(outside kernels)" holds the wall time the kernels do not cover.
void write_kernel_profile_csv(std::ostream& out, const KernelProfile& profile);

}  // namespace amphora::kernels
