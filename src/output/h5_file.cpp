#include "pcsim/output/h5_file.hpp"

#include "pcsim/core/error.hpp"

namespace pcsim {

H5File::H5File(const std::string& path, Mode mode) {
  if (mode == Mode::append) {
    file_ = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    if (file_ < 0) throw SolverError("cannot open HDF5 file " + path);
    return;
  }
  file_ = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  if (file_ < 0) throw SolverError("cannot create HDF5 file " + path);
}

H5File::~H5File() {
  if (file_ >= 0) H5Fclose(file_);
}

void H5File::ensure_parent_groups(const std::string& path) {
  std::size_t pos = 1;
  while ((pos = path.find('/', pos)) != std::string::npos) {
    std::string group = path.substr(0, pos);
    if (H5Lexists(file_, group.c_str(), H5P_DEFAULT) <= 0) {
      hid_t g = H5Gcreate2(file_, group.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
      if (g < 0) throw SolverError("cannot create HDF5 group " + group);
      H5Gclose(g);
    }
    ++pos;
  }
}

// An attribute is written anew: an earlier one of the same name is removed.
static void drop_attribute(hid_t file, const std::string& object_path, const std::string& name) {
  if (H5Aexists_by_name(file, object_path.c_str(), name.c_str(), H5P_DEFAULT) > 0)
    H5Adelete_by_name(file, object_path.c_str(), name.c_str(), H5P_DEFAULT);
}

static void write_any(hid_t file, const std::string& path, const void* data, hid_t type,
                      std::size_t rows, std::size_t cols) {
  hsize_t dims[2] = {rows, cols};
  int rank = cols == 1 ? 1 : 2;
  hid_t space = H5Screate_simple(rank, dims, nullptr);
  hid_t set = H5Dcreate2(file, path.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  if (set < 0) {
    H5Sclose(space);
    throw SolverError("cannot create HDF5 dataset " + path);
  }
  if (rows * cols > 0) H5Dwrite(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data);
  H5Dclose(set);
  H5Sclose(space);
}

void H5File::write(const std::string& path, const std::vector<double>& data, std::size_t rows,
                   std::size_t cols) {
  ensure_parent_groups(path);
  write_any(file_, path, data.data(), H5T_NATIVE_DOUBLE, rows, cols);
}

void H5File::write_int(const std::string& path, const std::vector<long>& data, std::size_t rows,
                       std::size_t cols) {
  ensure_parent_groups(path);
  write_any(file_, path, data.data(), H5T_NATIVE_LONG, rows, cols);
}

void H5File::write_strings(const std::string& path, const std::vector<std::string>& data) {
  ensure_parent_groups(path);
  std::vector<const char*> ptrs;
  for (const auto& s : data) ptrs.push_back(s.c_str());
  hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, H5T_VARIABLE);
  write_any(file_, path, ptrs.data(), type, data.size(), 1);
  H5Tclose(type);
}

void H5File::write(const std::string& path, const std::vector<double>& data, std::size_t rows,
                   std::size_t cols, const DatasetInfo& info) {
  write(path, data, rows, cols);
  describe(path, info);
}

void H5File::write_int(const std::string& path, const std::vector<long>& data, std::size_t rows,
                       std::size_t cols, const DatasetInfo& info) {
  write_int(path, data, rows, cols);
  describe(path, info);
}

void H5File::write_strings(const std::string& path, const std::vector<std::string>& data,
                           const DatasetInfo& info) {
  write_strings(path, data);
  describe(path, info);
}

void H5File::describe(const std::string& path, const DatasetInfo& info) {
  attribute(path, "unit", info.unit);
  attribute(path, "description", info.description);
  if (!info.labels.empty()) attribute(path, "labels", info.labels);
}

void H5File::attribute(const std::string& object_path, const std::string& name, double value) {
  drop_attribute(file_, object_path, name);
  hid_t space = H5Screate(H5S_SCALAR);
  hid_t attr = H5Acreate_by_name(file_, object_path.c_str(), name.c_str(), H5T_NATIVE_DOUBLE, space,
                                 H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(attr, H5T_NATIVE_DOUBLE, &value);
  H5Aclose(attr);
  H5Sclose(space);
}

void H5File::attribute(const std::string& object_path, const std::string& name,
                       const std::vector<std::string>& values) {
  std::vector<const char*> ptrs;
  for (const auto& v : values) ptrs.push_back(v.c_str());
  hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, H5T_VARIABLE);
  H5Tset_cset(type, H5T_CSET_UTF8);
  drop_attribute(file_, object_path, name);
  hsize_t dims[1] = {values.size()};
  hid_t space = H5Screate_simple(1, dims, nullptr);
  hid_t attr = H5Acreate_by_name(file_, object_path.c_str(), name.c_str(), type, space, H5P_DEFAULT,
                                 H5P_DEFAULT, H5P_DEFAULT);
  if (attr < 0) throw SolverError("cannot create HDF5 attribute " + object_path + ":" + name);
  H5Awrite(attr, type, ptrs.data());
  H5Aclose(attr);
  H5Sclose(space);
  H5Tclose(type);
}

void H5File::attribute(const std::string& object_path, const std::string& name,
                       const std::string& value) {
  // Variable-length UTF-8, as h5py writes strings (read back as str, not bytes).
  hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, H5T_VARIABLE);
  H5Tset_cset(type, H5T_CSET_UTF8);
  drop_attribute(file_, object_path, name);
  hid_t space = H5Screate(H5S_SCALAR);
  hid_t attr = H5Acreate_by_name(file_, object_path.c_str(), name.c_str(), type, space, H5P_DEFAULT,
                                 H5P_DEFAULT, H5P_DEFAULT);
  if (attr < 0) throw SolverError("cannot create HDF5 attribute " + object_path + ":" + name);
  const char* text = value.c_str();
  H5Awrite(attr, type, &text);
  H5Aclose(attr);
  H5Sclose(space);
  H5Tclose(type);
}

}  // namespace pcsim
