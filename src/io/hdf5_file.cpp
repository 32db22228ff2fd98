#include "io/hdf5_file.hpp"

#include <hdf5.h>

#include <algorithm>
#include <sstream>
#include <stdexcept>

namespace amphora::io {

namespace {

void check(herr_t status, const std::string& what) {
  if (status < 0) throw std::runtime_error("HDF5: " + what + " failed");
}
hid_t check_id(hid_t id, const std::string& what) {
  if (id < 0) throw std::runtime_error("HDF5: " + what + " failed");
  return id;
}

/// Every rank's (group, dataset, size), in rank order, on every rank.
std::vector<H5DatasetInfo> gather_layout(const Communicator& comm,
                                         const std::vector<H5Group>& local) {
  std::ostringstream s;
  for (const auto& g : local)
    for (const auto& [name, data] : g.datasets)
      s << g.name << '\t' << name << '\t' << data.size() << '\n';
  const std::string mine = s.str();
  const std::vector<char> all = comm.allgatherv(std::vector<char>(mine.begin(), mine.end()));
  // Records are whole lines, so the concatenation parses in rank order; the owner of each
  // line is recovered from every rank's line count.
  std::vector<int> lines_per_rank = comm.allgatherv(
      std::vector<int>{static_cast<int>(std::count(mine.begin(), mine.end(), '\n'))});
  std::vector<H5DatasetInfo> out;
  std::istringstream in(std::string(all.begin(), all.end()));
  std::string line;
  int rank = 0, seen = 0;
  while (std::getline(in, line)) {
    while (rank < comm.size() && seen == lines_per_rank[rank]) {
      ++rank;
      seen = 0;
    }
    std::istringstream f(line);
    H5DatasetInfo d;
    std::getline(f, d.group, '\t');
    std::getline(f, d.name, '\t');
    f >> d.size;
    d.owner = rank;
    out.push_back(d);
    ++seen;
  }
  return out;
}

hid_t mpio_fapl(const Communicator& comm) {
  // amphora reports HDF5 failures itself, with the file name; HDF5's own stack dump is noise.
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  hid_t fapl = check_id(H5Pcreate(H5P_FILE_ACCESS), "H5Pcreate");
  check(H5Pset_fapl_mpio(fapl, comm.get(), MPI_INFO_NULL), "H5Pset_fapl_mpio");
  return fapl;
}

}  // namespace

std::vector<H5DatasetInfo> write_h5(const std::string& path, const Communicator& comm,
                                    const std::vector<H5Group>& local_groups,
                                    const H5Metadata& meta) {
  const auto layout = gather_layout(comm, local_groups);
  hid_t fapl = mpio_fapl(comm);
  hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl);
  H5Pclose(fapl);
  // Every rank must agree before any rank goes on, or the collective calls below would hang.
  if (comm.any(file < 0)) {
    if (file >= 0) H5Fclose(file);
    throw std::runtime_error("cannot create HDF5 file '" + path + "'");
  }
  hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
  H5Pset_obj_track_times(dcpl, 0);
  hid_t gcpl = H5Pcreate(H5P_GROUP_CREATE);
  H5Pset_obj_track_times(gcpl, 0);

  hid_t scalar = H5Screate(H5S_SCALAR);
  for (const auto& [name, v] : meta.reals) {
    hid_t a = check_id(
        H5Acreate2(file, name.c_str(), H5T_NATIVE_DOUBLE, scalar, H5P_DEFAULT, H5P_DEFAULT),
        "attribute " + name);
    check(H5Awrite(a, H5T_NATIVE_DOUBLE, &v), "write attribute " + name);
    H5Aclose(a);
  }
  for (const auto& [name, v] : meta.integers) {
    hid_t a =
        check_id(H5Acreate2(file, name.c_str(), H5T_NATIVE_LLONG, scalar, H5P_DEFAULT, H5P_DEFAULT),
                 "attribute " + name);
    check(H5Awrite(a, H5T_NATIVE_LLONG, &v), "write attribute " + name);
    H5Aclose(a);
  }
  H5Sclose(scalar);

  // Text entries as 1D char datasets (no attribute size limit); written by rank 0.
  std::vector<std::pair<hid_t, const std::string*>> texts;
  for (const auto& [name, v] : meta.texts) {
    hsize_t n = std::max<hsize_t>(1, v.size());
    hid_t space = H5Screate_simple(1, &n, nullptr);
    hid_t d = check_id(
        H5Dcreate2(file, name.c_str(), H5T_NATIVE_CHAR, space, H5P_DEFAULT, dcpl, H5P_DEFAULT),
        "text " + name);
    H5Sclose(space);
    texts.emplace_back(d, &v);
  }

