#pragma once
// Field output as a time series ParaView opens: one HDF5 file per output step
// (<dir>/fields_<step>.h5, a group per block with x, y, z and the point fields) and one XDMF
// file for the run (<dir>/<scene>.xmf, a temporal collection of spatial collections of 3D
// rectilinear, curvilinear, point-set or tetrahedral blocks), rewritten atomically after each
// step. The series' entries are part of a checkpoint so a restarted run continues the same file.
#include <string>
#include <vector>

#include "base/communicator.hpp"
#include "base/output_block.hpp"

namespace amphora::io {

class FieldSeries {
 public:
  FieldSeries(std::string dir, std::string scene_name, Communicator comm);

  /// Writes the blocks of all ranks for this step and updates the series. Collective.
  /// Returns the HDF5 file written.
  std::string write(long long step, double time, const std::vector<OutputBlock>& local_blocks);

  /// Path of the last file written ("" before the first), inside the output directory.
  std::string last_file() const { return last_file_.empty() ? "" : dir_ + "/" + last_file_; }
  long long last_step() const { return last_step_; }
  std::string series_path() const;

  /// The series' entries as text, for a checkpoint, and back.
  std::string save() const;
  void load(const std::string& saved);

 private:
  void write_xdmf() const;

  std::string dir_, name_;
  Communicator comm_;
  std::vector<std::string> entries_;  // one XDMF <Grid> per written step
  std::string last_file_;  // relative to dir_, so a checkpoint does not name its directory
  long long last_step_ = -1;
};

/// Writes `text` to `path` through a temporary file and a rename, so readers never see a
/// partial file. Throws std::runtime_error on failure.
void write_file_atomically(const std::string& path, const std::string& text);

}  // namespace amphora::io
