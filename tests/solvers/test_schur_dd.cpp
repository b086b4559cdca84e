// The exact domain-decomposition step solver (solvers/schur_dd.hpp) against
// known solutions: a nonsymmetric block chain (the shape of a catenary's
// step matrix: 6 unknowns per node, neighbours coupled) with a few "extra"
// unknowns on the last rank coupled to nodes anywhere (the pantographs), on
// 1, 2 and 3 ranks. It must be a direct solve: one application of the PC
// gives x to round-off, and the same x on any number of ranks.
// pcsim-test-ranks: 1 2 3
#include <gtest/gtest.h>
#include <petscksp.h>

#include <cmath>

#include "pcsim/core/error.hpp"
#include "pcsim/solvers/direct.hpp"
#include "pcsim/solvers/schur_dd.hpp"

namespace {

using pcsim::solvers::domain_decomposition_info;
using pcsim::solvers::use_schur_domain_decomposition;

constexpr PetscInt kNodes = 400, kBlock = 6, kExtras = 3;
constexpr PetscInt kChain = kNodes * kBlock, kSize = kChain + kExtras;

// Deterministic entries in (-1, 1), different for every (i, j).
double pseudo(PetscInt i, PetscInt j) {
  return std::sin(0.37 * static_cast<double>(i) + 1.71 * static_cast<double>(j) + 0.3);
}

// The extras couple to these nodes (one per third of the chain): across the cuts.
PetscInt coupled_node(PetscInt k) {
  return (2 * k + 1) * kNodes / (2 * kExtras);
}

// far: the value of a coupling between the first extra and node 0 (on rank
// 0), stored even when zero (as the step matrices store the pantographs'
// possible couplings with the whole contact wire).
Mat chain_matrix(double far) {
  int rank, size;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  // Whole nodes per rank; the extras on the last rank.
  const PetscInt first_node = kNodes * rank / size, end_node = kNodes * (rank + 1) / size;
  const PetscInt local = (end_node - first_node) * kBlock + (rank == size - 1 ? kExtras : 0);
  Mat A;
  PCSIM_PETSC(MatCreateAIJ(PETSC_COMM_WORLD, local, local, kSize, kSize, 3 * kBlock + kExtras + 1,
                           nullptr, 3 * kBlock + kExtras + 1, nullptr, &A));
  for (PetscInt n = first_node; n < end_node; ++n)
    for (PetscInt a = 0; a < kBlock; ++a) {
      const PetscInt row = n * kBlock + a;
      for (PetscInt m = std::max<PetscInt>(0, n - 1); m <= std::min(kNodes - 1, n + 1); ++m)
        for (PetscInt b = 0; b < kBlock; ++b) {
          const PetscInt col = m * kBlock + b;
          const double v = row == col ? 40.0 : pseudo(row, col);
          PCSIM_PETSC(MatSetValue(A, row, col, v, INSERT_VALUES));
        }
      if (n == 0 && a == 2) PCSIM_PETSC(MatSetValue(A, row, kChain, far, INSERT_VALUES));
      for (PetscInt k = 0; k < kExtras; ++k)
        if (n == coupled_node(k) && a == 2)
          PCSIM_PETSC(MatSetValue(A, row, kChain + k, -2.0 + 0.1 * k, INSERT_VALUES));
    }
  if (rank == size - 1)
    for (PetscInt k = 0; k < kExtras; ++k) {
      const PetscInt row = kChain + k;
      PCSIM_PETSC(MatSetValue(A, row, row, 5.0 + k, INSERT_VALUES));
      PCSIM_PETSC(MatSetValue(A, row, coupled_node(k) * kBlock + 2, -3.0, INSERT_VALUES));
      if (k > 0) PCSIM_PETSC(MatSetValue(A, row, row - 1, 0.5, INSERT_VALUES));
      if (k == 0) PCSIM_PETSC(MatSetValue(A, row, 2, far, INSERT_VALUES));
    }
  PCSIM_PETSC(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
  PCSIM_PETSC(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
  return A;
}

TEST(SchurDomainDecomposition, SolvesExactlyOnAnyNumberOfRanks) {
  Mat A = chain_matrix(0.0);
  Vec x_true, b, x;
  PCSIM_PETSC(MatCreateVecs(A, &x_true, &b));
  PCSIM_PETSC(VecDuplicate(b, &x));
  PetscInt lo, hi;
  PCSIM_PETSC(VecGetOwnershipRange(x_true, &lo, &hi));
  for (PetscInt i = lo; i < hi; ++i)
    PCSIM_PETSC(VecSetValue(x_true, i, 1.0 + pseudo(i, 7 * i), INSERT_VALUES));
  PCSIM_PETSC(VecAssemblyBegin(x_true));
  PCSIM_PETSC(VecAssemblyEnd(x_true));
  PCSIM_PETSC(MatMult(A, x_true, b));

  KSP ksp;
  PCSIM_PETSC(KSPCreate(PETSC_COMM_WORLD, &ksp));
  use_schur_domain_decomposition(ksp);
  PCSIM_PETSC(KSPSetOperators(ksp, A, A));
  PCSIM_PETSC(KSPSetUp(ksp));
  PCSIM_PETSC(KSPSolve(ksp, b, x));  // preonly: one application of the PC
  PCSIM_PETSC(VecAXPY(x, -1.0, x_true));
  PetscReal error, scale;
  PCSIM_PETSC(VecNorm(x, NORM_INFINITY, &error));
  PCSIM_PETSC(VecNorm(x_true, NORM_INFINITY, &scale));
  // A diagonally dominant matrix (condition ~10): LU leaves ~1e-15 relative;
  // 1e-12 allows for the Schur complement's extra rounding.
  EXPECT_LT(error / scale, 1e-12);

  int size;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  const auto info = domain_decomposition_info(ksp);
  EXPECT_GT(info.factor_nonzeros, kSize);  // at least the diagonal
  EXPECT_DOUBLE_EQ(info.factor_nonzeros, pcsim::solvers::step_factor_nonzeros(ksp));
  if (size == 1) EXPECT_EQ(info.interface_size, 0);
  // Each cut puts both neighbouring nodes (12 unknowns) in the interface; the
  // extras and the nodes they couple to join it when they sit on another rank.
  if (size > 1) EXPECT_GE(info.interface_size, 12 * (size - 1));
  if (size > 1) EXPECT_LE(info.interface_size, 12 * (size - 1) + 2 * kExtras * 6);

  // A new matrix (values changed, same pattern): set up again, still exact.
  PCSIM_PETSC(MatShift(A, 3.0));
  PCSIM_PETSC(MatMult(A, x_true, b));
  PCSIM_PETSC(KSPSetOperators(ksp, A, A));
  PCSIM_PETSC(KSPSolve(ksp, b, x));
  PCSIM_PETSC(VecAXPY(x, -1.0, x_true));
  PCSIM_PETSC(VecNorm(x, NORM_INFINITY, &error));
  EXPECT_LT(error / scale, 1e-12);

  // The far coupling switched on: on several ranks node 0 and the first extra
  // join the interface (a new split, new interior factors), still exact.
  Mat A_far = chain_matrix(1.5);
  PCSIM_PETSC(MatMult(A_far, x_true, b));
  PCSIM_PETSC(KSPSetOperators(ksp, A_far, A_far));
  PCSIM_PETSC(KSPSolve(ksp, b, x));
  PCSIM_PETSC(VecAXPY(x, -1.0, x_true));
  PCSIM_PETSC(VecNorm(x, NORM_INFINITY, &error));
  EXPECT_LT(error / scale, 1e-12);
  if (size > 1) EXPECT_GT(domain_decomposition_info(ksp).interface_size, info.interface_size);
  MatDestroy(&A_far);

  KSPDestroy(&ksp);
  VecDestroy(&x_true);
  VecDestroy(&b);
  VecDestroy(&x);
  MatDestroy(&A);
}

}  // namespace
