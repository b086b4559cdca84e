// The cheap path's varying blocks (src/solvers/varying_blocks.hpp): a small
// dense block of J0 whose value J0_b + delta changes at every Newton
// iteration is solved by its own LU, and a singular block is refused with a
// SolverError (the pivots of its LU, not Eigen's condition estimate).
#include <gtest/gtest.h>
#include <petscmat.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include "../../src/solvers/varying_blocks.hpp"
#include "pcsim/core/error.hpp"

namespace {

using pcsim::solvers::VaryingBlocks;

// J0: 2 identity rows, then an n x n block, decoupled (any size).
Mat step_matrix(const Eigen::MatrixXd& block) {
  const auto n = static_cast<PetscInt>(block.rows());
  Mat P;
  PCSIM_PETSC(MatCreateSeqAIJ(PETSC_COMM_SELF, 2 + n, 2 + n, n, nullptr, &P));
  for (PetscInt i = 0; i < 2; ++i) PCSIM_PETSC(MatSetValue(P, i, i, 1.0, INSERT_VALUES));
  for (PetscInt i = 0; i < n; ++i)
    for (PetscInt j = 0; j < n; ++j)
      if (block(i, j) != 0) PCSIM_PETSC(MatSetValue(P, 2 + i, 2 + j, block(i, j), INSERT_VALUES));
  PCSIM_PETSC(MatAssemblyBegin(P, MAT_FINAL_ASSEMBLY));
  PCSIM_PETSC(MatAssemblyEnd(P, MAT_FINAL_ASSEMBLY));
  return P;
}

pcsim::assembly::BlockChange change(const Eigen::MatrixXd& delta) {
  pcsim::assembly::BlockChange c;
  c.key = 7;
  c.first = 2;
  c.size = static_cast<int>(delta.rows());
  for (Eigen::Index i = 0; i < delta.rows(); ++i)
    for (Eigen::Index j = 0; j < delta.cols(); ++j) c.delta.push_back(delta(i, j));
  return c;
}

// A mechanism-like block of n unknowns: a chain (tridiagonal, unsymmetric)
// whose first unknown (a rigid-body angle) couples with every other one.
Eigen::MatrixXd chain_block(int n) {
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    a(i, i) = 4.0 + 0.01 * i;
    if (i + 1 < n) {
      a(i, i + 1) = -1.0;
      a(i + 1, i) = -1.5;
    }
    a(0, i) += 0.3;
    a(i, 0) += 0.2;
  }
  return a;
}

// x's block rows after solve_rows() for the right-hand side r_b.
Eigen::VectorXd block_solution(const VaryingBlocks& blocks, Mat P, const Eigen::VectorXd& rb) {
  Vec r, x;
  PCSIM_PETSC(MatCreateVecs(P, &x, &r));
  PCSIM_PETSC(VecSet(r, 9.0));
  for (Eigen::Index i = 0; i < rb.size(); ++i)
    PCSIM_PETSC(VecSetValue(r, 2 + static_cast<PetscInt>(i), rb[i], INSERT_VALUES));
  PCSIM_PETSC(VecAssemblyBegin(r));
  PCSIM_PETSC(VecAssemblyEnd(r));
  PCSIM_PETSC(VecSet(x, 3.0));
  blocks.solve_rows(r, x);
  const PetscScalar* xa;
  PCSIM_PETSC(VecGetArrayRead(x, &xa));
  Eigen::VectorXd xb = Eigen::Map<const Eigen::VectorXd>(xa + 2, rb.size());
  EXPECT_EQ(xa[0], 3.0);  // rows outside the block left as given
  PCSIM_PETSC(VecRestoreArrayRead(x, &xa));
  PCSIM_PETSC(VecDestroy(&r));
  PCSIM_PETSC(VecDestroy(&x));
  return xb;
}

}  // namespace

