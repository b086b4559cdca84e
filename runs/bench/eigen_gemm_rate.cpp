// The rate of the product of runs/bench/dgemm_rate.c (C = A^T B, A and B
// ROWS x 256) by Eigen's own kernels at pcsim's flags (-O2, any x86-64: SSE2),
// as src/simulation/modal_shift.cpp computed it before it called the BLAS.
// Prints GFlop/s (best of REPEAT).   eigen_gemm_rate [ROWS] [REPEAT]
#include <Eigen/Core>
#include <chrono>
#include <cstdio>
#include <cstdlib>

int main(int argc, char** argv) {
  const long k = argc > 1 ? std::atol(argv[1]) : 15790;
  const int repeat = argc > 2 ? std::atoi(argv[2]) : 5;
  const long n = 256;
  Eigen::MatrixXd a(k, n), b(k, n), c(n, n);
  for (long j = 0; j < n; ++j)
    for (long i = 0; i < k; ++i) a(i, j) = b(i, j) = static_cast<double>((i + j * k) % 1000) / 1000;
  double best = 1e300;
  for (int r = 0; r < repeat; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    c.noalias() = a.transpose() * b;
    const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (t < best) best = t;
  }
  std::printf("%.1f\n", 2.0 * n * n * k / best / 1e9 + 0 * c(0, 0));
  return 0;
}