  std::map<std::string, hid_t> groups;
  std::vector<std::pair<hid_t, const H5DatasetInfo*>> datasets;
  for (const auto& d : layout) {
    if (!groups.count(d.group)) {
      groups[d.group] = check_id(H5Gcreate2(file, d.group.c_str(), H5P_DEFAULT, gcpl, H5P_DEFAULT),
                                 "group " + d.group);
    }
    hsize_t n = d.size;
    hid_t space = H5Screate_simple(1, &n, nullptr);
    hid_t id = check_id(H5Dcreate2(groups[d.group], d.name.c_str(), H5T_NATIVE_DOUBLE, space,
                                   H5P_DEFAULT, dcpl, H5P_DEFAULT),
                        "dataset " + d.group + "/" + d.name);
    H5Sclose(space);
    datasets.emplace_back(id, &d);
  }

  bool ok = true;
  if (comm.is_root()) {
    for (auto& [id, text] : texts)
      if (!text->empty())
        ok = ok && H5Dwrite(id, H5T_NATIVE_CHAR, H5S_ALL, H5S_ALL, H5P_DEFAULT, text->data()) >= 0;
  }
  for (auto& [id, d] : datasets) {
    if (d->owner != comm.rank()) continue;
    for (const auto& g : local_groups) {
      if (g.name != d->group) continue;
      for (const auto& [name, data] : g.datasets) {
        if (name == d->name && !data.empty()) {
          ok = ok &&
               H5Dwrite(id, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()) >= 0;
        }
      }
    }
  }
  for (auto& [id, t] : texts) H5Dclose(id);
  for (auto& [id, d] : datasets) H5Dclose(id);
  for (auto& [name, id] : groups) H5Gclose(id);
  H5Pclose(dcpl);
  H5Pclose(gcpl);
  const bool closed = H5Fclose(file) >= 0;
  if (comm.any(!ok || !closed)) throw std::runtime_error("writing HDF5 file '" + path + "' failed");
  return layout;
}

H5Reader::H5Reader(const std::string& path, const Communicator& comm) : path_(path) {
  hid_t fapl = mpio_fapl(comm);
  hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, fapl);
  H5Pclose(fapl);
  if (comm.any(file < 0)) {
    if (file >= 0) H5Fclose(file);
    throw std::runtime_error("cannot open HDF5 file '" + path + "'");
  }
  file_ = file;
}

H5Reader::~H5Reader() {
  if (file_ >= 0) H5Fclose(static_cast<hid_t>(file_));
}

bool H5Reader::has(const std::string& name) const {
  const hid_t f = static_cast<hid_t>(file_);
  return H5Aexists(f, name.c_str()) > 0 || H5Lexists(f, name.c_str(), H5P_DEFAULT) > 0;
}

double H5Reader::real(const std::string& name) const {
  double v = 0;
  hid_t a = check_id(H5Aopen(static_cast<hid_t>(file_), name.c_str(), H5P_DEFAULT),
                     path_ + ": attribute " + name);
  check(H5Aread(a, H5T_NATIVE_DOUBLE, &v), "read attribute " + name);
  H5Aclose(a);
  return v;
}

long long H5Reader::integer(const std::string& name) const {
  long long v = 0;
  hid_t a = check_id(H5Aopen(static_cast<hid_t>(file_), name.c_str(), H5P_DEFAULT),
                     path_ + ": attribute " + name);
  check(H5Aread(a, H5T_NATIVE_LLONG, &v), "read attribute " + name);
  H5Aclose(a);
  return v;
}

std::string H5Reader::text(const std::string& name) const {
  hid_t d = check_id(H5Dopen2(static_cast<hid_t>(file_), name.c_str(), H5P_DEFAULT),
                     path_ + ": text " + name);
  hid_t space = H5Dget_space(d);
  const hssize_t n = H5Sget_simple_extent_npoints(space);
  H5Sclose(space);
  std::string s(static_cast<size_t>(n), '\0');
  check(H5Dread(d, H5T_NATIVE_CHAR, H5S_ALL, H5S_ALL, H5P_DEFAULT, s.data()), "read " + name);
  H5Dclose(d);
  while (!s.empty() && s.back() == '\0') s.pop_back();
  return s;
}

std::vector<NamedArray> H5Reader::group(const std::string& name) const {
  hid_t g = check_id(H5Gopen2(static_cast<hid_t>(file_), name.c_str(), H5P_DEFAULT),
                     path_ + ": group " + name);
  std::vector<std::string> names;
  H5Literate(
      g, H5_INDEX_NAME, H5_ITER_INC, nullptr,
      [](hid_t, const char* n, const H5L_info_t*, void* out) -> herr_t {
        static_cast<std::vector<std::string>*>(out)->push_back(n);
        return 0;
      },
      &names);
  std::vector<NamedArray> out;
  for (const auto& n : names) {
    hid_t d = check_id(H5Dopen2(g, n.c_str(), H5P_DEFAULT), path_ + ": " + name + "/" + n);
    hid_t space = H5Dget_space(d);
    const hssize_t count = H5Sget_simple_extent_npoints(space);
    H5Sclose(space);
    std::vector<double> data(static_cast<size_t>(count));
    check(H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()),
          "read " + name + "/" + n);
    H5Dclose(d);
    out.emplace_back(n, std::move(data));
  }
  H5Gclose(g);
  return out;
}

}  // namespace amphora::io