// A large block with few entries takes the sparse LU: its solution is the
// dense LU's to rounding (1e-14 of the solution, measured up to 1.0e-15 with
// KLU: 10 times for other orderings of the sums on other machines); a change
// within the analysed pattern keeps the analysis, one with a new entry
// makes a new one and still solves exactly; a block with many entries (over
// 20 %) takes the dense LU.
TEST(VaryingBlocks, LargeSparseBlockTakesTheSparseLU) {
  const int n = 64;
  const Eigen::MatrixXd j0 = chain_block(n);
  Mat P = step_matrix(j0);
  VaryingBlocks blocks;
  Eigen::MatrixXd delta = Eigen::MatrixXd::Zero(n, n);
  blocks.set({change(delta)});
  blocks.setup(P);
  EXPECT_EQ(blocks.sparse_blocks(), 1);
  EXPECT_EQ(blocks.pattern_analyses(), 1);
  const Eigen::VectorXd rb = Eigen::VectorXd::LinSpaced(n, -1.0, 2.0);
  const auto check = [&](const Eigen::MatrixXd& d) {
    const Eigen::VectorXd expected = (j0 + d).partialPivLu().solve(rb);
    const double error = (block_solution(blocks, P, rb) - expected).norm() / expected.norm();
    std::printf("  relative difference from the dense LU: %.1e\n", error);
    EXPECT_LE(error, 1e-14);
  };
  check(delta);
  for (int i = 0; i < n; ++i) delta(i, i) = 0.5 * std::sin(i);  // on the pattern
  delta(3, 4) = 0.25;
  blocks.set({change(delta)});
  EXPECT_EQ(blocks.pattern_analyses(), 1);
  check(delta);
  delta(10, 40) = 0.7;  // off the pattern: a new analysis
  blocks.set({change(delta)});
  EXPECT_EQ(blocks.pattern_analyses(), 2);
  EXPECT_EQ(blocks.sparse_blocks(), 1);
  check(delta);
  Eigen::MatrixXd full = Eigen::MatrixXd::Constant(n, n, 0.01);  // every entry: dense LU
  blocks.set({change(full)});
  EXPECT_EQ(blocks.sparse_blocks(), 0);
  check(full);
  PCSIM_PETSC(MatDestroy(&P));
}

