#include "mesh/tet/gmsh_reader.hpp"

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <unordered_map>
#include <utility>

namespace amphora::mesh::tet {

namespace {

/// Line-numbered reading, every error naming the file and line.
class MshLines {
 public:
  explicit MshLines(const std::string& path) : path_(path), in_(path) {
    if (!in_) throw std::invalid_argument(path + ": cannot open the mesh file");
  }
  /// The next line as a stream; throws at the end of the file.
  std::istringstream next(const std::string& expecting) {
    std::string line;
    if (!std::getline(in_, line))
      fail("the file ends where " + expecting + " should be", line_ + 1);
    ++line_;
    return std::istringstream(line);
  }
  bool next_line(std::string& line) {
    if (!std::getline(in_, line)) return false;
    ++line_;
    return true;
  }
  [[noreturn]] void fail(const std::string& what, long line = -1) const {
    throw std::invalid_argument(path_ + ":" + std::to_string(line < 0 ? line_ : line) + ": " +
                                what);
  }
  template <class... T>
  void read(std::istringstream& s, const std::string& what, T&... values) {
    if (!(s >> ... >> values)) fail("cannot read " + what);
  }

 private:
  std::string path_;
  std::ifstream in_;
  long line_ = 0;
};

void read_format(MshLines& f) {
  auto s = f.next("the format line");
  double version = 0;
  int binary = 0, size = 0;
  f.read(s, "the version, file type and data size", version, binary, size);
  if (version < 4.0 || version >= 5.0)
    f.fail("MSH version " + std::to_string(version) + "; amphora reads 4.1 (Gmsh -format msh41)");
  if (binary != 0) f.fail("binary MSH; save the mesh as ASCII (Gmsh -bin 0)");
}

/// The section's block count (its first line: blocks, entries, min tag, max tag).
long read_block_count(MshLines& f, const std::string& section) {
  auto s = f.next("the " + section + " counts");
  long blocks = 0, n = 0, lo = 0, hi = 0;
  f.read(s, "the " + section + " section's counts", blocks, n, lo, hi);
  return blocks;
}

/// A block header: entity dimension, entity tag, a kind (parametric flag or element type),
/// entry count; returns {kind, count}.
std::pair<int, long> read_block_header(MshLines& f, const std::string& section) {
  auto h = f.next("a block header of the " + section + "s");
  int dim = 0, tag = 0, kind = 0;
  long count = 0;
  f.read(h, "a block header of the " + section + "s", dim, tag, kind, count);
  return {kind, count};
}

void read_nodes(MshLines& f, TetMesh& m, std::unordered_map<long, int>& index) {
  const long blocks = read_block_count(f, "node");
  for (long b = 0; b < blocks; ++b) {
    const long count = read_block_header(f, "node").second;
    std::vector<long> tags(count);
    for (long i = 0; i < count; ++i) {
      auto t = f.next("a node tag");
      f.read(t, "a node tag", tags[i]);
    }
    for (long i = 0; i < count; ++i) {
      auto x = f.next("node coordinates");
      std::array<double, 3> p{};
      f.read(x, "node coordinates", p[0], p[1], p[2]);  // parametric extras ignored
      index[tags[i]] = m.n_nodes();
      m.nodes.push_back(p);
    }
  }
}

void read_elements(MshLines& f, TetMesh& m, const std::unordered_map<long, int>& index) {
  const long blocks = read_block_count(f, "element");
  for (long b = 0; b < blocks; ++b) {
    const auto [type, count] = read_block_header(f, "element");
    for (long i = 0; i < count; ++i) {
      auto e = f.next("an element");
      if (type != 4) continue;  // only linear tetrahedra
      long id = 0, nodes[4];
      f.read(e, "a tetrahedron's tag and four nodes", id, nodes[0], nodes[1], nodes[2], nodes[3]);
      std::array<int, 4> t;
      for (int c = 0; c < 4; ++c) {
        const auto it = index.find(nodes[c]);
        if (it == index.end())
          f.fail("element " + std::to_string(id) + " names node " + std::to_string(nodes[c]) +
                 ", which the $Nodes section lacks");
        t[c] = it->second;
      }
      m.tets.push_back(t);
    }
  }
}

}  // namespace

TetMesh read_gmsh(const std::string& path) {
  MshLines f(path);
  TetMesh m;
  std::unordered_map<long, int> index;
  bool format = false, nodes = false;
  std::string line;
  while (f.next_line(line)) {
    if (line == "$MeshFormat") {
      read_format(f), format = true;
    } else if (line == "$Nodes") {
      if (!format) f.fail("$Nodes before $MeshFormat: not an MSH file");
      read_nodes(f, m, index), nodes = true;
    } else if (line == "$Elements") {
      if (!nodes) f.fail("$Elements before $Nodes");
      read_elements(f, m, index);
    } else if (!format && !line.empty()) {
      f.fail("not an MSH file (the first section must be $MeshFormat)");
    }
  }
  if (m.tets.empty()) f.fail("no linear tetrahedra (element type 4) in the file");
  return m;
}

}  // namespace amphora::mesh::tet
