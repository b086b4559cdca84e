// TripletPattern: the same matrix as Eigen's setFromTriplets, bit for bit,
// from the kept pattern while the triplets' positions repeat, and a new
// analysis when they change.
#include <gtest/gtest.h>

#include <Eigen/SparseCore>
#include <cmath>
#include <random>
#include <vector>

#include "pcsim/core/triplet_pattern.hpp"

namespace {

using Triplets = std::vector<Eigen::Triplet<double>>;

// Positions with duplicates (each entry written up to four times, in no
// order), values of mixed signs and magnitudes, so that the order of the sum
// shows in the last bits.
Triplets random_triplets(int n, int count, unsigned seed, std::mt19937& values) {
  std::mt19937 positions(seed);
  std::uniform_int_distribution<int> index(0, n - 1);
  std::uniform_real_distribution<double> mantissa(-1.0, 1.0), exponent(-8.0, 8.0);
  Triplets t;
  for (int k = 0; k < count; ++k) {
    const int i = index(positions), j = index(positions);
    for (int d = 0; d < 1 + k % 4; ++d)
      t.emplace_back(i, j, mantissa(values) * std::pow(10.0, exponent(values)));
  }
  return t;
}

Eigen::SparseMatrix<double> eigen_reference(const Triplets& t, int n) {
  Eigen::SparseMatrix<double> m(n, n);
  m.setFromTriplets(t.begin(), t.end());
  return m;
}

void expect_same_bits(const Eigen::SparseMatrix<double>& a, const Eigen::SparseMatrix<double>& b) {
  ASSERT_EQ(a.rows(), b.rows());
  ASSERT_EQ(a.nonZeros(), b.nonZeros());
  for (Eigen::Index j = 0; j <= a.outerSize(); ++j)
    ASSERT_EQ(a.outerIndexPtr()[j], b.outerIndexPtr()[j]);
  for (Eigen::Index k = 0; k < a.nonZeros(); ++k) {
    ASSERT_EQ(a.innerIndexPtr()[k], b.innerIndexPtr()[k]);
    // Exact: the same sums in the same order.
    ASSERT_EQ(a.valuePtr()[k], b.valuePtr()[k]) << "entry " << k;
  }
}

TEST(TripletPattern, RepeatedPositionsGiveSetFromTripletsBits) {
  const int n = 40;
  std::mt19937 values(7);
  pcsim::core::TripletPattern pattern;
  Eigen::SparseMatrix<double> out;
  for (int pass = 0; pass < 5; ++pass) {
    const Triplets t = random_triplets(n, 300, 11, values);  // same positions, new values
    pattern.assemble(t, n, out);
    expect_same_bits(out, eigen_reference(t, n));
  }
  EXPECT_EQ(pattern.analyses(), 1);  // only the first sorted them
}

TEST(TripletPattern, ChangedPositionsAreAnalysedAgain) {
  const int n = 30;
  std::mt19937 values(3);
  pcsim::core::TripletPattern pattern;
  Eigen::SparseMatrix<double> out;
  Triplets t = random_triplets(n, 200, 5, values);
  pattern.assemble(t, n, out);
  // One more triplet (a one-way damper engaging), one fewer, one moved, the
  // same triplets in another order, another size: each a new analysis.
  Triplets more = t;
  more.emplace_back(2, 3, 1.5);
  Triplets fewer(t.begin(), t.end() - 1);
  Triplets moved = t;
  moved[17] = Eigen::Triplet<double>((moved[17].row() + 1) % n, moved[17].col(), 2.0);
  Triplets reordered(t.rbegin(), t.rend());
  long analyses = 1;
  for (const Triplets* next : {&more, &fewer, &moved, &reordered, &t}) {
    pattern.assemble(*next, n, out);
    expect_same_bits(out, eigen_reference(*next, n));
    EXPECT_EQ(pattern.analyses(), ++analyses);
  }
  pattern.assemble(t, n + 1, out);
  expect_same_bits(out, eigen_reference(t, n + 1));
  EXPECT_EQ(pattern.analyses(), ++analyses);
}

TEST(TripletPattern, ExplicitZerosStayInThePattern) {
  const int n = 3;
  const Triplets first = {{0, 0, 1.0}, {1, 2, 2.0}, {1, 2, -2.0}, {2, 1, 0.0}};
  pcsim::core::TripletPattern pattern;
  Eigen::SparseMatrix<double> out;
  pattern.assemble(first, n, out);
  EXPECT_EQ(out.nonZeros(), 3);  // (1,2) sums to 0 and (2,1) is 0: both kept
  const Triplets second = {{0, 0, 4.0}, {1, 2, 2.0}, {1, 2, 1.0}, {2, 1, -5.0}};
  pattern.assemble(second, n, out);
  EXPECT_EQ(pattern.analyses(), 1);
  EXPECT_EQ(out.coeff(0, 0), 4.0);
  EXPECT_EQ(out.coeff(1, 2), 3.0);
  EXPECT_EQ(out.coeff(2, 1), -5.0);
  EXPECT_EQ(out.nonZeros(), 3);
}

}  // namespace
