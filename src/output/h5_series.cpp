#include "h5_series.hpp"

#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>

#include "pcsim/core/error.hpp"

namespace pcsim::output::h5 {

namespace {

[[noreturn]] void fail(const std::string& what, const std::string& path) {
  throw SolverError("cannot " + what + " " + path);
}

hid_t link_properties() {
  hid_t lcpl = H5Pcreate(H5P_LINK_CREATE);
  H5Pset_create_intermediate_group(lcpl, 1);
  return lcpl;
}

// A small chunk cache per series (HDF5's default is 1 MiB each): rows are
// appended, so only the last chunk or two are ever written again.
hid_t access_properties() {
  hid_t dapl = H5Pcreate(H5P_DATASET_ACCESS);
  H5Pset_chunk_cache(dapl, 521, 256 * 1024, 1.0);
  return dapl;
}

// Rows per chunk: about 64 KiB per chunk, at least one row.
hsize_t chunk_rows(std::size_t row_size) {
  return std::max<hsize_t>(1, 8192 / std::max<std::size_t>(1, row_size));
}

void replace_attribute(hid_t object, const std::string& name, hid_t type, const void* value) {
  if (H5Aexists(object, name.c_str()) > 0) H5Adelete(object, name.c_str());
  hid_t space = H5Screate(H5S_SCALAR);
  hid_t attr = H5Acreate2(object, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT);
  const bool ok = attr >= 0 && H5Awrite(attr, type, value) >= 0;
  if (attr >= 0) H5Aclose(attr);
  H5Sclose(space);
  if (!ok) fail("write the attribute", name);
}

hid_t open_object(hid_t file, const std::string& object) {
  hid_t o = H5Oopen(file, object.c_str(), H5P_DEFAULT);
  if (o < 0) fail("open", object);
  return o;
}

void describe(hid_t set, const std::string& unit, const std::string& description) {
  const std::pair<const char*, const std::string*> texts[] = {{"unit", &unit},
                                                              {"description", &description}};
  for (const auto& [name, text] : texts) {
    if (text->empty()) continue;
    hid_t type = H5Tcopy(H5T_C_S1);
    H5Tset_size(type, text->size() + 1);
    replace_attribute(set, name, type, text->c_str());
    H5Tclose(type);
  }
}

}  // namespace

Series::Series(hid_t file, const std::string& path, std::vector<hsize_t> row_shape,
               const std::string& unit, const std::string& description) {
  std::vector<hsize_t> dims = {0}, max_dims = {H5S_UNLIMITED};
  for (hsize_t d : row_shape) {
    dims.push_back(d);
    max_dims.push_back(d);
    row_size_ *= d;
  }
  rank_ = static_cast<int>(dims.size());
  std::vector<hsize_t> chunk = dims;
  chunk[0] = chunk_rows(row_size_);
  hid_t space = H5Screate_simple(rank_, dims.data(), max_dims.data());
  hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
  H5Pset_chunk(dcpl, rank_, chunk.data());
  hid_t lcpl = link_properties();
  hid_t dapl = access_properties();
  H5E_BEGIN_TRY {
    set_ = H5Dcreate2(file, path.c_str(), H5T_NATIVE_DOUBLE, space, lcpl, dcpl, dapl);
  }
  H5E_END_TRY;
  H5Pclose(dapl);
  H5Pclose(lcpl);
  H5Pclose(dcpl);
  H5Sclose(space);
  if (set_ < 0) fail("create HDF5 dataset", path);
  describe(set_, unit, description);
}

Series::Series(hid_t file, const std::string& path) {
  hid_t dapl = access_properties();
  H5E_BEGIN_TRY {
    set_ = H5Dopen2(file, path.c_str(), dapl);
  }
  H5E_END_TRY;
  H5Pclose(dapl);
  if (set_ < 0) fail("open HDF5 dataset", path);
  hid_t space = H5Dget_space(set_);
  rank_ = H5Sget_simple_extent_ndims(space);
  std::vector<hsize_t> dims(static_cast<std::size_t>(std::max(rank_, 1)), 0);
  H5Sget_simple_extent_dims(space, dims.data(), nullptr);
  H5Sclose(space);
  rows_ = dims[0];
  for (int d = 1; d < rank_; ++d) row_size_ *= dims[d];
}

Series::~Series() {
  if (set_ >= 0) H5Dclose(set_);
}

void Series::append(const double* values, std::size_t n) {
  if (n == 0) return;
  std::vector<hsize_t> dims(rank_), start(rank_, 0), count(rank_);
  hid_t space = H5Dget_space(set_);
  H5Sget_simple_extent_dims(space, dims.data(), nullptr);
  H5Sclose(space);
  count = dims;
  count[0] = n;
  start[0] = rows_;
  dims[0] = rows_ + n;
  if (H5Dset_extent(set_, dims.data()) < 0) fail("extend an HDF5 dataset", "");
  space = H5Dget_space(set_);
  H5Sselect_hyperslab(space, H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr);
  hid_t memory = H5Screate_simple(rank_, count.data(), nullptr);
  const herr_t status = H5Dwrite(set_, H5T_NATIVE_DOUBLE, memory, space, H5P_DEFAULT, values);
  H5Sclose(memory);
  H5Sclose(space);
  if (status < 0) fail("write rows of an HDF5 dataset", "");
  rows_ += n;
}

void Series::truncate(std::size_t n) {
  if (n >= rows_) return;
  std::vector<hsize_t> dims(rank_);
  hid_t space = H5Dget_space(set_);
  H5Sget_simple_extent_dims(space, dims.data(), nullptr);
  H5Sclose(space);
  dims[0] = n;
  if (H5Dset_extent(set_, dims.data()) < 0) fail("shorten an HDF5 dataset", "");
  rows_ = n;
}

std::vector<double> read(hid_t file, const std::string& path, std::vector<hsize_t>* dims_out) {
  hid_t set;
  H5E_BEGIN_TRY {
    set = H5Dopen2(file, path.c_str(), H5P_DEFAULT);
  }
  H5E_END_TRY;
  if (set < 0) fail("open HDF5 dataset", path);
  hid_t space = H5Dget_space(set);
  const int rank = H5Sget_simple_extent_ndims(space);
  std::vector<hsize_t> dims(static_cast<std::size_t>(std::max(rank, 0)));
  H5Sget_simple_extent_dims(space, dims.data(), nullptr);
  H5Sclose(space);
  std::size_t n = 1;
  for (hsize_t d : dims) n *= d;
  std::vector<double> values(n);
  const herr_t status =
      n > 0 ? H5Dread(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) : 0;
  H5Dclose(set);
  if (status < 0) fail("read HDF5 dataset", path);
  if (dims_out) *dims_out = dims;
  return values;
}

void write(hid_t file, const std::string& path, const std::vector<double>& values,
           std::vector<hsize_t> dims, const std::string& unit, const std::string& description) {
  hid_t space = H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr);
  hid_t lcpl = link_properties();
  hid_t set =
      H5Dcreate2(file, path.c_str(), H5T_NATIVE_DOUBLE, space, lcpl, H5P_DEFAULT, H5P_DEFAULT);
  H5Pclose(lcpl);
  H5Sclose(space);
  if (set < 0) fail("create HDF5 dataset", path);
  const herr_t status = values.empty() ? 0
                                       : H5Dwrite(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL,
                                                  H5P_DEFAULT, values.data());
  if (status >= 0) describe(set, unit, description);
  H5Dclose(set);
  if (status < 0) fail("write HDF5 dataset", path);
}

