// The cheap path's varying blocks (src/solvers/varying_blocks.hpp): a small
// dense block of J0 whose value J0_b + delta changes at every Newton
// iteration is solved by its own LU, and a singular block is refused with a
// SolverError (the pivots of its LU, not Eigen's condition estimate).
#include <gtest/gtest.h>
#include <petscmat.h>

#include <Eigen/Dense>
#include <limits>
#include <vector>

#include "../../src/solvers/varying_blocks.hpp"
#include "pcsim/core/error.hpp"

namespace {

using pcsim::solvers::VaryingBlocks;

// J0: 2 x 2 identity rows, then the block (rows 2..4), decoupled.
Mat step_matrix(const Eigen::Matrix3d& block) {
  Mat P;
  PCSIM_PETSC(MatCreateSeqAIJ(PETSC_COMM_SELF, 5, 5, 3, nullptr, &P));
  for (PetscInt i = 0; i < 2; ++i) PCSIM_PETSC(MatSetValue(P, i, i, 1.0, INSERT_VALUES));
  for (PetscInt i = 0; i < 3; ++i)
    for (PetscInt j = 0; j < 3; ++j)
      PCSIM_PETSC(MatSetValue(P, 2 + i, 2 + j, block(i, j), INSERT_VALUES));
  PCSIM_PETSC(MatAssemblyBegin(P, MAT_FINAL_ASSEMBLY));
  PCSIM_PETSC(MatAssemblyEnd(P, MAT_FINAL_ASSEMBLY));
  return P;
}

pcsim::assembly::BlockChange change(const Eigen::Matrix3d& delta) {
  pcsim::assembly::BlockChange c;
  c.key = 7;
  c.first = 2;
  c.size = 3;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) c.delta.push_back(delta(i, j));  // row-major
  return c;
}

}  // namespace

// The block rows of the solution are (J0_b + delta)^-1 r_b (to rounding:
// 1e-14 of the solution, measured 1e-16), the other rows are left as given.
TEST(VaryingBlocks, SolvesTheChangedBlock) {
  Eigen::Matrix3d j0, delta;
  j0 << 4, 1, 0, 1, 3, 1, 0, 1, 2;
  delta << 0.5, -0.2, 0.1, 0.0, 0.3, -0.4, 0.2, 0.0, 0.7;
  Mat P = step_matrix(j0);
  VaryingBlocks blocks;
  blocks.set({change(delta)});
  blocks.setup(P);
  Vec r, x;
  PCSIM_PETSC(MatCreateVecs(P, &x, &r));
  const double rv[5] = {9, 9, 1.0, -2.0, 0.5};
  for (PetscInt i = 0; i < 5; ++i) PCSIM_PETSC(VecSetValue(r, i, rv[i], INSERT_VALUES));
  PCSIM_PETSC(VecAssemblyBegin(r));
  PCSIM_PETSC(VecAssemblyEnd(r));
  PCSIM_PETSC(VecSet(x, 3.0));
  blocks.solve_rows(r, x);
  const Eigen::Vector3d expected = (j0 + delta).lu().solve(Eigen::Vector3d(1.0, -2.0, 0.5));
  const PetscScalar* xa;
  PCSIM_PETSC(VecGetArrayRead(x, &xa));
  EXPECT_EQ(xa[0], 3.0);
  EXPECT_EQ(xa[1], 3.0);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(xa[2 + i], expected[i], 1e-14 * expected.norm());
  PCSIM_PETSC(VecRestoreArrayRead(x, &xa));
  PCSIM_PETSC(VecDestroy(&r));
  PCSIM_PETSC(VecDestroy(&x));
  PCSIM_PETSC(MatDestroy(&P));
}

// A change that makes the block singular (a zero row), or not finite, is
// refused at once: the step never solves with it.
TEST(VaryingBlocks, RefusesASingularOrNotFiniteBlock) {
  Eigen::Matrix3d j0;
  j0 << 4, 1, 0, 1, 3, 1, 0, 1, 2;
  Mat P = step_matrix(j0);
  VaryingBlocks blocks;
  blocks.set({change(Eigen::Matrix3d::Zero())});
  blocks.setup(P);
  Eigen::Matrix3d singular = Eigen::Matrix3d::Zero();
  singular.row(1) = -j0.row(1);  // J0_b + delta has a zero row
  EXPECT_THROW(blocks.set({change(singular)}), pcsim::SolverError);
  Eigen::Matrix3d not_finite = Eigen::Matrix3d::Zero();
  not_finite(0, 0) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(blocks.set({change(not_finite)}), pcsim::SolverError);
  EXPECT_NO_THROW(blocks.set({change(Eigen::Matrix3d::Identity())}));
  PCSIM_PETSC(MatDestroy(&P));
}
