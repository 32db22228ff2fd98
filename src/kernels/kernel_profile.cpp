#include "kernels/kernel_profile.hpp"

#include <Kokkos_Core.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <map>
#include <ostream>
#include <stdexcept>
#include <utility>

namespace amphora::kernels {
namespace {
namespace timing {  // named, so a unity build's other files in this namespace cannot collide

using Clock = std::chrono::steady_clock;
using Begin = void (*)(const char*, std::uint32_t, std::uint64_t*);
using End = void (*)(std::uint64_t);
using Push = void (*)(const char*);
using Pop = void (*)();

std::atomic<bool> active{false};
Clock::time_point started;
std::map<std::pair<std::string, std::string>, KernelTime> table;  // by (region, label)
std::vector<std::string> regions;  // Kokkos::Profiling::pushRegion's stack
// kernels begun and not yet ended (a stack: a kernel's end comes before the next one's begin,
// but a tool's own id is not ours to use)
std::vector<std::pair<KernelTime*, Clock::time_point>> open;
Begin previous_begin[3] = {};
End previous_end[3] = {};
Push previous_push = nullptr;
Pop previous_pop = nullptr;

void on_push(const char* name) {
  if (previous_push) previous_push(name);
  regions.emplace_back(name);
}

void on_pop() {
  if (!regions.empty()) regions.pop_back();
  if (previous_pop) previous_pop();
}

template <int kind>
void on_begin(const char* name, std::uint32_t device, std::uint64_t* id) {
  if (previous_begin[kind]) previous_begin[kind](name, device, id);
  Kokkos::fence();  // what ran before is not this kernel's
  const std::string region = regions.empty() ? std::string() : regions.back();
  KernelTime& entry = table[{region, name}];
  if (entry.label.empty()) entry.label = name, entry.region = region;
  open.emplace_back(&entry, Clock::now());
}

template <int kind>
void on_end(std::uint64_t id) {
  Kokkos::fence();
  const auto now = Clock::now();
  if (!open.empty()) {
    auto [entry, t0] = open.back();
    open.pop_back();
    const double s = std::chrono::duration<double>(now - t0).count();
    entry->min_seconds = entry->calls == 0 ? s : std::min(entry->min_seconds, s);
    entry->seconds += s;
    ++entry->calls;
  }
  if (previous_end[kind]) previous_end[kind](id);
}

}  // namespace timing
}  // namespace

KernelProfile::KernelProfile() {
  if (timing::active.exchange(true))
    throw std::logic_error("amphora::KernelProfile: one is already timing");
  namespace tools = Kokkos::Tools::Experimental;
  const auto callbacks = tools::get_callbacks();
  timing::previous_begin[0] = callbacks.begin_parallel_for;
  timing::previous_begin[1] = callbacks.begin_parallel_reduce;
  timing::previous_begin[2] = callbacks.begin_parallel_scan;
  timing::previous_end[0] = callbacks.end_parallel_for;
  timing::previous_end[1] = callbacks.end_parallel_reduce;
  timing::previous_end[2] = callbacks.end_parallel_scan;
  timing::previous_push = callbacks.push_region;
  timing::previous_pop = callbacks.pop_region;
  tools::set_begin_parallel_for_callback(&timing::on_begin<0>);
  tools::set_begin_parallel_reduce_callback(&timing::on_begin<1>);
  tools::set_begin_parallel_scan_callback(&timing::on_begin<2>);
  tools::set_end_parallel_for_callback(&timing::on_end<0>);
  tools::set_end_parallel_reduce_callback(&timing::on_end<1>);
  tools::set_end_parallel_scan_callback(&timing::on_end<2>);
  tools::set_push_region_callback(&timing::on_push);
  tools::set_pop_region_callback(&timing::on_pop);
  reset();
}

KernelProfile::~KernelProfile() {
  namespace tools = Kokkos::Tools::Experimental;
  tools::set_begin_parallel_for_callback(timing::previous_begin[0]);
  tools::set_begin_parallel_reduce_callback(timing::previous_begin[1]);
  tools::set_begin_parallel_scan_callback(timing::previous_begin[2]);
  tools::set_end_parallel_for_callback(timing::previous_end[0]);
  tools::set_end_parallel_reduce_callback(timing::previous_end[1]);
  tools::set_end_parallel_scan_callback(timing::previous_end[2]);
  tools::set_push_region_callback(timing::previous_push);
  tools::set_pop_region_callback(timing::previous_pop);
  timing::regions.clear();
  timing::table.clear();
  timing::open.clear();
  timing::active = false;
}

std::vector<KernelTime> KernelProfile::kernels() const {
  std::vector<KernelTime> rows;
  for (const auto& [key, row] : timing::table) rows.push_back(row);
  std::stable_sort(rows.begin(), rows.end(),
                   [](const KernelTime& a, const KernelTime& b) { return a.seconds > b.seconds; });
  return rows;
}

double KernelProfile::seconds() const {
  return std::chrono::duration<double>(timing::Clock::now() - timing::started).count();
}

void KernelProfile::reset() {
  timing::table.clear();
  timing::open.clear();
  timing::started = timing::Clock::now();
}

void write_kernel_profile_csv(std::ostream& out, const KernelProfile& profile) {
  const double wall = profile.seconds();
  const std::vector<KernelTime> rows = profile.kernels();
  const auto share = [wall](double s) { return wall > 0.0 ? s / wall : 0.0; };
  out << "region,label,calls,seconds,mean_us,min_us,share\n";
  const auto quoted = [](const std::string& text) {  // a quote inside is doubled
    std::string q = "\"";
    for (const char c : text) q += c == '"' ? std::string("\"\"") : std::string(1, c);
    return q + '"';
  };
  double covered = 0.0;
  for (const KernelTime& k : rows) {
    covered += k.seconds;
    out << quoted(k.region) << ',' << quoted(k.label) << ',' << k.calls << ',' << k.seconds << ','
        << 1e6 * k.seconds / static_cast<double>(k.calls) << ',' << 1e6 * k.min_seconds << ','
        << share(k.seconds) << '\n';
  }
  const double outside = std::max(0.0, wall - covered);
  out << "\"\",\"(outside kernels)\",0," << outside << ",0,0," << share(outside) << '\n';
}

}  // namespace amphora::kernels
