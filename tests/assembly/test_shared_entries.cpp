// SharedEntries (include/pcsim/assembly/term.hpp), a rank-one term's index and
// weight: made from a vector (the copies keep it), or a view of a row that an
// owner keeps alive (a slack dropper's kept rows) or that outlives every copy
// (the reduced catenary's own rows); equality by pointer first, then by value.
#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "pcsim/assembly/term.hpp"

namespace {

using pcsim::assembly::SharedEntries;

TEST(SharedEntries, CopiesOfAVectorShareItsEntries) {
  const SharedEntries<double> a(std::vector<double>{1.0, 2.0, 3.0});
  const SharedEntries<double> b = a;
  ASSERT_EQ(a.size(), 3u);
  EXPECT_EQ(a.data(), b.data());  // one copy of the entries, not two
  EXPECT_EQ(a[2], 3.0);
  EXPECT_TRUE(a == b);
}

TEST(SharedEntries, AViewKeepsItsOwnerAlive) {
  auto matrix = std::make_shared<std::vector<double>>(std::vector<double>{1, 2, 3, 4, 5, 6});
  const std::weak_ptr<std::vector<double>> watch = matrix;
  SharedEntries<double> row(matrix, matrix->data() + 3, 3);  // the second row of 2 x 3
  matrix.reset();
  ASSERT_FALSE(watch.expired());  // the view holds the matrix
  EXPECT_EQ(row.size(), 3u);
  EXPECT_EQ(row[0], 4.0);
  EXPECT_EQ(row[2], 6.0);
  row = SharedEntries<double>();
  EXPECT_TRUE(watch.expired());  // and only the view did
}

TEST(SharedEntries, AViewWithoutOwnerPointsAtTheEntries) {
  const std::vector<double> kept{7.0, 8.0};
  const SharedEntries<double> view(nullptr, kept.data(), kept.size());
  EXPECT_EQ(view.data(), kept.data());  // no copy
  EXPECT_EQ(view.size(), 2u);
  EXPECT_EQ(view[1], 8.0);
}

TEST(SharedEntries, EqualByPointerOrByValue) {
  const std::vector<double> kept{1.0, 2.0, 3.0};
  const SharedEntries<double> view(nullptr, kept.data(), kept.size());
  const SharedEntries<double> same_values(std::vector<double>{1.0, 2.0, 3.0});
  const SharedEntries<double> other_value(std::vector<double>{1.0, 2.0, 4.0});
  const SharedEntries<double> shorter(nullptr, kept.data(), 2);
  EXPECT_TRUE(view == SharedEntries<double>(nullptr, kept.data(), kept.size()));
  EXPECT_TRUE(view == same_values);
  EXPECT_TRUE(view != other_value);
  EXPECT_TRUE(view != shorter);  // the same pointer, not the same entries
  EXPECT_TRUE(SharedEntries<double>() == SharedEntries<double>(std::vector<double>{}));
  EXPECT_TRUE(SharedEntries<double>().empty());
}

}  // namespace
