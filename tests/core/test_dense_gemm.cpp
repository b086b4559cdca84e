// dense_gemm: C = alpha op(A) op(B) + beta C by the BLAS, against Eigen's
// product, for each transposition, with leading dimensions wider than the
// blocks, an accumulating beta, a row-major product through the transposes,
// and k = 0 (no terms: C = beta C).
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "pcsim/core/dense_gemm.hpp"

namespace {

using Matrix = Eigen::MatrixXd;
using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// A sum of k products of entries in [-1, 1]: its round-off in another order
// is within k * 2^-52 of each term's scale; 1e-13 holds that for k <= 64
// with a margin of 30, and a wrong index or transposition is off by O(1).
constexpr double kTolerance = 1e-13;

void check(bool ta, bool tb, long m, long n, long k) {
  std::srand(3);
  const Matrix A = Matrix::Random(ta ? k + 2 : m + 2, ta ? m : k);  // 2 rows beyond: lda wider
  const Matrix B = Matrix::Random(tb ? n + 1 : k + 1, tb ? k : n);
  const Matrix C0 = Matrix::Random(m + 3, n);
  const Matrix opA = ta ? Matrix(A.topRows(k).transpose()) : Matrix(A.topRows(m));
  const Matrix opB = tb ? Matrix(B.topRows(n).transpose()) : Matrix(B.topRows(k));
  Matrix C = C0;
  pcsim::dense_gemm(ta, tb, m, n, k, 0.5, A.data(), A.rows(), B.data(), B.rows(), -2.0, C.data(),
                    C.rows());
  const Matrix expected = 0.5 * opA * opB - 2.0 * C0.topRows(m);
  EXPECT_LE((C.topRows(m) - expected).cwiseAbs().maxCoeff(), kTolerance)
      << "transpose " << ta << tb << ", " << m << " x " << n << " x " << k;
  EXPECT_EQ(C.bottomRows(3), C0.bottomRows(3)) << "rows beyond m written";
}

}  // namespace

TEST(DenseGemm, EachTranspositionAgainstEigen) {
  for (bool ta : {false, true})
    for (bool tb : {false, true}) check(ta, tb, 7, 5, 64);
}

TEST(DenseGemm, RowMajorProductThroughTheTransposes) {
  std::srand(5);
  const RowMatrix A = RowMatrix::Random(6, 9), B = RowMatrix::Random(9, 4);
  RowMatrix C(6, 4);
  // Row-major C = A B is column-major C^T = B^T A^T: each operand as stored.
  pcsim::dense_gemm(false, false, 4, 6, 9, 1.0, B.data(), 4, A.data(), 9, 0.0, C.data(), 4);
  EXPECT_LE((C - A * B).cwiseAbs().maxCoeff(), kTolerance);
}

TEST(DenseGemm, NoTermsScalesC) {
  Matrix C = Matrix::Constant(3, 2, 4.0);
  pcsim::dense_gemm(false, false, 3, 2, 0, 1.0, nullptr, 3, nullptr, 1, 0.5, C.data(), 3);
  EXPECT_EQ(C, Matrix::Constant(3, 2, 2.0));
  pcsim::dense_gemm(false, false, 3, 2, 0, 1.0, nullptr, 3, nullptr, 1, 0.0, C.data(), 3);
  EXPECT_EQ(C, Matrix::Zero(3, 2));
}