bool exists(hid_t file, const std::string& path) {
  // Every parent must exist for H5Lexists; walk down the path.
  std::size_t pos = 0;
  while ((pos = path.find('/', pos + 1)) != std::string::npos)
    if (H5Lexists(file, path.substr(0, pos).c_str(), H5P_DEFAULT) <= 0) return false;
  return H5Lexists(file, path.c_str(), H5P_DEFAULT) > 0;
}

void add_row_view(hid_t file, const std::string& view_path, const std::string& source_path,
                  std::size_t k, const std::string& unit) {
  hid_t source = H5Dopen2(file, source_path.c_str(), H5P_DEFAULT);
  if (source < 0) fail("open the dataset", source_path);
  hid_t source_space = H5Dget_space(source);
  H5Dclose(source);
  const int rank = H5Sget_simple_extent_ndims(source_space);
  std::vector<hsize_t> dims(static_cast<std::size_t>(rank)), start(dims.size(), 0);
  H5Sget_simple_extent_dims(source_space, dims.data(), nullptr);
  start[0] = k;
  std::vector<hsize_t> count = dims;
  count[0] = 1;
  H5Sselect_hyperslab(source_space, H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr);
  hid_t view_space = H5Screate_simple(rank - 1, dims.data() + 1, nullptr);
  hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
  H5Pset_virtual(dcpl, view_space, ".", source_path.c_str(), source_space);
  hid_t lcpl = link_properties();
  hid_t view =
      H5Dcreate2(file, view_path.c_str(), H5T_NATIVE_DOUBLE, view_space, lcpl, dcpl, H5P_DEFAULT);
  H5Pclose(lcpl);
  H5Pclose(dcpl);
  H5Sclose(view_space);
  H5Sclose(source_space);
  if (view < 0) fail("create the view", view_path);
  describe(view, unit, "row " + std::to_string(k) + " of " + source_path + " (a view, for XDMF)");
  H5Dclose(view);
}

