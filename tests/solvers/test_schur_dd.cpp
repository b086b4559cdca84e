// The exact domain-decomposition step solver (solvers/schur_dd.hpp) against
// known solutions: a nonsymmetric block chain (the shape of a catenary's
// step matrix: 6 unknowns per node, neighbours coupled) with a few "extra"
// unknowns on the last rank coupled to nodes anywhere (the pantographs), on
// 1, 2 and 3 ranks. It must be a direct solve: one application of the PC
// gives x to round-off, and the same x on any number of ranks. And the
// interface factorisation alone (src/solvers/interface_solve.hpp) on the
// Schur complement of a chain of 9 parts numbered out of track order. And
// the interior correction's sparse copy (negligible_entries.hpp).
// pcsim-test-ranks: 1 2 3
#include <gtest/gtest.h>
#include <petscksp.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <vector>

#include "../../src/solvers/interface_solve.hpp"
#include "../../src/solvers/negligible_entries.hpp"
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
  // S is stored sparse (measured 166 of 14^2 entries on 2 ranks, 411 of 28^2
  // on 3) and ordered banded (13, 19: the extras couple across the chain).
  if (size > 1) {
    EXPECT_GE(info.interface_nonzeros, info.interface_size);  // the diagonal
    EXPECT_LT(info.interface_nonzeros, info.interface_size * info.interface_size);
    EXPECT_GT(info.interface_bandwidth, 0);
    EXPECT_LT(info.interface_bandwidth, info.interface_size);
  }

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

// The Schur complement of a catenary cut into parts along the track: part p
// has 12 interface unknowns at each of its cuts (two wires' nodes, 6 each),
// all coupled with each other (dense: through the part's interior), and
// each node with its neighbour across the cut (6 x 6). The parts are numbered
// (as METIS may number them) out of track order, G numbered part by part.
constexpr int kParts = 9, kSide = 12;
constexpr int kPartNumber[kParts] = {4, 0, 7, 2, 8, 1, 5, 3, 6};  // along the track

struct ChainSchur {
  pcsim::solvers::InterfaceRows S;
  Eigen::MatrixXd dense;
};

ChainSchur chain_schur(double shift) {
  std::vector<int> position(kParts), first(kParts + 1, 0);  // G numbers of part
  for (int k = 0; k < kParts; ++k) position[kPartNumber[k]] = k;
  for (int p = 0; p < kParts; ++p) {
    const int cuts = (position[p] > 0) + (position[p] < kParts - 1);
    first[p + 1] = first[p] + cuts * kSide;
  }
  const int n = first[kParts];
  Eigen::MatrixXd S = Eigen::MatrixXd::Zero(n, n);
  for (int p = 0; p < kParts; ++p)  // each part's block, dense
    for (int i = first[p]; i < first[p + 1]; ++i)
      for (int j = first[p]; j < first[p + 1]; ++j) S(i, j) = i == j ? 50.0 + shift : pseudo(i, j);
  for (int k = 0; k + 1 < kParts; ++k) {  // the cut between parts k and k + 1 along the track
    const int left = kPartNumber[k], right = kPartNumber[k + 1];
    const int a = first[left + 1] - kSide, b = first[right];  // their sides of the cut
    for (int i = 0; i < kSide; ++i)
      for (int j = i / 6 * 6; j < i / 6 * 6 + 6; ++j) {
        S(a + i, b + j) = pseudo(a + i, b + j);
        S(b + j, a + i) = pseudo(b + j, a + i);
      }
  }
  ChainSchur c{{}, S};
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j)
      if (S(i, j) != 0.0) {
        c.S.columns.push_back(j);
        c.S.values.push_back(S(i, j));
      }
    c.S.starts.push_back(static_cast<PetscInt>(c.S.columns.size()));
  }
  return c;
}

