#include "io/progress.hpp"

#include <cstdio>
#include <ostream>
#include <string>

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
      last_print_(start_),
      last_line_step_(first_step) {}

double Progress::elapsed() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void Progress::update(long long step, double time, double dt, double work, bool force) {
  if (!active_) return;
  const auto now = std::chrono::steady_clock::now();
  if (!force && std::chrono::duration<double>(now - last_print_).count() < interval_) return;
  last_print_ = now;
  out_ << line(step, time, dt, work, elapsed()) << std::flush;
}

std::string Progress::line(long long step, double time, double dt, double work, double seconds) {
  const double span = seconds - last_line_seconds_;
  const long long steps = step - last_line_step_;
  const double eta =
      steps > 0 && span > 0 ? span / double(steps) * double(last_ - step) : last_eta_;
  last_eta_ = eta;
  // No step since the line before (the run's closing line): the rate of that line stands.
  if (steps > 0 && span > 0) last_rate_ = (work - last_line_work_) / span;
  last_line_step_ = step;
  last_line_work_ = work;
  last_line_seconds_ = seconds;
  char text[256];
  std::snprintf(text, sizeof text,
                "[progress] step %lld/%lld t=%.4e dt=%.4e ETA %.1f s %.3e %s/s\n", step, last_,
                time, dt, eta, last_rate_, unit_.c_str());
  return text;
}

}  // namespace amphora::io