void set_attribute(hid_t file, const std::string& object, const std::string& name, double value) {
  hid_t o = open_object(file, object);
  replace_attribute(o, name, H5T_NATIVE_DOUBLE, &value);
  H5Oclose(o);
}

void set_attribute(hid_t file, const std::string& object, const std::string& name,
                   const std::string& value) {
  hid_t o = open_object(file, object);
  hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, value.size() + 1);
  replace_attribute(o, name, type, value.c_str());
  H5Tclose(type);
  H5Oclose(o);
}

double number_attribute(hid_t file, const std::string& object, const std::string& name) {
  double value = 0;
  hid_t attr;
  H5E_BEGIN_TRY {
    attr = H5Aopen_by_name(file, object.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT);
  }
  H5E_END_TRY;
  if (attr < 0) fail("find the attribute", name);
  const herr_t status = H5Aread(attr, H5T_NATIVE_DOUBLE, &value);
  H5Aclose(attr);
  if (status < 0) fail("read the attribute", name);
  return value;
}

std::string text_attribute(hid_t file, const std::string& object, const std::string& name) {
  hid_t attr;
  H5E_BEGIN_TRY {
    attr = H5Aopen_by_name(file, object.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT);
  }
  H5E_END_TRY;
  if (attr < 0) fail("find the attribute", name);
  hid_t type = H5Aget_type(attr);
  std::string value;
  if (H5Tget_class(type) == H5T_STRING && !H5Tis_variable_str(type)) {
    value.resize(H5Tget_size(type));
    if (H5Aread(attr, type, value.data()) < 0) value.clear();
    value.resize(value.find('\0') == std::string::npos ? value.size() : value.find('\0'));
  }
  H5Tclose(type);
  H5Aclose(attr);
  return value;
}

int descriptor(hid_t file) {
  void* handle = nullptr;
  if (H5Fget_vfd_handle(file, H5P_DEFAULT, &handle) < 0 || !handle) return -1;
  return *static_cast<int*>(handle);
}

void discard_writes(hid_t file, int fd) {
  if (fd < 0 && H5Iis_valid(file) > 0) fd = descriptor(file);
  const int memory = memfd_create("pcsim-discarded-writes", MFD_CLOEXEC);
  if (fd >= 0 && memory >= 0) dup2(memory, fd);
  if (memory >= 0) ::close(memory);
}

void discard_close(hid_t file, int fd) {
  if (H5Iis_valid(file) <= 0) return;
  discard_writes(file, fd);
  H5Fclose(file);
}

}  // namespace pcsim::output::h5