TEST(SchurDomainDecomposition, InterfaceFactorIsBandedAndExact) {
  pcsim::solvers::InterfaceFactor lu;
  for (const double shift : {0.0, 7.0}) {  // a new factorisation, then new values only
    const ChainSchur c = chain_schur(shift);
    const PetscInt n = c.S.rows();
    ASSERT_EQ(n, 2 * kSide * (kParts - 1));
    lu.factor(c.S, shift != 0.0);
    Eigen::VectorXd x_true(n), x(n);
    for (PetscInt i = 0; i < n; ++i) x_true(i) = 1.0 + pseudo(i, 3 * i);
    const Eigen::VectorXd b = c.dense * x_true;
    lu.solve(b.data(), x.data());
    const Eigen::VectorXd reference = c.dense.partialPivLu().solve(b);  // dense LU
    // Diagonally dominant (Gershgorin: condition below 4): ~1e-15 relative.
    EXPECT_LT((x - reference).lpNorm<Eigen::Infinity>() / x_true.lpNorm<Eigen::Infinity>(), 1e-13);
    EXPECT_LT((x - x_true).lpNorm<Eigen::Infinity>() / x_true.lpNorm<Eigen::Infinity>(), 1e-13);
  }
  // As numbered, S's bandwidth spans several parts (measured 161 of 191).
  // A part's block is a clique of 24 unknowns: no order has a bandwidth
  // below 23, which is reached along the track (each part's 24 together, a
  // cut's 12 + 12 next to each other). Reverse Cuthill-McKee on the pattern,
  // measured 23: asserted within one node (6 unknowns) of it, room for its
  // tie-breaking (where it starts); independent of the number of cuts.
  const ChainSchur c = chain_schur(0.0);
  PetscInt as_numbered = 0;
  for (PetscInt i = 0; i < c.S.rows(); ++i)
    for (PetscInt k = c.S.starts[i]; k < c.S.starts[i + 1]; ++k)
      as_numbered = std::max(as_numbered, std::abs(c.S.columns[k] - i));
  EXPECT_GT(as_numbered, 4 * (2 * kSide));
  EXPECT_GE(lu.bandwidth(), 2 * kSide - 1);
  EXPECT_LE(lu.bandwidth(), 2 * kSide - 1 + 6);
  EXPECT_EQ(lu.nonzeros(), static_cast<PetscInt>(c.S.columns.size()));
  EXPECT_GE(lu.factor_nonzeros(), static_cast<double>(lu.nonzeros()));
}

