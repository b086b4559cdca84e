// Dense products by the BLAS behind libblas.so.3 (dgemm): where pcsim's
// portable build (-O2, any x86-64) runs Eigen's own kernels at SSE2 width,
// an optimised BLAS runs its vector kernels (docs/benchmarks.md, "The BLAS
// behind the modes").
#pragma once

namespace pcsim {

// C = alpha op(A) op(B) + beta C, column-major as the BLAS takes them: op(A)
// m x k, op(B) k x n, C m x n; transpose_a, transpose_b: op(X) = X^T. A
// row-major matrix is the column-major view of its transpose: callers with
// row-major storage compute C^T = op(B)^T op(A)^T. beta 0: C is only written.
void dense_gemm(bool transpose_a, bool transpose_b, long m, long n, long k, double alpha,
                const double* A, long lda, const double* B, long ldb, double beta, double* C,
                long ldc);

}  // namespace pcsim
