#pragma once
// diagnostics.csv: one row per diagnostics step (step, time, dt, then the module's values),
// written by rank 0 and flushed per row so a run that dies keeps what it had. Holds no wall
// times, so a restarted run reproduces it exactly.
#include <fstream>
#include <string>

#include "base/output_block.hpp"

namespace amphora::io {

class DiagnosticsCsv {
 public:
  /// Fresh file, or (resume_after_step >= 0) the existing one truncated to rows with
  /// step <= resume_after_step. Only `active` (rank 0) touches the file.
  DiagnosticsCsv(const std::string& path, bool active, long long resume_after_step = -1);
  void write(long long step, double time, double dt, const Diagnostics& values);

 private:
  std::string path_;
  bool active_;
  bool header_written_ = false;
  std::ofstream out_;
};

}  // namespace amphora::io
