// The kept rows of the modes as they are computed (modal_basis.cpp), stored
// row-major from the start: the data's mode_rows and then the basis's rows
// (catenary::assemble_basis) are formed in the same storage, so a first
// run's basis holds one copy of its rows where it used to hold two (a
// column per mode, then their transpose).
#pragma once

#include <cstddef>
#include <vector>

namespace pcsim::simulation {

class ModeRowStore {
 public:
  explicit ModeRowStore(std::size_t rows) : rows_(rows) {}

  // Room for 'columns' columns in all, set once their number is known (the
  // modes counted below the cut-off, and the basis's columns beyond them).
  void reserve_columns(std::size_t columns);
  // A mode's rows (rows() values) as the next column; more room if needed
  // (the columns twice as many).
  void append(const double* column);

  std::size_t columns() const { return count_; }
  double at(std::size_t row, std::size_t column) const { return values_[row * stride_ + column]; }
  const double* data() const { return values_.data(); }

  // The rows as rows() x columns() row-major, with capacity for 'room' more
  // columns, in the store's own storage: the store is empty after.
  std::vector<double> take(std::size_t room);
  // Rows taken earlier (rows() x columns row-major) as the store's again,
  // for more columns (a raised cut-off's modes).
  void adopt(std::vector<double>&& rows, std::size_t columns);

 private:
  void restride(std::size_t stride);

  std::size_t rows_, stride_ = 0, count_ = 0;
  std::vector<double> values_;  // rows_ x stride_, row-major; columns count_.. unused
};

}  // namespace pcsim::simulation