// A block given as its sparse value (a model's sparse step tangent) solves
// as the dense LU of that value (1e-14 of the solution, as above; measured
// 3.0e-16 to 7.8e-16), keeps its
// analysis while the value's entries are where they were, analyses anew when
// one is added, and its change is the value less J0, -J0 where J0 has an
// entry the value has not, also after J0 is read anew (to rounding of the
// value: 1e-15 of |J0| + |J| times |x|, as in AddsItsChange; measured 0).
TEST(VaryingBlocks, GivenSparseValue) {
  const int n = 64;
  const Eigen::MatrixXd j0 = chain_block(n);
  Mat P = step_matrix(j0);
  Eigen::MatrixXd value = j0;
  for (int i = 0; i < n; ++i) value(i, i) += 0.5 * std::sin(i);
  value(0, 5) = 0;  // J0's entry, not in the value
  const auto given = [&](const Eigen::MatrixXd& v) {
    pcsim::assembly::BlockChange c;
    c.key = 7;
    c.first = 2;
    c.size = n;
    c.value = v.sparseView(0.0, 0.0);
    return c;
  };
  VaryingBlocks blocks;
  blocks.set({given(value)});
  blocks.setup(P);
  EXPECT_EQ(blocks.sparse_blocks(), 1);
  EXPECT_EQ(blocks.pattern_analyses(), 1);
  const Eigen::VectorXd rb = Eigen::VectorXd::LinSpaced(n, -1.0, 2.0);
  const auto check = [&](const Eigen::MatrixXd& v) {
    const Eigen::VectorXd expected = v.partialPivLu().solve(rb);
    const double error = (block_solution(blocks, P, rb) - expected).norm() / expected.norm();
    std::printf("  given value: relative difference from the dense LU %.1e\n", error);
    EXPECT_LE(error, 1e-14);
  };
  check(value);
  value(3, 4) = 0.25;  // on the pattern (J0's chain)
  blocks.set({given(value)});
  EXPECT_EQ(blocks.pattern_analyses(), 1);
  check(value);
  value(10, 40) = 0.7;  // a new entry
  blocks.set({given(value)});
  EXPECT_EQ(blocks.pattern_analyses(), 2);
  check(value);
  Vec x, y;
  PCSIM_PETSC(MatCreateVecs(P, &x, &y));
  Eigen::VectorXd xb(n);
  for (int i = 0; i < n; ++i) {
    xb[i] = std::cos(0.3 * i) - 0.2;
    PCSIM_PETSC(VecSetValue(x, 2 + i, xb[i], INSERT_VALUES));
  }
  for (Vec v : {x, y}) {
    PCSIM_PETSC(VecAssemblyBegin(v));
    PCSIM_PETSC(VecAssemblyEnd(v));
  }
  // The change against J0, then against a new J0 (J0 rebuilt: its block read
  // anew) with an entry off the value's pattern.
  Eigen::MatrixXd j0_rebuilt = j0;
  j0_rebuilt(1, 30) = 0.4;
  const Eigen::MatrixXd& j0_new = j0_rebuilt;
  Mat P_new = step_matrix(j0_new);
  for (const Eigen::MatrixXd* reference : {&j0, &j0_new}) {
    if (reference == &j0_new) {
      blocks.invalidate();
      blocks.setup(P_new);
      EXPECT_EQ(blocks.pattern_analyses(), 2);  // the value's pattern is unchanged
    }
    PCSIM_PETSC(VecSet(y, 0.0));
    blocks.add_change(x, y);
    const Eigen::VectorXd expected = (value - *reference) * xb;
    const double scale = ((reference->cwiseAbs() + value.cwiseAbs()) * xb.cwiseAbs()).maxCoeff();
    const PetscScalar* ya;
    PCSIM_PETSC(VecGetArrayRead(y, &ya));
    double error = 0;
    for (int i = 0; i < n; ++i) error = std::max(error, std::abs(ya[2 + i] - expected[i]));
    std::printf("  given value: largest difference from (J - J0) x: %.1e of the scale\n",
                error / scale);
    EXPECT_LE(error, 1e-15 * scale);
    PCSIM_PETSC(VecRestoreArrayRead(y, &ya));
  }
  PCSIM_PETSC(VecDestroy(&x));
  PCSIM_PETSC(VecDestroy(&y));
  PCSIM_PETSC(MatDestroy(&P));
  PCSIM_PETSC(MatDestroy(&P_new));
}

// The sparse factors depend on the block's value alone, not on the patterns
// seen before (a restarted run equals the uninterrupted one bitwise): blocks
// that went through other patterns solve with the same bits as a fresh one.
// (Measured: an analysis kept while the nonzeros lay on its pattern gave
// other bits here.)
TEST(VaryingBlocks, SparseFactorsDependOnTheValueAlone) {
  const int n = 64;
  const Eigen::MatrixXd j0 = chain_block(n);
  Mat P = step_matrix(j0);
  Eigen::MatrixXd wider = Eigen::MatrixXd::Zero(n, n), target = wider;
  for (int i = 1; i + 8 < n; i += 3) wider(i, (i * 37 + 11) % n) = 0.7;  // most off J0's pattern
  target(5, 6) = 0.125;                                                  // on J0's pattern
  VaryingBlocks fresh, seasoned;
  fresh.set({change(target)});
  fresh.setup(P);
  seasoned.set({change(Eigen::MatrixXd::Zero(n, n))});
  seasoned.setup(P);
  seasoned.set({change(wider)});
  seasoned.set({change(target)});
  ASSERT_EQ(fresh.sparse_blocks(), 1);
  ASSERT_EQ(seasoned.sparse_blocks(), 1);
  const Eigen::VectorXd rb = Eigen::VectorXd::LinSpaced(n, -1.0, 2.0);
  const Eigen::VectorXd a = block_solution(fresh, P, rb), b = block_solution(seasoned, P, rb);
  for (int i = 0; i < n; ++i) EXPECT_EQ(a[i], b[i]) << i;
  PCSIM_PETSC(MatDestroy(&P));
}

