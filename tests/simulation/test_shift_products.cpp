// A moving window's shift products G = V^T M S V (src/simulation/
// modal_shift.cpp) over 600 vectors (three blocks of 256 columns, the last
// partly filled), on 1 and 2 ranks, against the products taken one by one
// (VecMDot of M S v_j with every v_i):
//  - with the full blocks on an unlinked file in a folder (VectorStore) and
//    all in memory: the same bits, and nothing left in the folder;
//  - computed in two steps (300 vectors, then 300 more: the rows and columns
//    of the new ones only, as a raised cut-off's modes) as at once;
//  - a folder that takes no file keeps the vectors in memory, and a block that
//    cannot be written (a file size limit: a full disk) stays in memory;
//  - take() moves out the products compute() gave, bit for bit, and no
//    compute() follows it until they are given back (a raise's, read from
//    the cache): then the new vectors' products, the same bits as kept;
//  - the products over the nonzero rows only (nonzero_row_ranges,
//    product_tn_rows) equal those over every row.
// pcsim-test-ranks: 1 2
#include <gtest/gtest.h>
#include <petscmat.h>
#include <sys/resource.h>
#include <unistd.h>

#include <Eigen/Core>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "../../src/simulation/modal_basis_internal.hpp"

namespace {

using pcsim::simulation::modal_detail::ShiftProducts;
using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

constexpr PetscInt kSize = 500, kShift = 12, kVectors = 600;

// Deterministic entries in (-1, 1), different for every (i, j).
double pseudo(PetscInt i, PetscInt j) {
  return std::sin(0.37 * static_cast<double>(i) + 1.71 * static_cast<double>(j) + 0.3);
}

class ShiftProductsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    // M: a symmetric positive tridiagonal mass; S(g, g + kShift) = 1 (the
    // displacement moved back by kShift unknowns, zero at the front).
    for (Mat* A : {&M_, &S_}) {
      PetscCallAbort(PETSC_COMM_WORLD, MatCreateAIJ(PETSC_COMM_WORLD, PETSC_DECIDE, PETSC_DECIDE,
                                                    kSize, kSize, 3, nullptr, 2, nullptr, A));
    }
    PetscInt lo, hi;
    PetscCallAbort(PETSC_COMM_WORLD, MatGetOwnershipRange(M_, &lo, &hi));
    for (PetscInt g = lo; g < hi; ++g) {
      MatSetValue(M_, g, g, 4.0 + 0.01 * static_cast<double>(g % 7), INSERT_VALUES);
      if (g > 0) MatSetValue(M_, g, g - 1, 1.0, INSERT_VALUES);
      if (g + 1 < kSize) MatSetValue(M_, g, g + 1, 1.0, INSERT_VALUES);
      if (g + kShift < kSize) MatSetValue(S_, g, g + kShift, 1.0, INSERT_VALUES);
    }
    for (Mat A : {M_, S_}) {
      MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY);
      MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY);
    }
    vectors_.resize(kVectors);
    for (PetscInt k = 0; k < kVectors; ++k) {
      MatCreateVecs(M_, &vectors_[k], nullptr);
      for (PetscInt g = lo; g < hi; ++g) VecSetValue(vectors_[k], g, pseudo(g, k), INSERT_VALUES);
      VecAssemblyBegin(vectors_[k]);
      VecAssemblyEnd(vectors_[k]);
    }
    dir_ = std::filesystem::temp_directory_path() / ("pcsim-shift-" + std::to_string(getpid()));
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override {
    for (Vec& v : vectors_) VecDestroy(&v);
    MatDestroy(&M_);
    MatDestroy(&S_);
    std::filesystem::remove_all(dir_);
  }
  // G(i, j) = v_i^T M S v_j, one column at a time.
  RowMajor one_by_one() const {
    RowMajor G(kVectors, kVectors);
    Vec shifted, w;
    MatCreateVecs(M_, &shifted, &w);
    std::vector<PetscScalar> dots(kVectors);
    for (PetscInt j = 0; j < kVectors; ++j) {
      MatMult(S_, vectors_[j], shifted);
      MatMult(M_, shifted, w);
      VecMDot(w, kVectors, vectors_.data(), dots.data());
      for (PetscInt i = 0; i < kVectors; ++i) G(i, j) = dots[i];
    }
    VecDestroy(&shifted);
    VecDestroy(&w);
    return G;
  }
  // The products over vectors [0, split) computed first (kept for a later
  // compute), then over all of them.
  RowMajor products(const std::string& dir, PetscInt split, long* spilled = nullptr) const {
    ShiftProducts products(M_, S_, dir);
    for (PetscInt k = 0; k < split; ++k) products.append(vectors_[k]);
    if (split < kVectors) {
      products.compute(vectors_[0], true);
      for (PetscInt k = split; k < kVectors; ++k) products.append(vectors_[k]);
    }
    if (spilled) *spilled = products.spilled_blocks();
    return products.compute(vectors_[0], false);
  }
  Mat M_ = nullptr, S_ = nullptr;
  std::vector<Vec> vectors_;
  std::filesystem::path dir_;
};

