// Minimal serial HDF5 writer (used on one rank after gathering results).
// Datasets are double or int arrays with up to 2 dimensions; groups are
// created on demand from '/'-separated paths.
#pragma once

#include <hdf5.h>

#include <string>
#include <vector>

namespace pcsim {

class H5File {
 public:
  explicit H5File(const std::string& path);  // creates (truncates) the file
  ~H5File();
  H5File(const H5File&) = delete;
  H5File& operator=(const H5File&) = delete;

  // rows x cols row-major (cols = 1 for a vector).
  void write(const std::string& path, const std::vector<double>& data, std::size_t rows,
             std::size_t cols = 1);
  void write(const std::string& path, const std::vector<double>& data) {
    write(path, data, data.size(), 1);
  }
  void write_int(const std::string& path, const std::vector<long>& data, std::size_t rows,
                 std::size_t cols = 1);
  void write_int(const std::string& path, const std::vector<long>& data) {
    write_int(path, data, data.size(), 1);
  }
  void write_strings(const std::string& path, const std::vector<std::string>& data);
  void attribute(const std::string& object_path, const std::string& name, double value);
  void attribute(const std::string& object_path, const std::string& name, const std::string& value);

 private:
  void ensure_parent_groups(const std::string& path);
  hid_t file_ = -1;
};

}  // namespace pcsim
