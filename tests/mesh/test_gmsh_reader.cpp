#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>

#include "mesh/tet/gmsh_reader.hpp"
#include "test_backend.hpp"

namespace amphora {
namespace {

// The unit cube as Gmsh 4.1 writes it: one node block, a block of two boundary triangles
// (skipped) and the six Kuhn tetrahedra, as written (three of them negatively oriented).
// app.solid reads the same file.
/// The file's text (tests/mesh/kuhn_cube.msh).
std::string cube_msh() {
  std::ifstream in(std::string(AMPHORA_TEST_MESH_DIR) + "/kuhn_cube.msh");
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}
std::string write(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}

std::string error_of(const std::string& path) {
  try {
    mesh::tet::read_gmsh(path);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(GmshReader, ReadsTheTetrahedraAndSkipsOtherElements) {
  const auto m = mesh::tet::read_gmsh(write("cube.msh", cube_msh()));
  ASSERT_EQ(m.n_nodes(), 8);
  ASSERT_EQ(m.n_tets(), 6);
  double total = 0.0;
  int negative = 0;
  for (int e = 0; e < m.n_tets(); ++e) {
    const double v = mesh::tet::tet_volume(m, e);
    total += std::abs(v);
    negative += v < 0.0;
  }
  EXPECT_NEAR(total, 1.0, 1e-14);
  EXPECT_EQ(negative, 3);
  EXPECT_EQ(m.nodes[7][0], 1.0);
  EXPECT_EQ(m.tets[5][3], 7);  // tag 8 -> index 7
}

TEST(GmshReader, BadFilesAreOneClearLine) {
  const std::string text = cube_msh();
  EXPECT_EQ(error_of("/nonexistent/x.msh"), "/nonexistent/x.msh: cannot open the mesh file");
  std::string v2 = text;
  v2.replace(v2.find("4.1 0 8"), 7, "2.2 0 8");
  const std::string p2 = write("v2.msh", v2);
  EXPECT_EQ(error_of(p2), p2 + ":2: MSH version 2.200000; amphora reads 4.1 (Gmsh -format msh41)");
  std::string missing = text;
  missing.replace(missing.find("6 1 3 7 8"), 9, "6 1 3 7 9");
  const std::string pm = write("missing.msh", missing);
  EXPECT_EQ(error_of(pm), pm + ":37: element 6 names node 9, which the $Nodes section lacks");
  const std::string pt = write("truncated.msh", text.substr(0, text.find("0 1 1\n")));
  EXPECT_EQ(error_of(pt), pt + ":25: the file ends where node coordinates should be");
  const std::string pn = write("notmsh.msh", "solid cube\nfacet normal 0 0 1\n");
  EXPECT_EQ(error_of(pn), pn + ":1: not an MSH file (the first section must be $MeshFormat)");
}

}  // namespace
}  // namespace amphora
