#pragma once
// The memory-bandwidth roofline every benchmark reports its fraction of: STREAM triad
// (a = b + s c) through Kokkos on the default execution space, measured in the same executable.
#include <cstddef>

namespace amphora::perf {

/// Best-of-`repeats` STREAM triad bandwidth in bytes/s over arrays of n doubles (24 n bytes
/// moved per pass, write-allocate not counted, as STREAM counts). Cached after the first call
/// with the same n.
double stream_triad_bandwidth(std::size_t n = std::size_t(1) << 26, int repeats = 10);

}  // namespace amphora::perf
