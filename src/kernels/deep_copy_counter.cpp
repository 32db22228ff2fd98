#include "kernels/deep_copy_counter.hpp"

#include <atomic>
#include <cstring>
#include <stdexcept>

#include <Kokkos_Core.hpp>

namespace amphora::kernels {
namespace {

using Handle = Kokkos_Profiling_SpaceHandle;  // the C struct: the same name in Kokkos 3.4 and 4.x
using Callback = void (*)(Handle, const char*, const void*, Handle, const char*, const void*,
                          std::uint64_t);

std::atomic<bool> active{false};
Callback previous = nullptr;
DeepCopyCount tally;

void on_deep_copy(Handle dst, const char* dst_label, const void* dst_ptr, Handle src,
                  const char* src_label, const void* src_ptr, std::uint64_t bytes) {
  // Kokkos labels the host side of a fill and of a rank-0 read "Scalar" (Kokkos_CopyViews.hpp).
  if (std::strcmp(src_label, "Scalar") == 0) {
    ++tally.fills;
  } else if (std::strcmp(dst_label, "Scalar") == 0) {
    ++tally.scalar_reads;
  } else {
    ++tally.copies;
    tally.bytes += static_cast<long long>(bytes);
    if (std::strncmp(dst.name, src.name, sizeof(dst.name)) != 0) {
      ++tally.crossing;
      tally.crossing_bytes += static_cast<long long>(bytes);
    } else if (dst_ptr == src_ptr) {
      ++tally.onto_itself;
      tally.onto_itself_bytes += static_cast<long long>(bytes);
    }
  }
  if (previous) previous(dst, dst_label, dst_ptr, src, src_label, src_ptr, bytes);
}

}  // namespace

DeepCopyCounter::DeepCopyCounter() {
  if (active.exchange(true))
    throw std::logic_error("amphora::DeepCopyCounter: one is already counting");
  tally = {};
  previous = Kokkos::Tools::Experimental::get_callbacks().begin_deep_copy;
  Kokkos::Tools::Experimental::set_begin_deep_copy_callback(&on_deep_copy);
}

DeepCopyCounter::~DeepCopyCounter() {
  Kokkos::Tools::Experimental::set_begin_deep_copy_callback(previous);
  previous = nullptr;
  active = false;
}

DeepCopyCount DeepCopyCounter::count() const { return tally; }
void DeepCopyCounter::reset() { tally = {}; }

}  // namespace amphora::kernels
