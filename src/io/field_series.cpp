#include "io/field_series.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>
#include <sstream>
#include <stdexcept>

#include "io/hdf5_file.hpp"

namespace amphora::io {

void write_file_atomically(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out << text;
    out.flush();
    if (!out) throw std::runtime_error("cannot write '" + tmp + "'");
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0)
    throw std::runtime_error("cannot rename '" + tmp + "' to '" + path + "'");
}

FieldSeries::FieldSeries(std::string dir, std::string scene_name, Communicator comm)
    : dir_(std::move(dir)), name_(std::move(scene_name)), comm_(comm) {}

std::string FieldSeries::series_path() const { return dir_ + "/" + name_ + ".xmf"; }

std::string FieldSeries::write(long long step, double time,
                               const std::vector<OutputBlock>& local_blocks) {
  std::ostringstream fname;
  fname << "fields_" << std::setw(6) << std::setfill('0') << step << ".h5";
  const std::string file = fname.str();

  std::vector<H5Group> groups;
  for (const auto& b : local_blocks) {
    H5Group g{b.name, {{"x", b.x}, {"y", b.y}, {"z", b.z}}};
    if (b.points) g.datasets.push_back({"topology_points", {1.0}});  // marks a point set
    if (!b.tets.empty()) g.datasets.push_back({"topology_tets", b.tets});
    if (b.curvilinear)  // marks a curvilinear grid and gives its node counts
      g.datasets.push_back(
          {"topology_nodes", {double(b.nodes[0]), double(b.nodes[1]), double(b.nodes[2])}});
    for (const auto& f : b.fields) g.datasets.push_back(f);
    groups.push_back(std::move(g));
  }
  H5Metadata meta;
  meta.reals["time"] = time;
  meta.integers["step"] = step;
  const auto layout = write_h5(dir_ + "/" + file, comm_, groups, meta);

  // Node counts of curvilinear blocks (gathered: a block is written by one rank).
  std::map<std::string, std::vector<long>> curvilinear_nodes;
  {
    std::vector<double> mine;
    std::string names;
    for (const auto& b : local_blocks)
      if (b.curvilinear) {
        names += b.name + '\n';
        for (long n : b.nodes) mine.push_back(static_cast<double>(n));
      }
    const auto all_nodes = comm_.allgatherv(mine);
    std::vector<char> name_chars(names.begin(), names.end());
    const auto all_names = comm_.allgatherv(name_chars);
    std::string joined(all_names.begin(), all_names.end());
    std::size_t pos = 0, i = 0;
    while (pos < joined.size()) {
      const std::size_t end = joined.find('\n', pos);
      curvilinear_nodes[joined.substr(pos, end - pos)] = {static_cast<long>(all_nodes[3 * i]),
                                                          static_cast<long>(all_nodes[3 * i + 1]),
                                                          static_cast<long>(all_nodes[3 * i + 2])};
      pos = end + 1;
      ++i;
    }
  }
  // XDMF for this step: blocks in first-seen order, each with its coordinates' sizes.
  std::vector<std::string> order;
  std::map<std::string, std::map<std::string, unsigned long long>> sizes;
  for (const auto& d : layout) {
    if (!sizes.count(d.group)) order.push_back(d.group);
    sizes[d.group][d.name] = d.size;
  }
  std::ostringstream x;
  x << std::setprecision(17);
  x << "    <Grid Name=\"step_" << step << "\" GridType=\"Collection\" "
    << "CollectionType=\"Spatial\">\n      <Time Value=\"" << time << "\"/>\n";
  for (const auto& g : order) {
    const auto& s = sizes[g];
    const bool points = s.count("topology_points") != 0;
    const bool tets = s.count("topology_tets") != 0;
    const unsigned long long n_tets = tets ? s.at("topology_tets") / 4 : 0;
    const bool curvilinear = s.count("topology_nodes") != 0;
    std::string dims = points || tets
                           ? std::to_string(s.at("x"))
                           : std::to_string(s.at("z")) + " " + std::to_string(s.at("y")) + " " +
                                 std::to_string(s.at("x"));
    if (curvilinear) {
      const auto& nodes = curvilinear_nodes.at(g);
      dims = std::to_string(nodes[2]) + " " + std::to_string(nodes[1]) + " " +
             std::to_string(nodes[0]);
    }
    x << "      <Grid Name=\"" << g << "\" GridType=\"Uniform\">\n";
    if (points) {
      x << "        <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" << s.at("x")
        << "\" NodesPerElement=\"1\"/>\n"
        << "        <Geometry GeometryType=\"X_Y_Z\">\n";
    } else if (tets) {
      x << "        <Topology TopologyType=\"Tetrahedron\" NumberOfElements=\"" << n_tets
        << "\">\n          <DataItem Dimensions=\"" << n_tets
        << " 4\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" << file << ":/" << g
        << "/topology_tets</DataItem>\n        </Topology>\n"
        << "        <Geometry GeometryType=\"X_Y_Z\">\n";
    } else if (curvilinear) {
      x << "        <Topology TopologyType=\"3DSMesh\" Dimensions=\"" << dims << "\"/>\n"
        << "        <Geometry GeometryType=\"X_Y_Z\">\n";
    } else {
      x << "        <Topology TopologyType=\"3DRectMesh\" Dimensions=\"" << dims << "\"/>\n"
        << "        <Geometry GeometryType=\"VXVYVZ\">\n";
    }
    for (const char* c : {"x", "y", "z"}) {
      x << "          <DataItem Dimensions=\"" << s.at(c)
        << "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" << file << ":/" << g << "/"
        << c << "</DataItem>\n";
    }
    x << "        </Geometry>\n";
    for (const auto& d : layout) {
      if (d.group != g || d.name == "x" || d.name == "y" || d.name == "z" ||
          d.name == "topology_points" || d.name == "topology_nodes" || d.name == "topology_tets")
        continue;
      const bool cell = tets && d.size == n_tets && d.size != s.at("x");
      x << "        <Attribute Name=\"" << d.name << "\" AttributeType=\"Scalar\" "
        << "Center=\"" << (cell ? "Cell" : "Node") << "\">\n          <DataItem Dimensions=\""
        << (cell ? std::to_string(n_tets) : dims)
        << "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" << file << ":/" << g << "/"
        << d.name << "</DataItem>\n        </Attribute>\n";
    }
    x << "      </Grid>\n";
  }
  x << "    </Grid>\n";
  entries_.push_back(x.str());
  last_file_ = file;
  last_step_ = step;
  if (comm_.is_root()) write_xdmf();
  comm_.barrier();
  return last_file();
}

void FieldSeries::write_xdmf() const {
  std::ostringstream x;
  x << "<?xml version=\"1.0\" ?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
    << "<Xdmf Version=\"3.0\">\n  <Domain>\n"
    << "   <Grid Name=\"" << name_ << "\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (const auto& e : entries_) x << e;
  x << "   </Grid>\n  </Domain>\n</Xdmf>\n";
  write_file_atomically(series_path(), x.str());
}

std::string FieldSeries::save() const {
  std::string s = std::to_string(last_step_) + "\x1e" + last_file_;
  for (const auto& e : entries_) s += "\x1e" + e;
  return s;
}

void FieldSeries::load(const std::string& saved) {
  entries_.clear();
  std::vector<std::string> parts;
  size_t start = 0;
  while (true) {
    const size_t end = saved.find('\x1e', start);
    parts.push_back(saved.substr(start, end == std::string::npos ? end : end - start));
    if (end == std::string::npos) break;
    start = end + 1;
  }
  if (parts.size() < 2) throw std::runtime_error("checkpoint: malformed output series state");
  last_step_ = std::stoll(parts[0]);
  last_file_ = parts[1];
  entries_.assign(parts.begin() + 2, parts.end());
}

}  // namespace amphora::io
