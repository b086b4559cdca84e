// The BLAS kernels (core/blas_kernels.hpp), as the tests' main selected them
// (tests/gtest_main_petsc.cpp, as the pcsim executable does): BLIS never
// runs its generic kernels on a processor with AVX2 and FMA, and a dgemm by
// the kernels in use is right.
// clang-format off
#include <petscsys.h>
#include <petscblaslapack.h>
// clang-format on
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <random>
#include <vector>

#include "pcsim/core/blas_kernels.hpp"

namespace {

bool vector_kernels_fit() {
  __builtin_cpu_init();
  return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
}

TEST(BlasKernels, BlisRunsVectorKernelsWhereTheyFit) {
  const auto& k = pcsim::blas_kernels();
  ASSERT_FALSE(k.library.empty()) << "no library defines dgemm_";
  EXPECT_EQ(k.is_blis, k.library.find("/blis") != std::string::npos) << k.text();
  const char* arch = std::getenv("BLIS_ARCH_TYPE");
  EXPECT_TRUE(k.too_late.empty()) << k.text();  // the main selected before any BLAS call
  if (!k.is_blis) {
    // Another BLAS is left alone.
    EXPECT_TRUE(k.blis.empty() && k.kernels.empty() && !k.chosen) << k.text();
  } else if (k.detected.empty()) {
    // The user's BLIS_ARCH_TYPE (set before the process started) wins.
    ASSERT_NE(arch, nullptr) << k.text();
    EXPECT_EQ(k.kernels, std::string("BLIS_ARCH_TYPE=") + arch);
  } else {
    // BLIS's detection asked: its generic kernels replaced where vector ones fit.
    EXPECT_EQ(k.chosen, k.detected == "generic" && vector_kernels_fit()) << k.text();
    if (vector_kernels_fit()) EXPECT_NE(k.kernels, "generic") << k.text();
    EXPECT_EQ(arch != nullptr, k.chosen) << k.text();
  }
  std::printf("BLAS: %s\n", k.text().c_str());
}

// Which BLAS counts as optimised (the slicing's basis storage,
// solvers/modes.cpp): BLIS on kernels other than its generic ones, the user's
// BLIS_ARCH_TYPE, OpenBLAS or MKL; not the reference BLAS, nor BLIS whose
// kernels are generic or unknown.
TEST(BlasKernels, OptimisedBlasIsNamed) {
  pcsim::BlasKernels k;
  k.library = "/usr/lib/x86_64-linux-gnu/blas/libblas.so.3";
  EXPECT_FALSE(k.optimised());
  k.library = "/usr/lib/x86_64-linux-gnu/openblas-pthread/libblas.so.3";
  EXPECT_TRUE(k.optimised());
  k.library = "/opt/intel/oneapi/mkl/lib/libmkl_rt.so.2";
  EXPECT_TRUE(k.optimised());
  k.library = "/usr/lib/x86_64-linux-gnu/blis-serial/libblas.so.3";
  k.is_blis = true;
  EXPECT_FALSE(k.optimised());  // kernels unknown (its library was not asked)
  k.kernels = "generic";
  EXPECT_FALSE(k.optimised());
  for (const char* kernels : {"skx", "haswell", "zen3", "BLIS_ARCH_TYPE=3"}) {
    k.kernels = kernels;
    EXPECT_TRUE(k.optimised()) << kernels;
  }
}

// C = A^T B (the window shift's shape, smaller) against a plain sum: the
// chosen kernels run on this processor and compute the product.
TEST(BlasKernels, DgemmByTheKernelsInUseIsRight) {
  const PetscBLASInt m = 37, n = 53, k = 301;
  std::mt19937 random(7);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<double> A(k * m), B(k * n), C(m * n, 0.0);
  for (double& a : A) a = u(random);
  for (double& b : B) b = u(random);
  const double one = 1, zero = 0;
  BLASgemm_("T", "N", &m, &n, &k, &one, A.data(), &k, B.data(), &k, &zero, C.data(), &m);
  double worst = 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < m; ++i) {
      double sum = 0, size = 0;
      for (int l = 0; l < k; ++l) {
        sum += A[i * k + l] * B[j * k + l];
        size += std::abs(A[i * k + l] * B[j * k + l]);
      }
      worst = std::max(worst, std::abs(C[i + j * m] - sum) / size);
    }
  // Two sums of k = 301 products in other orders differ by at most ~2 k u
  // of the sum of |products| (u = 1.1e-16: 6.7e-14); a wrong kernel is O(1).
  EXPECT_LT(worst, 7e-14);
}

}  // namespace
