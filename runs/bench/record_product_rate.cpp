// The dropper records' product dl = B eta of the modal catenary
// (src/assembly/modal_slack_set.cpp) three ways, at pcsim's flags (-O2, any
// x86-64: SSE2): Eigen's float product (the single-precision anchor), its
// double product (the exact anchor), and a float matrix times a double vector
// accumulated in double (a tighter single-precision bound, tried 2026-11-30
// and not kept: slower than the double product), and the records in batches
// (src/assembly/modal_records.cpp): the BLAS dgemm of B and 32 states, per
// state. B is ROWS x COLS (tracked bars x basis vectors: 90 x 4804 on
// dsa380-300-base at 136.1 Hz, 180 x 8014 on two-pantographs-300 at 108.8 Hz).
// Prints microseconds per product (mean of REPEAT).
//   g++ -O2 -DNDEBUG -I/usr/include/eigen3 -o record_product_rate
//   runs/bench/record_product_rate.cpp -lblas
//   ./record_product_rate [ROWS] [COLS] [REPEAT]
#include <Eigen/Core>
#include <chrono>
#include <cstdio>
#include <cstdlib>

extern "C" void dgemm_(const char*, const char*, const int*, const int*, const int*, const double*,
                       const double*, const int*, const double*, const int*, const double*, double*,
                       const int*);

using FloatRows = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
using DoubleRows = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// A float row times a double vector, four double accumulators.
double mixed_dot(const float* row, const double* v, long n) {
  double s0 = 0, s1 = 0, s2 = 0, s3 = 0;
  long j = 0;
  for (; j + 4 <= n; j += 4) {
    s0 += double(row[j]) * v[j];
    s1 += double(row[j + 1]) * v[j + 1];
    s2 += double(row[j + 2]) * v[j + 2];
    s3 += double(row[j + 3]) * v[j + 3];
  }
  for (; j < n; ++j) s0 += double(row[j]) * v[j];
  return (s0 + s1) + (s2 + s3);
}

int main(int argc, char** argv) {
  const long rows = argc > 1 ? std::atol(argv[1]) : 90;
  const long cols = argc > 2 ? std::atol(argv[2]) : 4804;
  const int repeat = argc > 3 ? std::atoi(argv[3]) : 2000;
  const DoubleRows b = DoubleRows::Random(rows, cols);
  const FloatRows b_single = b.cast<float>();
  const Eigen::VectorXd eta = Eigen::VectorXd::Random(cols);
  Eigen::VectorXd out(rows);
  Eigen::VectorXf eta_single(cols), out_single(rows);
  auto time_us = [&](auto product) {
    const auto t0 = std::chrono::steady_clock::now();
    for (int r = 0; r < repeat; ++r) product();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() / repeat *
           1e6;
  };
  const double single = time_us([&] {
    eta_single = eta.cast<float>();
    out_single.noalias() = b_single * eta_single;
  });
  const double exact = time_us([&] { out.noalias() = b * eta; });
  const double mixed = time_us([&] {
    for (long d = 0; d < rows; ++d)
      out[d] = mixed_dot(b_single.data() + d * cols, eta.data(), cols);
  });
  constexpr int kBatch = 32;
  const Eigen::MatrixXd states = Eigen::MatrixXd::Random(cols, kBatch);
  Eigen::MatrixXd batch(rows, kBatch);
  const int m = static_cast<int>(rows), n = kBatch, k = static_cast<int>(cols);
  const double one = 1, zero = 0;
  const double batched = time_us([&] {
                           dgemm_("T", "N", &m, &n, &k, &one, b.data(), &k, states.data(), &k,
                                  &zero, batch.data(), &m);
                         }) /
                         kBatch;
  std::printf(
      "B %ld x %ld: float %.1f us, double %.1f us, float x double in double %.1f us, "
      "BLAS dgemm of %d states %.1f us a state (%g)\n",
      rows, cols, single, exact, mixed, kBatch, batched,
      out.sum() + out_single.sum() + batch.sum());
  return 0;
}
