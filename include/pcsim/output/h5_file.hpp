// Minimal serial HDF5 writer (used on one rank after gathering results).
// Datasets are double or int arrays with up to 2 dimensions; groups are
// created on demand from '/'-separated paths. A dataset written with a
// DatasetInfo carries the attributes 'unit', 'description' and, for columns
// of generalised coordinates, 'labels' (one name per column).
#pragma once

#include <hdf5.h>

#include <string>
#include <vector>

namespace pcsim::output {

// What a dataset holds. Units are SI, written as UDUNITS strings ("m", "N",
// "m/s", "rad", "s", "Hz", "kg", "J"); "1" for dimensionless numbers, counts
// and indices, "none" for text.
struct DatasetInfo {
  DatasetInfo(std::string unit_, std::string description_, std::vector<std::string> labels_ = {})
      : unit(std::move(unit_)), description(std::move(description_)), labels(std::move(labels_)) {}
  std::string unit;
  std::string description;
  std::vector<std::string> labels;  // column names (empty: no 'labels' attribute)
};

class H5File {
 public:
  enum class Mode { create, append };
  // create: creates (truncates) the file; append: opens an existing one.
  // A failed write (create, dataset, attribute, close) throws OutputError
  // naming the file and the OS error.
  explicit H5File(const std::string& path, Mode mode = Mode::create);
  // Closes the file; throws OutputError if that fails (unless another
  // exception is on its way): call close() to see the failure earlier.
  ~H5File() noexcept(false);
  void close();
  H5File(const H5File&) = delete;
  H5File& operator=(const H5File&) = delete;

  // rows x cols row-major (cols = 1 for a vector).
  void write(const std::string& path, const std::vector<double>& data, std::size_t rows,
             std::size_t cols = 1);
  void write(const std::string& path, const std::vector<double>& data) {
    write(path, data, data.size(), 1);
  }
  // The same in single precision (a dataset of 32-bit floats).
  void write(const std::string& path, const std::vector<float>& data, std::size_t rows,
             std::size_t cols = 1);
  void write_int(const std::string& path, const std::vector<long>& data, std::size_t rows,
                 std::size_t cols = 1);
  void write_int(const std::string& path, const std::vector<long>& data) {
    write_int(path, data, data.size(), 1);
  }
  void write_strings(const std::string& path, const std::vector<std::string>& data);
  // The same with the dataset's unit, description and labels.
  void write(const std::string& path, const std::vector<double>& data, std::size_t rows,
             std::size_t cols, const DatasetInfo& info);
  void write(const std::string& path, const std::vector<double>& data, const DatasetInfo& info) {
    write(path, data, data.size(), 1, info);
  }
  void write_int(const std::string& path, const std::vector<long>& data, std::size_t rows,
                 std::size_t cols, const DatasetInfo& info);
  void write_int(const std::string& path, const std::vector<long>& data, const DatasetInfo& info) {
    write_int(path, data, data.size(), 1, info);
  }
  void write_strings(const std::string& path, const std::vector<std::string>& data,
                     const DatasetInfo& info);
  // Unit, description and labels of an existing dataset.
  void describe(const std::string& path, const DatasetInfo& info);

  void attribute(const std::string& object_path, const std::string& name, double value);
  void attribute(const std::string& object_path, const std::string& name, const std::string& value);
  void attribute(const std::string& object_path, const std::string& name,
                 const std::vector<std::string>& values);

 private:
  void ensure_parent_groups(const std::string& path);
  [[noreturn]] void fail_write();  // closes the file as it is, throws OutputError
  void check(bool ok);             // fail_write() unless ok
  std::string path_;
  int exceptions_ = 0;  // std::uncaught_exceptions() when made
  hid_t file_ = -1;
  int fd_ = -1;  // its OS descriptor
};

}  // namespace pcsim::output
