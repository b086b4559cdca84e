#include "mode_row_store.hpp"

#include <algorithm>
#include <cstring>

namespace pcsim::simulation {

void ModeRowStore::reserve_columns(std::size_t columns) {
  if (columns > stride_) restride(columns);
}

void ModeRowStore::append(const double* column) {
  if (count_ == stride_) restride(std::max<std::size_t>(2 * stride_, 8));
  for (std::size_t i = 0; i < rows_; ++i) values_[i * stride_ + count_] = column[i];
  ++count_;
}

// Each row moved to its place at the wider stride, from the last: a row's
// new place starts at or after its old one and ends before the next row's
// new place, and no earlier row's old place reaches it.
void ModeRowStore::restride(std::size_t stride) {
  values_.resize(rows_ * stride);
  for (std::size_t i = rows_; i-- > 0;)
    std::memmove(values_.data() + i * stride, values_.data() + i * stride_,
                 count_ * sizeof(double));
  stride_ = stride;
}

std::vector<double> ModeRowStore::take(std::size_t room) {
  // Rows moved to the stride of the columns, from the first (each to a place
  // at or before its old one); none where they are there already.
  if (stride_ != count_)
    for (std::size_t i = 0; i < rows_; ++i)
      std::memmove(values_.data() + i * count_, values_.data() + i * stride_,
                   count_ * sizeof(double));
  values_.resize(rows_ * count_);
  values_.reserve(rows_ * (count_ + room));
  std::vector<double> out = std::move(values_);
  values_ = std::vector<double>();
  stride_ = count_ = 0;
  return out;
}

void ModeRowStore::adopt(std::vector<double>&& rows, std::size_t columns) {
  values_ = std::move(rows);
  stride_ = count_ = columns;
}

}  // namespace pcsim::simulation
