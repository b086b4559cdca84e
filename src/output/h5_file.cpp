#include "pcsim/output/h5_file.hpp"

#include <cerrno>
#include <exception>

#include "h5_series.hpp"
#include "pcsim/core/error.hpp"

namespace pcsim::output {

H5File::H5File(const std::string& path, Mode mode)
    : path_(path), exceptions_(std::uncaught_exceptions()) {
  errno = 0;
  if (mode == Mode::append) {
    file_ = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    if (file_ < 0) throw SolverError("cannot open HDF5 file " + path);
    return;
  }
  file_ = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  if (file_ < 0) fail_write();
  fd_ = output::h5::descriptor(file_);
}

H5File::~H5File() noexcept(false) {
  if (file_ < 0) return;
  errno = 0;
  const herr_t status = H5Fclose(file_);
  // Not while an exception unwinds: that one is reported.
  if (status < 0 && std::uncaught_exceptions() == exceptions_) fail_write();
  file_ = -1;
}

void H5File::close() {
  if (file_ < 0) return;
  errno = 0;
  if (H5Fclose(file_) < 0) fail_write();
  file_ = -1;
}

void H5File::fail_write() {
  const std::string reason = write_failure_reason(path_, errno, "HDF5 could not write it");
  if (file_ >= 0) output::h5::discard_close(file_, fd_);
  file_ = -1;
  throw OutputError(path_, reason);
}

void H5File::check(bool ok) {
  if (!ok) fail_write();
}

void H5File::ensure_parent_groups(const std::string& path) {
  std::size_t pos = 1;
  while ((pos = path.find('/', pos)) != std::string::npos) {
    std::string group = path.substr(0, pos);
    if (H5Lexists(file_, group.c_str(), H5P_DEFAULT) <= 0) {
      hid_t g = H5Gcreate2(file_, group.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
      check(g >= 0);
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

// False if the dataset could not be created or written.
static bool write_any(hid_t file, const std::string& path, const void* data, hid_t type,
                      std::size_t rows, std::size_t cols) {
  hsize_t dims[2] = {rows, cols};
  int rank = cols == 1 ? 1 : 2;
  hid_t space = H5Screate_simple(rank, dims, nullptr);
  hid_t set = H5Dcreate2(file, path.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  bool ok = set >= 0;
  if (ok && rows * cols > 0) ok = H5Dwrite(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) >= 0;
  if (set >= 0) ok = H5Dclose(set) >= 0 && ok;
  H5Sclose(space);
  return ok;
}

void H5File::write(const std::string& path, const std::vector<double>& data, std::size_t rows,
                   std::size_t cols) {
  ensure_parent_groups(path);
  check(write_any(file_, path, data.data(), H5T_NATIVE_DOUBLE, rows, cols));
}

void H5File::write(const std::string& path, const std::vector<float>& data, std::size_t rows,
                   std::size_t cols) {
  ensure_parent_groups(path);
  check(write_any(file_, path, data.data(), H5T_NATIVE_FLOAT, rows, cols));
}

void H5File::write_int(const std::string& path, const std::vector<long>& data, std::size_t rows,
                       std::size_t cols) {
  ensure_parent_groups(path);
  check(write_any(file_, path, data.data(), H5T_NATIVE_LONG, rows, cols));
}

void H5File::write_strings(const std::string& path, const std::vector<std::string>& data) {
  ensure_parent_groups(path);
  std::vector<const char*> ptrs;
  for (const auto& s : data) ptrs.push_back(s.c_str());
  hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, H5T_VARIABLE);
  const bool ok = write_any(file_, path, ptrs.data(), type, data.size(), 1);
  H5Tclose(type);
  check(ok);
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
  const bool ok = attr >= 0 && H5Awrite(attr, H5T_NATIVE_DOUBLE, &value) >= 0;
  if (attr >= 0) H5Aclose(attr);
  H5Sclose(space);
  check(ok);
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
  const bool ok = attr >= 0 && H5Awrite(attr, type, ptrs.data()) >= 0;
  if (attr >= 0) H5Aclose(attr);
  H5Sclose(space);
  H5Tclose(type);
  check(ok);
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
  const char* text = value.c_str();
  const bool ok = attr >= 0 && H5Awrite(attr, type, &text) >= 0;
  if (attr >= 0) H5Aclose(attr);
  H5Sclose(space);
  H5Tclose(type);
  check(ok);
}

}  // namespace pcsim::output
