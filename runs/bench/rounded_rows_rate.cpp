// The modal dropper check's product three ways (docs/benchmarks.md,
// "Rounded rows"): RoundedRows in half and in single precision
// (src/assembly/rounded_rows.cpp) and Eigen's float product, on random rows
// of R x C (default 99 x 4406, the 1000-span window's at 108.8 Hz), with the
// rows in cache ("hot") and after a 64 MB sweep ("cold"). Median of 400.
// Build and run from the repository root:
//   g++ -O2 -DNDEBUG -std=c++17 -Iinclude -I/usr/include/eigen3 \
//     runs/bench/rounded_rows_rate.cpp src/assembly/rounded_rows.cpp src/core/vector_units.cpp \
//     -o /tmp/rounded_rows_rate
//   /tmp/rounded_rows_rate [R C]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <random>
#include <vector>

#include "pcsim/assembly/rounded_rows.hpp"

using pcsim::assembly::RoundedRows;

namespace {

double median_us(std::vector<double> t) {
  std::sort(t.begin(), t.end());
  return 1e6 * t[t.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  long rows = 99, cols = 4406;
  if (argc > 2) rows = std::atol(argv[1]), cols = std::atol(argv[2]);
  std::mt19937_64 random(1);
  std::normal_distribution<double> normal;
  RoundedRows::RowMatrix B(rows, cols);
  for (long i = 0; i < B.size(); ++i) B.data()[i] = normal(random);
  Eigen::VectorXd x(cols);
  for (long i = 0; i < cols; ++i) x[i] = normal(random);
  const RoundedRows half(B, RoundedRows::Precision::half);
  const RoundedRows single(B, RoundedRows::Precision::single);
  const Eigen::Matrix<float, -1, -1, Eigen::RowMajor> Bf = B.cast<float>();
  Eigen::VectorXd y;
  Eigen::VectorXf xf, yf;
  const std::vector<std::pair<const char*, std::function<void()>>> products = {
      {"half", [&] { half.multiply(x, y); }},
      {"single", [&] { single.multiply(x, y); }},
      {"Eigen float", [&] {
         xf = x.cast<float>();
         yf.noalias() = Bf * xf;
       }}};
  std::vector<char> sweep(64 << 20);
  std::printf("%ld x %ld rows, vector kernel: %s\n", rows, cols,
              RoundedRows::vector_kernel_available() ? "yes" : "no");
  std::printf("| product | hot us | cold us |\n|---|---:|---:|\n");
  for (const auto& [name, product] : products) {
    std::vector<double> hot, cold;
    for (int cached = 1; cached >= 0; --cached)
      for (int r = 0; r < 400; ++r) {
        if (!cached)
          for (std::size_t i = 0; i < sweep.size(); i += 64) ++sweep[i];
        const auto t0 = std::chrono::steady_clock::now();
        product();
        const auto t1 = std::chrono::steady_clock::now();
        (cached ? hot : cold).push_back(std::chrono::duration<double>(t1 - t0).count());
      }
    std::printf("| %s | %.1f | %.1f |\n", name, median_us(hot), median_us(cold));
  }
  return 0;
}
