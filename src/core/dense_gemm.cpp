#include "pcsim/core/dense_gemm.hpp"

// petscblaslapack.h needs petscsys.h first.
// clang-format off
#include <petscsys.h>
#include <petscblaslapack.h>
// clang-format on

#include <algorithm>

#include "pcsim/core/error.hpp"

namespace pcsim {

void dense_gemm(bool transpose_a, bool transpose_b, long m, long n, long k, double alpha,
                const double* A, long lda, const double* B, long ldb, double beta, double* C,
                long ldc) {
  if (m == 0 || n == 0) return;
  if (k == 0) {  // no terms: C = beta C here, where A and B may be null
    for (long j = 0; j < n; ++j)
      for (long i = 0; i < m; ++i) C[i + j * ldc] = beta == 0 ? 0.0 : beta * C[i + j * ldc];
    return;
  }
  PetscBLASInt bm, bn, bk, blda, bldb, bldc;
  PCSIM_PETSC(PetscBLASIntCast(m, &bm));
  PCSIM_PETSC(PetscBLASIntCast(n, &bn));
  PCSIM_PETSC(PetscBLASIntCast(k, &bk));
  PCSIM_PETSC(PetscBLASIntCast(std::max(lda, 1L), &blda));
  PCSIM_PETSC(PetscBLASIntCast(std::max(ldb, 1L), &bldb));
  PCSIM_PETSC(PetscBLASIntCast(std::max(ldc, 1L), &bldc));
  BLASgemm_(transpose_a ? "T" : "N", transpose_b ? "T" : "N", &bm, &bn, &bk, &alpha, A, &blda, B,
            &bldb, &beta, C, &bldc);
}

}  // namespace pcsim
