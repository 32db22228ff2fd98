#pragma once
// A plain, greppable progress line on rank 0:
//   [progress] step 1200/20000 t=6.0000e-02 dt=5.0000e-05 ETA 12.3 s 2.31e+07 point-steps/s
#include <chrono>
#include <iosfwd>
#include <string>

namespace amphora::io {

class Progress {
 public:
  Progress(std::ostream& out, bool active, long long first_step, long long last_step,
           std::string unit, double interval_seconds);
  /// Prints if `interval_seconds` passed since the last line (or force). `work` is the work
  /// done since construction (the unit's count: points, particles... times steps).
  void update(long long step, double time, double dt, double work, bool force = false);
  double elapsed() const;
  /// The step the run now expects to end on (an adaptive run's estimate moves).
  void set_last_step(long long last) { last_ = last; }

 private:
  std::ostream& out_;
  bool active_;
  long long first_, last_;
  std::string unit_;
  double interval_;
  std::chrono::steady_clock::time_point start_, last_print_;
};

}  // namespace amphora::io
