// The sparse LU of the cheap path's varying blocks (src/solvers/klu_lu.hpp):
// each value is refactored in the pivot order of a kept reference (the
// block's J0 value) while that order stays stable, else factored with pivots
// of its own; either way the factors are a function of the value and the
// reference alone, never of the values factored before (a restarted run
// computes the bits of an uninterrupted one).
#include <gtest/gtest.h>

#include <Eigen/SparseCore>
#include <cmath>

#include "../../src/solvers/klu_lu.hpp"

namespace {

using pcsim::solvers::KluLU;

// An unsymmetric chain of n unknowns whose first one couples with every other
// one (as the flexible DSA-380's rigid-body angle with its beams), scaled
// column by column by 1 + 'change' sin(j): a reference and values near it.
Eigen::SparseMatrix<double> chain(int n, double change, double diagonal = 4.0) {
  Eigen::SparseMatrix<double> a(n, n);
  for (int j = 0; j < n; ++j) {
    const double s = 1 + change * std::sin(j + 1.0);
    a.insert(j, j) = s * (diagonal + 0.01 * j);
    if (j > 0) a.insert(j - 1, j) = -s;
    if (j + 1 < n) a.insert(j + 1, j) = -1.5 * s;
    if (j > 1) a.insert(0, j) = 0.3 * s;
    if (j > 1) a.coeffRef(j, 0) += 0.2;
  }
  a.makeCompressed();
  return a;
}

Eigen::VectorXd solution(const KluLU& lu, int n) {
  Eigen::VectorXd x(n);
  lu.solve(Eigen::VectorXd::LinSpaced(n, -1.0, 2.0), x);
  return x;
}

constexpr int kN = 40;

// A value near the reference takes the kept order, and its factors are those
// of a factorisation that pivots anew (the same pivots, the same arithmetic):
// the same bits.
TEST(KluLU, KeptOrderGivesTheBitsOfAFreshFactorisation) {
  const auto reference = chain(kN, 0.0), value = chain(kN, 1e-3);
  KluLU kept, fresh;
  kept.analyze(reference);
  kept.keep_pivots_of(reference);
  fresh.analyze(reference);
  ASSERT_TRUE(kept.factor(value));
  ASSERT_TRUE(fresh.factor(value));
  EXPECT_TRUE(kept.refactored());
  EXPECT_FALSE(fresh.refactored());
  const Eigen::VectorXd a = solution(kept, kN), b = solution(fresh, kN);
  for (int i = 0; i < kN; ++i) EXPECT_EQ(a[i], b[i]) << i;
}

// The reference's diagonal with nearly zero entries: the reference's
// (diagonal) pivots would grow without bound.
Eigen::SparseMatrix<double> tiny_diagonal(const Eigen::SparseMatrix<double>& reference) {
  auto value = reference;
  for (int j = 0; j < value.cols(); ++j) value.coeffRef(j, j) = 1e-9;
  return value;
}

// A value on which the kept order's pivots would grow without bound is
// factored with pivots of its own, and solves to round-off.
TEST(KluLU, AnUnstableOrderIsRefactoredWithPivotsOfItsOwn) {
  const auto reference = chain(kN, 0.0);
  const auto value = tiny_diagonal(reference);
  KluLU lu;
  lu.analyze(reference);
  lu.keep_pivots_of(reference);
  ASSERT_TRUE(lu.factor(value));
  EXPECT_FALSE(lu.refactored());
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(kN, -1.0, 2.0);
  const Eigen::VectorXd x = solution(lu, kN);
  // Backward error to round-off: measured 6.0e-16 of |A| |x|; asserted
  // 5e-15, about n u (40 unknowns), the bound of an LU whose growth is
  // bounded, as its own pivots keep it.
  EXPECT_LT((value * x - b).norm(), 5e-15 * value.norm() * x.norm());
}

// The factors of a value do not depend on what was factored before: after
// an unstable value (pivots of its own) and a singular one (refused), the
// kept order serves again, with the bits of a fresh object.
TEST(KluLU, FactorsDoNotDependOnEarlierValues) {
  const auto reference = chain(kN, 0.0), value = chain(kN, 2e-3);
  const auto unstable = tiny_diagonal(reference);
  auto singular = reference;
  for (Eigen::SparseMatrix<double>::InnerIterator it(singular, 3); it; ++it) it.valueRef() = 0;
  KluLU seasoned, fresh;
  for (KluLU* lu : {&seasoned, &fresh}) {
    lu->analyze(reference);
    lu->keep_pivots_of(reference);
  }
  ASSERT_TRUE(seasoned.factor(unstable));
  EXPECT_FALSE(seasoned.factor(singular));
  EXPECT_TRUE(std::isnan(solution(seasoned, kN)[0]));  // no factors: no solution
  ASSERT_TRUE(seasoned.factor(value));
  ASSERT_TRUE(fresh.factor(value));
  EXPECT_TRUE(seasoned.refactored());
  const Eigen::VectorXd a = solution(seasoned, kN), b = solution(fresh, kN);
  for (int i = 0; i < kN; ++i) EXPECT_EQ(a[i], b[i]) << i;
}

// A singular reference keeps no order: each value pivots anew.
TEST(KluLU, ASingularReferenceKeepsNoOrder) {
  auto reference = chain(kN, 0.0);
  for (Eigen::SparseMatrix<double>::InnerIterator it(reference, 5); it; ++it) it.valueRef() = 0;
  KluLU lu;
  lu.analyze(reference);
  lu.keep_pivots_of(reference);
  ASSERT_TRUE(lu.factor(chain(kN, 1e-3)));
  EXPECT_FALSE(lu.refactored());
}

}  // namespace
