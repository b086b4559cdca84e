#include "pcsim/output/checkpoint.hpp"

#include <hdf5.h>

#include <cerrno>
#include <cstdio>

#include "h5_series.hpp"
#include "pcsim/core/error.hpp"

namespace pcsim::output {

namespace {

constexpr const char* kFormatAttribute = "pcsim_checkpoint";
constexpr double kFormatVersion = 1;

constexpr const char* kArraysAttribute = "pcsim_arrays";  // their names, one a line

struct Visit {
  hid_t file;
  CheckpointData* data;
};

herr_t collect_attribute(hid_t, const char* name, const H5A_info_t*, void* ptr) {
  auto* v = static_cast<Visit*>(ptr);
  hid_t attr = H5Aopen_by_name(v->file, "/", name, H5P_DEFAULT, H5P_DEFAULT);
  hid_t type = H5Aget_type(attr);
  const bool text = H5Tget_class(type) == H5T_STRING;
  H5Tclose(type);
  H5Aclose(attr);
  if (text)
    v->data->texts[name] = h5::text_attribute(v->file, "/", name);
  else
    v->data->numbers[name] = h5::number_attribute(v->file, "/", name);
  return 0;
}

}  // namespace

void write_checkpoint(const std::string& path, const CheckpointData& data) {
  const std::string tmp = path + ".tmp";
  errno = 0;
  hid_t file = H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  if (file < 0)
    throw OutputError(tmp, write_failure_reason(tmp, errno, "HDF5 could not create it"));
  const int fd = h5::descriptor(file);
  try {
    std::string names;
    for (const auto& [name, values] : data.arrays) {
      h5::write(file, name, values, {values.size()}, "", "");
      names += name + "\n";
    }
    h5::set_attribute(file, "/", kArraysAttribute, names);
    for (const auto& [name, value] : data.numbers) h5::set_attribute(file, "/", name, value);
    for (const auto& [name, value] : data.texts) h5::set_attribute(file, "/", name, value);
    h5::set_attribute(file, "/", kFormatAttribute, kFormatVersion);
  } catch (const std::exception& e) {
    const int saved = errno;
    h5::discard_close(file, fd);
    std::remove(tmp.c_str());
    throw OutputError(tmp, write_failure_reason(tmp, saved, e.what()));
  }
  errno = 0;
  if (H5Fclose(file) < 0 || std::rename(tmp.c_str(), path.c_str()) != 0) {
    const int saved = errno;
    h5::discard_close(file, fd);
    std::remove(tmp.c_str());
    throw OutputError(path, write_failure_reason(path, saved, "HDF5 could not close it"));
  }
}

CheckpointData read_checkpoint(const std::string& path) {
  hid_t file;
  H5E_BEGIN_TRY {
    file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  }
  H5E_END_TRY;
  if (file < 0) throw SolverError(path + " is not an HDF5 file");
  CheckpointData data;
  Visit visit{file, &data};
  try {
    if (H5Aexists(file, kFormatAttribute) <= 0)
      throw SolverError(path + " is not a pcsim checkpoint");
    if (h5::number_attribute(file, "/", kFormatAttribute) != kFormatVersion)
      throw SolverError(path + " is a checkpoint of another pcsim version");
    if (H5Aiterate2(file, H5_INDEX_NAME, H5_ITER_INC, nullptr, collect_attribute, &visit) < 0)
      throw SolverError("cannot read the checkpoint " + path);
    const std::string names = data.texts[kArraysAttribute];
    for (std::size_t begin = 0, end; (end = names.find('\n', begin)) != std::string::npos;
         begin = end + 1) {
      const std::string name = names.substr(begin, end - begin);
      data.arrays[name] = h5::read(file, name);
    }
  } catch (...) {
    H5Fclose(file);
    throw;
  }
  H5Fclose(file);
  data.numbers.erase(kFormatAttribute);
  data.texts.erase(kArraysAttribute);
  return data;
}

}  // namespace pcsim::output