// A 64-row chain block set up as J0 with no change yet.
class SparseChainBlock : public ::testing::Test {
 protected:
  void SetUp() override {
    blocks.set({change(Eigen::MatrixXd::Zero(n, n))});
    blocks.setup(P);
  }
  void TearDown() override { PCSIM_PETSC(MatDestroy(&P)); }
  const int n = 64;
  const Eigen::MatrixXd j0 = chain_block(n);
  Mat P = step_matrix(j0);
  VaryingBlocks blocks;
};

// add_change() adds delta x_b to the block rows of y, for a sparse block from
// its pattern: the value less J0 there, and -J0 where an entry of J0 is now
// zero (off the pattern). To rounding of the value J0_b + delta (each entry's
// change is the value less J0, within eps of the value): 1e-15 of the sum of
// |J0_b| + |delta| times |x|, measured 5.5e-17 (2.2e-16 is one rounding).
TEST_F(SparseChainBlock, AddsItsChange) {
  Eigen::MatrixXd delta = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) delta(i, i) = 0.5 * std::sin(i) + 1e-9 * i;  // on the pattern
  delta(0, 5) = -j0(0, 5);  // J0's entry cancelled: off the new pattern
  delta(10, 40) = 0.7;      // a new entry
  blocks.set({change(delta)});
  ASSERT_EQ(blocks.sparse_blocks(), 1);
  ASSERT_EQ(blocks.pattern_analyses(), 2);
  Vec x, y;
  PCSIM_PETSC(MatCreateVecs(P, &x, &y));
  Eigen::VectorXd xb(n), yb0(n);
  for (int i = 0; i < n; ++i) {
    xb[i] = std::cos(0.3 * i) - 0.2;
    yb0[i] = 0.1 * i;
    PCSIM_PETSC(VecSetValue(x, 2 + i, xb[i], INSERT_VALUES));
    PCSIM_PETSC(VecSetValue(y, 2 + i, yb0[i], INSERT_VALUES));
  }
  for (PetscInt i = 0; i < 2; ++i) {
    PCSIM_PETSC(VecSetValue(x, i, 5.0, INSERT_VALUES));
    PCSIM_PETSC(VecSetValue(y, i, 7.0, INSERT_VALUES));
  }
  for (Vec v : {x, y}) {
    PCSIM_PETSC(VecAssemblyBegin(v));
    PCSIM_PETSC(VecAssemblyEnd(v));
  }
  blocks.add_change(x, y);
  const Eigen::VectorXd expected = yb0 + delta * xb;
  const double scale = ((j0.cwiseAbs() + delta.cwiseAbs()) * xb.cwiseAbs()).maxCoeff();
  const PetscScalar* ya;
  PCSIM_PETSC(VecGetArrayRead(y, &ya));
  EXPECT_EQ(ya[0], 7.0);  // rows outside the block left as given
  EXPECT_EQ(ya[1], 7.0);
  double error = 0;
  for (int i = 0; i < n; ++i) error = std::max(error, std::abs(ya[2 + i] - expected[i]));
  std::printf("  largest difference from delta x: %.1e of the scale\n", error / scale);
  EXPECT_LE(error, 1e-15 * scale);
  PCSIM_PETSC(VecRestoreArrayRead(y, &ya));
  PCSIM_PETSC(VecDestroy(&x));
  PCSIM_PETSC(VecDestroy(&y));
}

// The sparse LU refuses a singular or not finite block as the dense one does.
TEST_F(SparseChainBlock, RefusesASingularOrNotFiniteValue) {
  ASSERT_EQ(blocks.sparse_blocks(), 1);
  Eigen::MatrixXd singular = Eigen::MatrixXd::Zero(n, n);
  singular.row(5) = -j0.row(5);  // a zero row
  EXPECT_THROW(blocks.set({change(singular)}), pcsim::SolverError);
  Eigen::MatrixXd not_finite = Eigen::MatrixXd::Zero(n, n);
  not_finite(7, 7) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(blocks.set({change(not_finite)}), pcsim::SolverError);
  EXPECT_NO_THROW(blocks.set({change(Eigen::MatrixXd::Identity(n, n))}));
  EXPECT_EQ(blocks.sparse_blocks(), 1);
}

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
