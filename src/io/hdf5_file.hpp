#pragma once
// One HDF5 file written collectively by all ranks through MPI-IO: each rank contributes the
// groups (blocks) it owns, every dataset is 1D double, and the file carries scalar
// attributes and text entries on its root. Block metadata is gathered first so that every rank
// makes the same collective create calls; each rank then writes its own data independently.
// Object timestamps are off, so the same data gives the same bytes.
#include <map>
#include <string>
#include <vector>

#include "base/communicator.hpp"
#include "base/output_block.hpp"

namespace amphora::io {

struct H5Group {
  std::string name;
  std::vector<NamedArray> datasets;
};

struct H5Metadata {
  std::map<std::string, double> reals;
  std::map<std::string, long long> integers;
  std::map<std::string, std::string> texts;
};

/// One dataset of the file, as every rank sees it after the write.
struct H5DatasetInfo {
  std::string group, name;
  unsigned long long size = 0;
  int owner = 0;
};

/// Writes `path` (replacing it) and returns the layout of every rank's datasets, in rank
/// order. Collective. Throws std::runtime_error on failure.
std::vector<H5DatasetInfo> write_h5(const std::string& path, const Communicator& comm,
                                    const std::vector<H5Group>& local_groups,
                                    const H5Metadata& meta);

/// Reads a file written by write_h5. Opening is collective; group reads are not.
class H5Reader {
 public:
  H5Reader(const std::string& path, const Communicator& comm);
  ~H5Reader();
  H5Reader(const H5Reader&) = delete;
  H5Reader& operator=(const H5Reader&) = delete;

  double real(const std::string& name) const;
  long long integer(const std::string& name) const;
  std::string text(const std::string& name) const;
  bool has(const std::string& name) const;
  /// Every dataset of a group.
  std::vector<NamedArray> group(const std::string& name) const;

 private:
  std::string path_;
  long long file_ = -1;  // hid_t, kept out of this header
};

}  // namespace amphora::io
