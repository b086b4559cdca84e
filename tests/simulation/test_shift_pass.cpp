// A modal window's shift pass (src/simulation/shift_pass.hpp): P in single
// precision times three double vectors. The vector kernel gives the portable
// kernel's bits; each product is within the rounding bound of a sum in 8
// lanes of the exact products of the stored floats; a range of rows leaves
// the others as they were.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "../../src/simulation/shift_pass.hpp"

namespace {

using pcsim::simulation::shift_rows;
using pcsim::simulation::shift_rows_portable;

struct Case {
  long m;
  std::vector<float> P;
  std::vector<double> x[3];
  const double* inputs[3];
  explicit Case(long size) : m(size), P(static_cast<std::size_t>(size * size)) {
    std::mt19937_64 random(static_cast<unsigned long>(size));
    std::uniform_real_distribution<double> entry(-1.0, 1.0);
    for (auto& p : P) p = static_cast<float>(entry(random));
    for (auto& v : x) {
      v.resize(static_cast<std::size_t>(size));
      for (auto& e : v) e = entry(random) * 1e-3;  // displacements of a mm
    }
    for (int s = 0; s < 3; ++s) inputs[s] = x[s].data();
  }
  Case(const Case&) = delete;  // inputs point into x
  Case& operator=(const Case&) = delete;
};

using Outputs = std::vector<std::vector<double>>;

Outputs run(const Case& c, bool portable, long first, long last) {
  Outputs y(3, std::vector<double>(static_cast<std::size_t>(c.m), -7.0));
  double* const out[3] = {y[0].data(), y[1].data(), y[2].data()};
  if (portable)
    shift_rows_portable(c.P.data(), c.m, c.inputs, out, first, last);
  else
    shift_rows(c.P.data(), c.m, c.inputs, out, first, last);
  return y;
}

// Sizes with and without a tail beyond the 8 lanes (3012: a window's basis).
const long kSizes[] = {1, 7, 8, 13, 64, 3012};

TEST(ShiftPass, VectorKernelGivesThePortableBits) {
  for (long m : kSizes) {
    const Case c(m);
    EXPECT_EQ(run(c, false, 0, m), run(c, true, 0, m)) << "m = " << m;
  }
}

TEST(ShiftPass, WithinTheRoundingBoundOfTheStoredProducts) {
  for (long m : kSizes) {
    const Case c(m);
    const Outputs y = run(c, false, 0, m);
    // gamma_k (Higham) for a chain of k = m/8 + 3 (lane, tree) + the tail's
    // fused additions; the products of a float and a double are exact in
    // double only up to the double's rounding, which gamma covers too.
    const double u = std::ldexp(1.0, -53), k = static_cast<double>(m / 8 + 3 + m % 8 + 1);
    const double gamma = k * u / (1 - k * u);
    for (int s = 0; s < 3; ++s)
      for (long i = 0; i < m; ++i) {
        long double exact = 0;
        double magnitude = 0;
        for (long j = 0; j < m; ++j) {
          const double p = c.P[static_cast<std::size_t>(i * m + j)];
          exact += static_cast<long double>(p) * c.x[s][static_cast<std::size_t>(j)];
          magnitude += std::abs(p * c.x[s][static_cast<std::size_t>(j)]);
        }
        ASSERT_LE(std::abs(static_cast<long double>(y[s][i]) - exact), gamma * magnitude)
            << "m = " << m << ", vector " << s << ", row " << i;
      }
  }
}

TEST(ShiftPass, ARangeOfRowsOnly) {
  const long m = 13;
  const Case c(m);
  const Outputs whole = run(c, false, 0, m);
  const Outputs part = run(c, false, 4, 9);
  for (int s = 0; s < 3; ++s)
    for (long i = 0; i < m; ++i)
      EXPECT_EQ(part[s][i], i >= 4 && i < 9 ? whole[s][i] : -7.0) << "row " << i;
}

}  // namespace
