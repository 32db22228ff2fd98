#pragma once
// Counts Kokkos::deep_copy calls through the Kokkos Tools deep-copy hook, so a test or a run can
// say how many copies (and bytes) a time step makes between host and device. On a device build
// `crossing` counts them. A host build makes the same calls, but a host mirror is then the View
// itself: its copy is one of a View onto itself (`onto_itself`), which crosses on a device, and
// create_mirror_view_and_copy makes no call at all. host_device() adds the two: what crosses on
// this build, or would on a device, less the mirror-and-copy calls.
#include <cstdint>

namespace amphora::kernels {

struct DeepCopyCount {
  long long copies = 0;          ///< View to View (any memory spaces)
  long long bytes = 0;           ///< their bytes
  long long crossing = 0;        ///< of these, between two different memory spaces
  long long crossing_bytes = 0;  ///< their bytes
  long long onto_itself = 0;  ///< of `copies`, onto the same memory (a host mirror on a host build)
  long long onto_itself_bytes = 0;
  long long fills = 0;         ///< a View set to one value
  long long scalar_reads = 0;  ///< a rank-0 View read into a host value (a reduction's result)

  long long host_device() const { return crossing + onto_itself; }
  long long host_device_bytes() const { return crossing_bytes + onto_itself_bytes; }

  DeepCopyCount operator-(const DeepCopyCount& o) const {
    return {copies - o.copies,
            bytes - o.bytes,
            crossing - o.crossing,
            crossing_bytes - o.crossing_bytes,
            onto_itself - o.onto_itself,
            onto_itself_bytes - o.onto_itself_bytes,
            fills - o.fills,
            scalar_reads - o.scalar_reads};
  }
  DeepCopyCount operator+(const DeepCopyCount& o) const {
    return {copies + o.copies,
            bytes + o.bytes,
            crossing + o.crossing,
            crossing_bytes + o.crossing_bytes,
            onto_itself + o.onto_itself,
            onto_itself_bytes + o.onto_itself_bytes,
            fills + o.fills,
            scalar_reads + o.scalar_reads};
  }
};

/// While one of these lives, every deep copy is counted (one at a time: a second throws). A tool
/// library's own deep-copy callback, if one was loaded, is still called.
class DeepCopyCounter {
 public:
  DeepCopyCounter();
  ~DeepCopyCounter();
  DeepCopyCounter(const DeepCopyCounter&) = delete;
  DeepCopyCounter& operator=(const DeepCopyCounter&) = delete;

  DeepCopyCount count() const;
  void reset();
};

}  // namespace amphora::kernels
