// SubsetAxpy (Y += a X, X's pattern a subset of Y's) against PETSc's MatAXPY
// on distributed matrices: Y a banded matrix with a dense last row and
// column (as the Jacobian couples a pantograph with the whole contact wire),
// X tridiagonal with entries in the off-diagonal blocks on several ranks.
// The sums are the same floating-point operations: they must agree exactly.
// pcsim-test-ranks: 1 2 3
#include <gtest/gtest.h>
#include <petscmat.h>

#include <cmath>

#include "pcsim/assembly/subset_axpy.hpp"
#include "pcsim/core/error.hpp"

namespace {

constexpr PetscInt kN = 60;

Mat band(PetscInt width, bool dense_last, double scale) {
  Mat A;
  PCSIM_PETSC(MatCreateAIJ(PETSC_COMM_WORLD, PETSC_DECIDE, PETSC_DECIDE, kN, kN, kN, nullptr, kN,
                           nullptr, &A));
  PetscInt lo, hi;
  PCSIM_PETSC(MatGetOwnershipRange(A, &lo, &hi));
  for (PetscInt i = lo; i < hi; ++i)
    for (PetscInt j = 0; j < kN; ++j) {
      const bool in_band = std::abs(static_cast<double>(i - j)) <= width;
      const bool last = dense_last && (i == kN - 1 || j == kN - 1);
      if (in_band || last)
        PCSIM_PETSC(MatSetValue(A, i, j, scale * std::cos(0.1 * i + 0.37 * j), INSERT_VALUES));
    }
  PCSIM_PETSC(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
  PCSIM_PETSC(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
  return A;
}

TEST(SubsetAxpy, EqualsMatAXPY) {
  Mat Y = band(3, true, 1.0), X = band(1, false, 2.0), reference;
  PCSIM_PETSC(MatDuplicate(Y, MAT_COPY_VALUES, &reference));
  pcsim::assembly::SubsetAxpy axpy;
  for (double a : {0.7, -1.3}) {  // the second call reuses the map
    axpy.apply(Y, a, X);
    PCSIM_PETSC(MatAXPY(reference, a, X, SUBSET_NONZERO_PATTERN));
  }
  PCSIM_PETSC(MatAXPY(reference, -1.0, Y, SAME_NONZERO_PATTERN));
  PetscReal difference;
  PCSIM_PETSC(MatNorm(reference, NORM_FROBENIUS, &difference));
  EXPECT_EQ(difference, 0.0);
  // Not a subset: refused.
  EXPECT_THROW(axpy.apply(X, 1.0, Y), pcsim::SolverError);
  MatDestroy(&reference);
  MatDestroy(&X);
  MatDestroy(&Y);
}

}  // namespace