// The sparse copy keeps exactly the entries above 1e-18 of their column's
// largest magnitude (1e-18 itself is left out), with their values, and its
// product moves by at most 1e-18 of each column's largest term beyond the
// rounding of the sums.
TEST(SchurDomainDecomposition, CorrectionKeepsAllButNegligibleEntries) {
  constexpr PetscInt kRows = 80, kCols = 3;  // 37 of 80 rows kept: sparse
  Mat dense = nullptr;
  PCSIM_PETSC(MatCreateSeqDense(PETSC_COMM_SELF, kRows, kCols, nullptr, &dense));
  Eigen::MatrixXd values(kRows, kCols);
  const double largest[kCols] = {2.0, -3e-4, 7e10};
  for (PetscInt j = 0; j < kCols; ++j)
    for (PetscInt i = 0; i < kRows; ++i) {
      // A decay as along a wire: 10^-(i/2) of the column's largest, sign alternating.
      values(i, j) = largest[j] * std::pow(10.0, -0.5 * i) * (i % 2 ? -1.0 : 1.0);
      if (i == 36) values(i, j) = largest[j] * 1e-18;     // exactly at the limit: left out
      if (i == 37) values(i, j) = largest[j] * 1.01e-18;  // just above: kept
    }
  for (PetscInt j = 0; j < kCols; ++j)
    for (PetscInt i = 0; i < kRows; ++i)
      PCSIM_PETSC(MatSetValue(dense, i, j, values(i, j), INSERT_VALUES));
  PCSIM_PETSC(MatAssemblyBegin(dense, MAT_FINAL_ASSEMBLY));
  PCSIM_PETSC(MatAssemblyEnd(dense, MAT_FINAL_ASSEMBLY));
  double entries = 0, kept = 0;
  Mat sparse = dense;
  pcsim::solvers::drop_negligible(&sparse, &entries, &kept);
  PetscBool aij = PETSC_FALSE;
  PCSIM_PETSC(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(sparse), MATSEQAIJ, &aij));
  EXPECT_TRUE(aij);
  EXPECT_EQ(entries, kRows * kCols);
  // Rows 0..36 are at least 10^-18 (row 36 set to exactly that: out), row 37 in.
  EXPECT_EQ(kept, kCols * 37.0);
  Eigen::VectorXd x(kCols), product(kRows);
  x << 1.0, -2.0, 1e-9;
  Vec xv, yv;
  PCSIM_PETSC(VecCreateSeq(PETSC_COMM_SELF, kCols, &xv));
  PCSIM_PETSC(VecCreateSeq(PETSC_COMM_SELF, kRows, &yv));
  for (PetscInt j = 0; j < kCols; ++j) PCSIM_PETSC(VecSetValue(xv, j, x(j), INSERT_VALUES));
  PCSIM_PETSC(VecAssemblyBegin(xv));
  PCSIM_PETSC(VecAssemblyEnd(xv));
  PCSIM_PETSC(MatMult(sparse, xv, yv));
  const PetscScalar* y;
  PCSIM_PETSC(VecGetArrayRead(yv, &y));
  const Eigen::VectorXd exact = values * x;
  double largest_term = 0;
  for (PetscInt j = 0; j < kCols; ++j)
    largest_term = std::max(largest_term, std::abs(largest[j] * x(j)));
  // Dropped: at most 1e-18 of each column's largest term; and the sums'
  // rounding (3 terms: 4 u of their magnitudes).
  const Eigen::VectorXd magnitudes = values.cwiseAbs() * x.cwiseAbs();
  for (PetscInt i = 0; i < kRows; ++i) {
    EXPECT_LE(std::abs(y[i] - exact(i)), 1e-18 * kCols * largest_term + 4 * 1.1e-16 * magnitudes(i))
        << "row " << i;
    PetscInt n;
    const PetscInt* cols;
    const PetscScalar* vals;
    PCSIM_PETSC(MatGetRow(sparse, i, &n, &cols, &vals));
    for (PetscInt k = 0; k < n; ++k) EXPECT_EQ(vals[k], values(i, cols[k]));
    EXPECT_EQ(n, i < 36 || i == 37 ? kCols : 0) << "row " << i;
    PCSIM_PETSC(MatRestoreRow(sparse, i, &n, &cols, &vals));
  }
  PCSIM_PETSC(VecRestoreArrayRead(yv, &y));
  for (Vec* v : {&xv, &yv}) PCSIM_PETSC(VecDestroy(v));
  PCSIM_PETSC(MatDestroy(&sparse));

  // More than half kept: the matrix stays as it is (dense, every entry).
  Mat full = nullptr;
  PCSIM_PETSC(MatCreateSeqDense(PETSC_COMM_SELF, 4, 2, nullptr, &full));
  for (PetscInt i = 0; i < 4; ++i)
    for (PetscInt j = 0; j < 2; ++j)
      PCSIM_PETSC(MatSetValue(full, i, j, i < 3 ? 1.0 + i + j : 0.0, INSERT_VALUES));
  PCSIM_PETSC(MatAssemblyBegin(full, MAT_FINAL_ASSEMBLY));
  PCSIM_PETSC(MatAssemblyEnd(full, MAT_FINAL_ASSEMBLY));
  Mat same = full;
  pcsim::solvers::drop_negligible(&same, &entries, &kept);
  EXPECT_EQ(same, full);
  EXPECT_EQ(entries, 8.0);
  EXPECT_EQ(kept, 8.0);
  PCSIM_PETSC(MatDestroy(&full));
}

}  // namespace
