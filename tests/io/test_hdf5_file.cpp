// Collective HDF5 writes at 1 and 2 ranks: each rank's blocks come back intact, attributes and
// text entries are seen by all.
#include <cstdio>
#include <string>

#include "io/hdf5_file.hpp"
#include "test_backend.hpp"

namespace amphora {
namespace {

TEST(Hdf5File, RoundTripOfRankOwnedGroups) {
  Communicator comm;
  const std::string path = "test_hdf5_file_np" + std::to_string(comm.size()) + ".h5";
  std::vector<io::H5Group> mine;
  std::vector<double> values(100 + 7 * comm.rank());
  for (size_t i = 0; i < values.size(); ++i) values[i] = 1.0 / (1.0 + i) + comm.rank();
  mine.push_back({"block" + std::to_string(comm.rank()), {{"u", values}, {"empty", {}}}});
  io::H5Metadata meta;
  meta.reals["time"] = 0.1;
  meta.integers["step"] = 42;
  meta.texts["note"] = "written by " + std::to_string(comm.size()) + " ranks";
  const auto layout = io::write_h5(path, comm, mine, meta);
  EXPECT_EQ(layout.size(), size_t(2 * comm.size()));

  io::H5Reader in(path, comm);
  EXPECT_EQ(in.real("time"), 0.1);
  EXPECT_EQ(in.integer("step"), 42);
  EXPECT_EQ(in.text("note"), meta.texts["note"]);
  EXPECT_FALSE(in.has("absent"));
  for (int r = 0; r < comm.size(); ++r) {
    const auto g = in.group("block" + std::to_string(r));
    ASSERT_EQ(g.size(), 2u);
    for (const auto& [name, data] : g) {
      if (name == "u") {
        ASSERT_EQ(data.size(), size_t(100 + 7 * r));
        for (size_t i = 0; i < data.size(); ++i) EXPECT_EQ(data[i], 1.0 / (1.0 + i) + r);
      } else {
        EXPECT_EQ(name, "empty");
        EXPECT_TRUE(data.empty());
      }
    }
  }
}

TEST(Hdf5File, UnwritablePathIsAnErrorOnEveryRank) {
  Communicator comm;
  EXPECT_THROW(io::write_h5("/nonexistent_dir_amphora/x.h5", comm, {}, {}), std::runtime_error);
}

}  // namespace
}  // namespace amphora
