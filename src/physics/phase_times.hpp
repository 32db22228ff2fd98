#pragma once
// Wall time per phase of a module's step, for the run's closing [timing] lines (Module::
// phase_seconds): where a step's time goes, measured in the run itself. Laps: each lap() books
// the time since the previous one to a phase. Fenced, so kernels a device still queues count in
// the phase that launched them.
#include <Kokkos_Core.hpp>

#include <chrono>
#include <string>
#include <utility>
#include <vector>

namespace amphora::physics {

class PhaseTimes {
 public:
  explicit PhaseTimes(std::vector<std::string> names)
      : names_(std::move(names)), seconds_(names_.size(), 0.0) {}

  /// Starts the clock for the next lap.
  void start() {
    Kokkos::fence();
    last_ = Clock::now();
  }
  /// Books the time since start() or the previous lap to phase `phase` (an index of names).
  void lap(int phase) {
    Kokkos::fence();
    const auto now = Clock::now();
    seconds_[phase] += std::chrono::duration<double>(now - last_).count();
    last_ = now;
  }
  /// (name, seconds) of every phase, in order.
  std::vector<std::pair<std::string, double>> seconds() const {
    std::vector<std::pair<std::string, double>> out;
    for (std::size_t p = 0; p < names_.size(); ++p) out.emplace_back(names_[p], seconds_[p]);
    return out;
  }

 private:
  using Clock = std::chrono::steady_clock;
  std::vector<std::string> names_;
  std::vector<double> seconds_;
  Clock::time_point last_ = Clock::now();
};

}  // namespace amphora::physics
