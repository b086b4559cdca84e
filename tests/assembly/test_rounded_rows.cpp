// RoundedRows (include/pcsim/assembly/rounded_rows.hpp), the modal dropper check's
// rows in half precision: the binary16 rounding against every finite half
// value, and the product's error bound against an exact product on rows
// shaped like a window's dropper rows (entries over six decades).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "pcsim/assembly/rounded_rows.hpp"

namespace {

using pcsim::assembly::RoundedRows;

TEST(RoundedRows, EveryFiniteHalfRoundTrips) {
  for (unsigned h = 0; h < 0x10000; ++h) {
    if (((h >> 10) & 31) == 31) continue;  // infinities and NaNs: never stored
    const auto half = static_cast<std::uint16_t>(h);
    const float v = RoundedRows::from_half(half);
    // -0 keeps its sign bit: to_half reads it.
    ASSERT_EQ(RoundedRows::to_half(v), half) << "h = " << h << ", v = " << v;
  }
}

TEST(RoundedRows, RoundsToNearestEven) {
  EXPECT_EQ(RoundedRows::to_half(1.0), 0x3C00);
  EXPECT_EQ(RoundedRows::to_half(65504.0), 0x7BFF);
  EXPECT_EQ(RoundedRows::to_half(0x1p-24), 0x0001);
  EXPECT_EQ(RoundedRows::to_half(0x1p-14), 0x0400);
  EXPECT_EQ(RoundedRows::to_half(-2.0), 0xC000);
  EXPECT_EQ(RoundedRows::to_half(1 + 0x1p-11), 0x3C00);      // tie: to the even mantissa
  EXPECT_EQ(RoundedRows::to_half(1 + 3 * 0x1p-11), 0x3C02);  // tie: up, to the even one
  EXPECT_EQ(RoundedRows::to_half(1 + 0x1p-11 + 0x1p-30), 0x3C01);
  EXPECT_EQ(RoundedRows::to_half(0x1p-25), 0x0000);      // tie between 0 and 2^-24
  EXPECT_EQ(RoundedRows::to_half(2 - 0x1p-12), 0x4000);  // the mantissa carries
  EXPECT_THROW(RoundedRows::to_half(65520.0), std::invalid_argument);
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> unit(1.0, 2.0);
  for (int k = 0; k < 100000; ++k) {
    const double v = std::ldexp(unit(random), k % 29 - 14);  // normal halves
    ASSERT_LE(std::abs(RoundedRows::from_half(RoundedRows::to_half(v)) - v), 0x1p-11 * v);
  }
}

// Rows as a 1000-span window's at 108.8 Hz (99 x 4406), entries N(0, 1)
// times 10^U(-6, 0), one zero row; states changes with a few large entries.
class Product : public ::testing::TestWithParam<RoundedRows::Precision> {
 protected:
  void SetUp() override {
    std::mt19937_64 random(11);
    std::normal_distribution<double> normal;
    std::uniform_real_distribution<double> decade(-6, 0);
    rows_.resize(99, 4406);
    for (long d = 0; d < rows_.rows(); ++d)
      for (long i = 0; i < rows_.cols(); ++i)
        rows_(d, i) = d == 5 ? 0.0 : normal(random) * std::pow(10.0, decade(random));
    for (int s = 0; s < 20; ++s) {
      Eigen::VectorXd x(rows_.cols());
      for (long i = 0; i < x.size(); ++i) x[i] = normal(random) * std::pow(10.0, decade(random));
      x[s] = 1e3;  // a few coordinates dominate, as the lowest modes do
      x *= std::pow(10.0, s - 10);
      states_.push_back(x);
    }
  }
  RoundedRows::RowMatrix rows_;
  std::vector<Eigen::VectorXd> states_;
};

bool is_half(RoundedRows::Precision p) {
  return p == RoundedRows::Precision::half;
}

TEST_P(Product, WithinItsBound) {
  const RoundedRows half(rows_, GetParam());
  const double g = half.error_factor();
  // The rows' rounding (2^-11 in half, 2^-24 in single), x's (2^-24) and
  // the sums' (551 + 3) 2^-24 (n = 4406: 551 terms per lane), to within
  // 1e-3 of themselves (the products of the units).
  const double expected = (is_half(GetParam()) ? 0x1p-11 : 0x1p-24) + 555 * 0x1p-24;
  EXPECT_NEAR(g, expected, 1e-3 * expected);
  double worst = 0;  // the largest error over its bound
  Eigen::VectorXd y;
  for (const auto& x : states_) {
    half.multiply(x, y);
    for (long d = 0; d < rows_.rows(); ++d) {
      long double exact = 0;
      for (long i = 0; i < x.size(); ++i)
        exact += static_cast<long double>(rows_(d, i)) * static_cast<long double>(x[i]);
      const double bound = g * rows_.row(d).norm() * x.norm();
      const double error = std::abs(static_cast<double>(y[d] - exact));
      if (d == 5) {
        EXPECT_EQ(y[d], 0.0);
        continue;
      }
      ASSERT_LE(error, bound) << "row " << d;
      worst = std::max(worst, error / bound);
    }
  }
  // Random signs make the bound loose (the errors add as a random walk):
  // measured at worst 0.069 of it in half precision, 0.0015 in single.
  // Float rows in the half case would stay near 1e-5 of it, a double
  // product in the single case near 1e-9: what is bounded is the rounding
  // of the precision asked for (margin 3).
  RecordProperty("worst", std::to_string(worst));
  EXPECT_GT(worst, is_half(GetParam()) ? 0.02 : 5e-4);
}

// A state that is not finite (a diverging run) gives NaN, as a product in
// floating point would, never a finite elongation.
TEST_P(Product, NotFiniteStateGivesNaN) {
  const RoundedRows rounded(rows_, GetParam());
  Eigen::VectorXd x = states_[0], y;
  x[7] = std::numeric_limits<double>::infinity();
  rounded.multiply(x, y);
  EXPECT_TRUE(y.array().isNaN().all());
  x[7] = std::numeric_limits<double>::quiet_NaN();
  rounded.multiply(x, y);
  EXPECT_TRUE(y.array().isNaN().all());
}

// On a processor without AVX2/F16C/FMA both calls take the portable kernel.
TEST_P(Product, KernelsGiveTheSameBits) {
  RecordProperty("vector_kernel", RoundedRows::vector_kernel_available() ? "yes" : "no");
  const RoundedRows half(rows_, GetParam());
  Eigen::VectorXd vector, portable;
  for (const auto& x : states_) {
    half.multiply(x, vector, RoundedRows::Kernel::automatic);
    half.multiply(x, portable, RoundedRows::Kernel::portable);
    ASSERT_EQ(vector, portable);
  }
}

TEST_P(Product, StoredValuesAreTheRowsRounded) {
  const RoundedRows half(rows_, GetParam());
  const double unit = is_half(GetParam()) ? 0x1p-11 : 0x1p-24;
  for (long d = 0; d < rows_.rows(); ++d) {
    const double largest = rows_.row(d).cwiseAbs().maxCoeff();
    for (long i = 0; i < rows_.cols(); i += 37)
      ASSERT_LE(std::abs(half.value(d, i) - rows_(d, i)),
                unit * std::abs(rows_(d, i)) + 0x1p-39 * largest);
  }
  EXPECT_EQ(half.bytes(), (is_half(GetParam()) ? 2u : 4u) * 99 * 4408);
}

INSTANTIATE_TEST_SUITE_P(RoundedRows, Product,
                         ::testing::Values(RoundedRows::Precision::half,
                                           RoundedRows::Precision::single));

}  // namespace
