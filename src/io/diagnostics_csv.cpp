#include "io/diagnostics_csv.hpp"

#include <sstream>
#include <stdexcept>
#include <vector>

#include "io/field_series.hpp"

namespace amphora::io {

DiagnosticsCsv::DiagnosticsCsv(const std::string& path, bool active, long long resume_after_step)
    : path_(path), active_(active) {
  if (!active_) return;
  if (resume_after_step >= 0) {
    std::ifstream in(path);
    std::string line, kept;
    bool first = true;
    while (std::getline(in, line)) {
      if (first) {
        kept += line + "\n";
        header_written_ = true;
        first = false;
        continue;
      }
      const long long step = std::stoll(line.substr(0, line.find(',')));
      if (step <= resume_after_step) kept += line + "\n";
    }
    write_file_atomically(path, kept);
    out_.open(path, std::ios::app);
  } else {
    out_.open(path, std::ios::trunc);
  }
  if (!out_) throw std::runtime_error("cannot open '" + path + "' for writing");
  out_.precision(17);
}

void DiagnosticsCsv::write(long long step, double time, double dt, const Diagnostics& values) {
  if (!active_) return;
  if (!header_written_) {
    out_ << "step,time,dt";
    for (const auto& [name, v] : values) out_ << "," << name;
    out_ << "\n";
    header_written_ = true;
  }
  out_ << step << "," << time << "," << dt;
  for (const auto& [name, v] : values) out_ << "," << v;
  out_ << "\n";
  out_.flush();
}

}  // namespace amphora::io