double relative_difference(const RowMajor& a, const RowMajor& b) {
  return (a - b).cwiseAbs().maxCoeff() / b.cwiseAbs().maxCoeff();
}

TEST_F(ShiftProductsTest, OnFileAndInMemoryGiveTheSameBits) {
  long spilled = 0;
  const RowMajor on_file = products(dir_.string(), kVectors, &spilled);
  EXPECT_EQ(spilled, 2);                         // the two full blocks
  EXPECT_TRUE(std::filesystem::is_empty(dir_));  // unlinked when made
  const RowMajor in_memory = products("", kVectors);
  EXPECT_EQ((on_file - in_memory).cwiseAbs().maxCoeff(), 0.0);
  // Against VecMDot's sums: round-off of sums of 500 terms (~1e-16 each).
  EXPECT_LT(relative_difference(on_file, one_by_one()), 1e-13);
}

TEST_F(ShiftProductsTest, TwoStepsEqualAtOnce) {
  const RowMajor at_once = products(dir_.string(), kVectors);
  for (PetscInt split : {300, 256, 100}) {  // a block's middle, its end, the first block
    const RowMajor in_steps = products(dir_.string(), split);
    // Only the order of the sums differs (G(new, old) as (S^T M v_i)^T v_j).
    EXPECT_LT(relative_difference(in_steps, at_once), 1e-13) << "split " << split;
  }
  EXPECT_TRUE(std::filesystem::is_empty(dir_));
}

