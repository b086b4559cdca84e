// The modes' kept rows stored row-major as they come (mode_row_store.hpp):
// the same values as the columns appended, whether the room was reserved
// beforehand or grown on the way, and the rows taken in the store's own
// storage with the room the basis needs (no copy where a first run peaks).
#include <gtest/gtest.h>

#include <vector>

#include "../../src/simulation/mode_row_store.hpp"

using pcsim::simulation::ModeRowStore;

namespace {

constexpr std::size_t kRows = 5;

// Column k's value in row i: distinct for every entry.
double value(std::size_t i, std::size_t k) {
  return 1000.0 * static_cast<double>(k) + static_cast<double>(i) + 0.5;
}

void append_columns(ModeRowStore& store, std::size_t from, std::size_t to) {
  std::vector<double> column(kRows);
  for (std::size_t k = from; k < to; ++k) {
    for (std::size_t i = 0; i < kRows; ++i) column[i] = value(i, k);
    store.append(column.data());
  }
}

void expect_rows(const std::vector<double>& rows, std::size_t columns, const char* what) {
  ASSERT_EQ(rows.size(), kRows * columns) << what;
  for (std::size_t i = 0; i < kRows; ++i)
    for (std::size_t k = 0; k < columns; ++k)
      EXPECT_EQ(rows[i * columns + k], value(i, k)) << what << ": row " << i << ", column " << k;
}

}  // namespace

TEST(ModeRowStore, GrownOnTheWayOrReservedTheSameRows) {
  ModeRowStore grown(kRows);  // 8 columns, then 16, then 32: two moves of its rows
  append_columns(grown, 0, 21);
  ModeRowStore reserved(kRows);
  reserved.reserve_columns(21);
  append_columns(reserved, 0, 21);
  for (std::size_t k = 0; k < 21; ++k) EXPECT_EQ(grown.at(3, k), value(3, k));
  expect_rows(grown.take(0), 21, "grown, taken");
  expect_rows(reserved.take(0), 21, "reserved, taken");
}

// A raised cut-off's modes after the first data: the rows taken by the
// data, given back (as a raise reads them from the cache), more appended.
TEST(ModeRowStore, MoreColumnsAfterTheRowsAreGivenBack) {
  ModeRowStore store(kRows);
  store.reserve_columns(6 + 2);
  append_columns(store, 0, 6);
  std::vector<double> first = store.take(2);
  expect_rows(first, 6, "first data");
  EXPECT_EQ(store.columns(), 0u);
  store.adopt(std::move(first), 6);
  EXPECT_EQ(store.columns(), 6u);
  store.reserve_columns(11);
  append_columns(store, 6, 11);
  expect_rows(store.take(0), 11, "raised");
}

TEST(ModeRowStore, TakenInItsOwnStorageWithRoom) {
  ModeRowStore store(kRows);
  store.reserve_columns(7 + 3);  // 7 modes and room for 3 columns of the basis
  append_columns(store, 0, 7);
  const double* storage = store.data();
  const std::vector<double> rows = store.take(3);
  expect_rows(rows, 7, "taken");
  EXPECT_EQ(rows.data(), storage);  // no copy
  EXPECT_GE(rows.capacity(), kRows * 10);
  ModeRowStore grown(kRows);  // grown on the way: moved to the columns' stride
  append_columns(grown, 0, 7);
  const std::vector<double> moved = grown.take(3);
  expect_rows(moved, 7, "grown, taken");
  EXPECT_GE(moved.capacity(), kRows * 10);
}
