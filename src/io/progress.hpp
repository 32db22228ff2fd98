#pragma once
// A plain, greppable progress line on rank 0:
//   [progress] step 1200/20000 t=6.0000e-02 dt=5.0000e-05 ETA 12.3 s 2.31e+07 point-steps/s
// The ETA and the throughput are those of the steps since the line before: a run whose steps
// grow dearer (a bed forming, a flow turning turbulent) is not promised its mean rate.
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
  /// The line update prints at `seconds` after construction (elapsed(), or a test's clock);
  /// the interval since the last line is measured from here.
  std::string line(long long step, double time, double dt, double work, double seconds);
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
  long long last_line_step_;  // step and work of the last line (construction's at first)
  double last_line_work_ = 0.0, last_line_seconds_ = 0.0;
  double last_rate_ = 0.0, last_eta_ = 0.0;  // of the last line with steps in it
};

}  // namespace amphora::io