TEST_F(ShiftProductsTest, AFolderThatTakesNoFileKeepsThemInMemory) {
  long spilled = 1;
  const RowMajor G = products("/proc/pcsim-no-such-folder", kVectors, &spilled);
  EXPECT_EQ(spilled, 0);
  const RowMajor in_memory = products("", kVectors);
  EXPECT_EQ((G - in_memory).cwiseAbs().maxCoeff(), 0.0);
  // Files of at most 1.5 blocks: the second block's write fails (EFBIG; the
  // signal ignored), and it stays in memory.
  PetscInt local;
  PetscCallAbort(PETSC_COMM_WORLD, VecGetLocalSize(vectors_[0], &local));
  struct rlimit before {};
  getrlimit(RLIMIT_FSIZE, &before);
  struct rlimit limit = before;
  limit.rlim_cur = static_cast<rlim_t>(local) * 256 * sizeof(double) * 3 / 2;
  const auto handler = std::signal(SIGXFSZ, SIG_IGN);
  setrlimit(RLIMIT_FSIZE, &limit);
  const RowMajor part = products(dir_.string(), kVectors, &spilled);
  setrlimit(RLIMIT_FSIZE, &before);
  std::signal(SIGXFSZ, handler);
  EXPECT_EQ(spilled, 1);
  EXPECT_EQ((part - in_memory).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_TRUE(std::filesystem::is_empty(dir_));
}

TEST_F(ShiftProductsTest, TakeMovesOutTheProductsComputed) {
  const RowMajor computed = products(dir_.string(), 300);
  ShiftProducts products(M_, S_, dir_.string());
  for (PetscInt k = 0; k < 300; ++k) products.append(vectors_[k]);
  products.compute(vectors_[0], true);
  for (PetscInt k = 300; k < kVectors; ++k) products.append(vectors_[k]);
  EXPECT_THROW(products.take(), std::exception);  // the new vectors' products not computed
  products.compute(vectors_[0], false);
  const std::vector<double> taken = products.take();
  ASSERT_EQ(taken.size(), static_cast<std::size_t>(kVectors * kVectors));
  const RowMajor G = Eigen::Map<const RowMajor>(taken.data(), kVectors, kVectors);
  EXPECT_EQ((G - computed).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_THROW(products.compute(vectors_[0], false), std::exception);
}

TEST_F(ShiftProductsTest, GivenBackTheyGrowAsKept) {
  const RowMajor kept = products(dir_.string(), 300);
  ShiftProducts products(M_, S_, dir_.string());
  for (PetscInt k = 0; k < 300; ++k) products.append(vectors_[k]);
  products.compute(vectors_[0], true);
  std::vector<double> first = products.take();
  EXPECT_THROW(products.give_back(std::vector<double>(7)), std::exception);  // not G's size
  products.give_back(std::move(first));
  for (PetscInt k = 300; k < kVectors; ++k) products.append(vectors_[k]);
  const RowMajor grown = products.compute(vectors_[0], false);
  EXPECT_EQ((grown - kept).cwiseAbs().maxCoeff(), 0.0);
}

// The products over W's nonzero rows only (the window's front spans): zero
// rows at the start, in the middle and at the end skipped, and a W without
// nonzero rows gives zeros, against the products over every row.
TEST(ShiftProductRows, SkipOnlyZeroRows) {
  using pcsim::simulation::modal_detail::nonzero_row_ranges;
  using pcsim::simulation::modal_detail::product_tn_rows;
  constexpr long kRows = 40, kW = 3, kV = 5;
  Eigen::MatrixXd W(kRows, kW), V(kRows, kV);
  for (long i = 0; i < kRows; ++i) {
    for (long j = 0; j < kW; ++j) W(i, j) = pseudo(i, j);
    for (long j = 0; j < kV; ++j) V(i, j) = pseudo(i, j + 7);
  }
  for (long i : {0L, 1L, 17L, 18L, 19L, 39L}) W.row(i).setZero();
  W(25, 0) = 0.0;  // a row zero in one column only stays
  const auto rows = nonzero_row_ranges(W, 0, kW);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].begin, 2);
  EXPECT_EQ(rows[0].end, 17);
  EXPECT_EQ(rows[1].begin, 20);
  EXPECT_EQ(rows[1].end, 39);
  EXPECT_EQ(nonzero_row_ranges(W, 1, kW).size(), 2u);  // from column 1 on: the same rows
  // Column 0 alone: row 25 is zero there, a third run of rows.
  EXPECT_EQ(nonzero_row_ranges(W, 0, 1).size(), 3u);
  Eigen::MatrixXd C(kW, kV);
  product_tn_rows(kW, kV, rows, W.data(), kRows, V.data(), kRows, C.data(), kW);
  const Eigen::MatrixXd all = W.transpose() * V;
  // The same sums in another grouping: round-off of 40 terms.
  EXPECT_LT((C - all).cwiseAbs().maxCoeff(), 1e-14 * all.cwiseAbs().maxCoeff());
  C.setConstant(7.0);
  product_tn_rows(kW, kV, nonzero_row_ranges(Eigen::MatrixXd::Zero(kRows, kW), 0, kW), W.data(),
                  kRows, V.data(), kRows, C.data(), kW);
  EXPECT_EQ(C.cwiseAbs().maxCoeff(), 0.0);
}

}  // namespace
