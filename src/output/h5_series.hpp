// HDF5 helpers of the streamed run results (run_stream.cpp, run_results.cpp):
// an extendible, chunked dataset of doubles that grows along its first
// dimension (time), and plain reads of whole datasets.
#pragma once

#include <hdf5.h>

#include <string>
#include <vector>

namespace pcsim::output::h5 {

// A dataset rows x row_shape (row_shape empty: a vector), extendible in rows.
class Series {
 public:
  // Creates 'path' in 'file' (parent groups too) with 0 rows and the
  // attributes 'unit' and 'description'.
  Series(hid_t file, const std::string& path, std::vector<hsize_t> row_shape,
         const std::string& unit, const std::string& description);
  // Opens an existing one.
  Series(hid_t file, const std::string& path);
  ~Series();
  Series(const Series&) = delete;
  Series& operator=(const Series&) = delete;

  std::size_t rows() const { return rows_; }
  std::size_t row_size() const { return row_size_; }  // values per row
  // Appends n rows (n * row_size() values, row-major).
  void append(const double* values, std::size_t n);
  // Keeps the first n rows.
  void truncate(std::size_t n);

 private:
  hid_t set_ = -1;
  std::size_t rows_ = 0, row_size_ = 1;
  int rank_ = 1;
};

// Whole dataset: values row-major and its dimensions.
std::vector<double> read(hid_t file, const std::string& path, std::vector<hsize_t>* dims = nullptr);
// A fixed-size dataset (parent groups made) with 'unit' and 'description'.
void write(hid_t file, const std::string& path, const std::vector<double>& values,
           std::vector<hsize_t> dims, const std::string& unit, const std::string& description);
bool exists(hid_t file, const std::string& path);
// A virtual dataset at view_path (parent groups made) showing row k of the
// series at source_path (same file): no data of its own.
void add_row_view(hid_t file, const std::string& view_path, const std::string& source_path,
                  std::size_t k, const std::string& unit);
// Scalar attributes of an object ("/" for the file); set() replaces.
void set_attribute(hid_t file, const std::string& object, const std::string& name, double value);
void set_attribute(hid_t file, const std::string& object, const std::string& name,
                   const std::string& value);
double number_attribute(hid_t file, const std::string& object, const std::string& name);
std::string text_attribute(hid_t file, const std::string& object, const std::string& name);

// Closes 'file' after a write to it failed (a full disk): HDF5 1.10 keeps a
// file whose close failed half-destroyed and crashes when it ends, so the
// writes still pending go to an anonymous memory file instead and the close
// succeeds; the file on disk keeps what was written before. Also for a file
// whose H5Fclose already failed ('fd': its descriptor, from descriptor()).
void discard_close(hid_t file, int fd = -1);
// The first half of that: the file's later writes go to memory (close its
// datasets after this, then the file).
void discard_writes(hid_t file, int fd = -1);
// The file's OS descriptor (-1 if unknown).
int descriptor(hid_t file);

}  // namespace pcsim::output::h5
