#include "io/progress.hpp"

#include <cstdio>
#include <ostream>

namespace amphora::io {

Progress::Progress(std::ostream& out, bool active, long long first_step, long long last_step,
                   std::string unit, double interval_seconds)
    : out_(out),
      active_(active),
      first_(first_step),
      last_(last_step),
      unit_(std::move(unit)),
      interval_(interval_seconds),
      start_(std::chrono::steady_clock::now()),
      last_print_(start_) {}

double Progress::elapsed() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void Progress::update(long long step, double time, double dt, double work, bool force) {
  if (!active_) return;
  const auto now = std::chrono::steady_clock::now();
  if (!force && std::chrono::duration<double>(now - last_print_).count() < interval_) return;
  last_print_ = now;
  const double t = elapsed();
  const long long done = step - first_;
  const double eta = done > 0 ? t / double(done) * double(last_ - step) : 0.0;
  char line[256];
  std::snprintf(line, sizeof line,
                "[progress] step %lld/%lld t=%.4e dt=%.4e ETA %.1f s %.3e %s/s\n", step, last_,
                time, dt, eta, t > 0 ? work / t : 0.0, unit_.c_str());
  out_ << line << std::flush;
}

}  // namespace amphora::io
