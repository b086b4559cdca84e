// The cheap path's step solver (solvers/low_rank.hpp) on a J0 whose pattern
// is block diagonal with small blocks (the reduced-order catenary's: its modes
// and the pantographs' blocks) inverts J0 block by block; the solve of
// J0 + sum c u u^T (a dense u over every unknown, as a modal contact row, and a
// sparse one) then equals a dense LU solve of the same matrix to round-off
// (asserted 1e-12 relative: the matrix is well conditioned, measured ~1e-16).
// A J0 coupling its blocks into one of more than 32 rows is factored by the
// inner KSP as before, to the same accuracy. When only some terms change
// between solves (a moving contact's row; a window end's dashpots stay), the
// capacitance's rows and columns of the others are kept: the solution has the
// same bits as a new solver's with the same terms. A varying block (a
// nonlinear pantograph's, here of 35 rows on the last rank) is left out of
// the block inverse whatever its size, and its own LU solves its rows: the
// solution equals the dense LU's of J0 + delta + sum c u u^T to the same 1e-12.
// A J0 inverted by blocks and equal to its transpose bit for bit makes the
// capacitance form each pair of terms' product once, u_a . J0^-1 u_b (a before b), for both its
// entries: the same exactness, the same bits kept and fresh, and the set
// changes and rows counted alike.
// On 1 and 2 ranks (each rank's rows hold whole blocks).
// pcsim-test-ranks: 1 2
#include <gtest/gtest.h>
#include <petscksp.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <vector>

#include "pcsim/core/error.hpp"
#include "pcsim/solvers/direct.hpp"
#include "pcsim/solvers/low_rank.hpp"

namespace {

constexpr PetscInt kLocal = 42;  // rows per rank: blocks of 1, 2, 1, 3, repeated

// Block of local row r (its first row and size) in the pattern 1, 2, 1, 3.
void block_of(PetscInt r, PetscInt& first, PetscInt& size) {
  const PetscInt starts[] = {0, 1, 3, 4, 7};
  const PetscInt period = r / 7 * 7;
  for (int b = 0; b < 4; ++b)
    if (r - period < starts[b + 1]) {
      first = period + starts[b];
      size = starts[b + 1] - starts[b];
      return;
    }
}

// J0(i, j) for global i, j (deterministic, diagonally dominant); 'coupled'
// adds the neighbours of every row within its rank (one block per rank);
// 'symmetric' makes the blocks' entries J0(j, i) = J0(i, j).
double entry(PetscInt i, PetscInt j, bool coupled, bool symmetric = false) {
  const PetscInt ri = i % kLocal, rj = j % kLocal;
  PetscInt first, size;
  block_of(ri, first, size);
  const bool same_block = i / kLocal == j / kLocal && rj >= first && rj < first + size;
  if (i == j) return 10.0 + 0.7 * static_cast<double>(i);
  if (same_block) return 1.0 + 0.1 * static_cast<double>(symmetric ? i + j : i + 2 * j);
  if (coupled && i / kLocal == j / kLocal && (j == i + 1 || i == j + 1)) return 0.5;
  return 0.0;
}

// An n x n matrix of kLocal rows per rank with the entries value(i, j).
template <class Value>
Mat make_matrix(PetscInt n, Value value) {
  Mat J0;
  PCSIM_PETSC(
      MatCreateAIJ(PETSC_COMM_WORLD, kLocal, kLocal, n, n, kLocal, nullptr, kLocal, nullptr, &J0));
  PetscInt lo, hi;
  PCSIM_PETSC(MatGetOwnershipRange(J0, &lo, &hi));
  for (PetscInt i = lo; i < hi; ++i)
    for (PetscInt j = 0; j < n; ++j)
      if (value(i, j) != 0) PCSIM_PETSC(MatSetValue(J0, i, j, value(i, j), INSERT_VALUES));
  PCSIM_PETSC(MatAssemblyBegin(J0, MAT_FINAL_ASSEMBLY));
  PCSIM_PETSC(MatAssemblyEnd(J0, MAT_FINAL_ASSEMBLY));
  return J0;
}

// J0 over kLocal rows per rank (entry()); n its global size.
Mat make_j0(bool coupled, PetscInt& n, bool symmetric = false) {
  int size;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  n = kLocal * size;
  return make_matrix(
      n, [coupled, symmetric](PetscInt i, PetscInt j) { return entry(i, j, coupled, symmetric); });
}

// The step solver as a PC of a KSP that applies it once.
KSP preonly_ksp(pcsim::solvers::LowRankStepSolver& solver, Mat J0) {
  KSP ksp;
  PC pc;
  PCSIM_PETSC(KSPCreate(PETSC_COMM_WORLD, &ksp));
  PCSIM_PETSC(KSPSetType(ksp, KSPPREONLY));
  PCSIM_PETSC(KSPGetPC(ksp, &pc));
  solver.install(pc);
  PCSIM_PETSC(KSPSetOperators(ksp, solver.op(), J0));
  return ksp;
}

// b_i = cos(0.3 i), and x of the same layout.
void right_hand_side(Mat J0, Vec* x, Vec* b) {
  PCSIM_PETSC(MatCreateVecs(J0, x, b));
  PetscInt lo, hi;
  PCSIM_PETSC(VecGetOwnershipRange(*b, &lo, &hi));
  for (PetscInt i = lo; i < hi; ++i)
    PCSIM_PETSC(VecSetValue(*b, i, std::cos(0.3 * static_cast<double>(i)), INSERT_VALUES));
  PCSIM_PETSC(VecAssemblyBegin(*b));
  PCSIM_PETSC(VecAssemblyEnd(*b));
}

// The largest difference of x from the dense LU's solution of
// (A + sum c u u^T) x = b (b of right_hand_side()), relative to its largest
// entry, over every rank.
double error_against_dense(Eigen::MatrixXd A, const std::vector<pcsim::assembly::RankOne>& terms,
                           Vec x) {
  const auto n = static_cast<PetscInt>(A.rows());
  Eigen::VectorXd rhs(n);
  for (PetscInt i = 0; i < n; ++i) rhs[i] = std::cos(0.3 * static_cast<double>(i));
  for (const auto& t : terms) {
    Eigen::VectorXd u = Eigen::VectorXd::Zero(n);
    for (std::size_t k = 0; k < t.index.size(); ++k) u[t.index[k]] = t.weight[k];
    A += t.coefficient * u * u.transpose();
  }
  const Eigen::VectorXd expected = A.lu().solve(rhs);
  PetscInt lo, hi;
  PCSIM_PETSC(VecGetOwnershipRange(x, &lo, &hi));
  const PetscScalar* xx;
  PCSIM_PETSC(VecGetArrayRead(x, &xx));
  double err = 0;
  for (PetscInt i = lo; i < hi; ++i) err = std::max(err, std::abs(xx[i - lo] - expected[i]));
  PCSIM_PETSC(VecRestoreArrayRead(x, &xx));
  MPI_Allreduce(MPI_IN_PLACE, &err, 1, MPI_DOUBLE, MPI_MAX, PETSC_COMM_WORLD);
  return err / expected.cwiseAbs().maxCoeff();
}

// The step solver's solution (J0 + the blocks' changes + sum c u u^T) x = b
// for right_hand_side()'s b; by_blocks: whether it inverted J0 by blocks;
// symmetric (if given): whether it formed each pair's product once.
Vec solve_step(Mat J0, const char* prefix, const std::vector<pcsim::assembly::RankOne>& terms,
               const std::vector<pcsim::assembly::BlockChange>& blocks, bool* by_blocks,
               bool* symmetric = nullptr) {
  pcsim::solvers::LowRankStepSolver solver(J0, prefix);
  pcsim::solvers::use_step_lu(solver.inner());
  PCSIM_PETSC(KSPSetFromOptions(solver.inner()));
  solver.set_terms(terms, blocks);
  KSP ksp = preonly_ksp(solver, J0);
  solver.set_terms(terms, blocks);
  Vec b, x;
  right_hand_side(J0, &x, &b);
  PCSIM_PETSC(KSPSolve(ksp, b, x));
  *by_blocks = solver.block_inverse();
  if (symmetric) *symmetric = solver.symmetric_capacitance();
  KSPDestroy(&ksp);
  VecDestroy(&b);
  return x;
}

double solve_error(bool coupled, bool* by_blocks, bool symmetric = false,
                   bool* symmetric_used = nullptr) {
  PetscInt n;
  Mat J0 = make_j0(coupled, n, symmetric);
  // Rank-one terms: a dense u over every unknown, a sparse one over three.
  std::vector<pcsim::assembly::RankOne> terms(2);
  std::vector<PetscInt> dense_index;
  std::vector<double> dense_weight;
  for (PetscInt k = 0; k < n; ++k) {
    dense_index.push_back(k);
    dense_weight.push_back(std::sin(1.0 + static_cast<double>(k)));
  }
  terms[0].index = dense_index;
  terms[0].weight = dense_weight;
  terms[0].key = 1;
  terms[0].coefficient = 3.0;
  terms[0].contiguous = true;
  terms[1].key = 2;
  terms[1].index = std::vector<PetscInt>{0, n / 2, n - 1};
  terms[1].weight = {1.0, -0.5, 0.25};
  terms[1].coefficient = -0.8;
  terms[1].reuse_columns = true;
  Vec x = solve_step(J0, "test_j0_", terms, {}, by_blocks, symmetric_used);
  Eigen::MatrixXd A(n, n);  // the same system densely on every rank
  for (PetscInt i = 0; i < n; ++i)
    for (PetscInt j = 0; j < n; ++j) A(i, j) = entry(i, j, coupled, symmetric);
  const double err = error_against_dense(A, terms, x);
  VecDestroy(&x);
  MatDestroy(&J0);
  return err;
}

// One solver through a sequence of term sets (the solution after the last),
// and the bits of a new solver given only the last set.
struct Sequence {
  std::vector<double> kept, fresh;
};

// counts (if given): the solver's set changes and capacitance rows formed.
std::vector<double> solve_sequence(Mat J0,
                                   const std::vector<std::vector<pcsim::assembly::RankOne>>& sets,
                                   std::pair<long, long>* counts = nullptr) {
  pcsim::solvers::LowRankStepSolver solver(J0, "test_seq_");
  KSP ksp = preonly_ksp(solver, J0);
  Vec b, x;
  right_hand_side(J0, &x, &b);
  PetscInt lo, hi;
  PCSIM_PETSC(VecGetOwnershipRange(b, &lo, &hi));
  for (const auto& terms : sets) {
    solver.set_terms(terms);
    PCSIM_PETSC(KSPSolve(ksp, b, x));
  }
  if (counts) *counts = {solver.active_set_changes(), solver.capacitance_rows_formed()};
  const PetscScalar* xx;
  PCSIM_PETSC(VecGetArrayRead(x, &xx));
  std::vector<double> out(xx, xx + (hi - lo));
  PCSIM_PETSC(VecRestoreArrayRead(x, &xx));
  KSPDestroy(&ksp);
  VecDestroy(&b);
  VecDestroy(&x);
  return out;
}

pcsim::assembly::RankOne dense_term(int key, PetscInt n, double phase, double coefficient) {
  pcsim::assembly::RankOne t;
  t.key = key;
  std::vector<PetscInt> index;
  std::vector<double> weight;
  for (PetscInt k = 0; k < n; ++k) {
    index.push_back(k);
    weight.push_back(std::sin(phase + static_cast<double>(k)));
  }
  t.index = index;
  t.weight = weight;
  t.coefficient = coefficient;
  t.contiguous = true;
  return t;
}

// The varying block: local rows kVaryingFirst.. of the last rank (a block
// start of the pattern 1, 2, 1, 3), a band with a coupled first column.
constexpr PetscInt kVaryingFirst = 7, kVaryingSize = kLocal - kVaryingFirst;

double varying_entry(PetscInt a, PetscInt b, PetscInt first) {
  const PetscInt i = a - first, j = b - first;
  if (i == j) return 10.0 + 0.7 * static_cast<double>(a);
  if (std::abs(i - j) <= 3 || j == 0) return 0.3 * std::sin(static_cast<double>(i + 2 * j));
  return 0.0;
}

// J0 with the varying block at rows [first, n); its change and rank-one terms.
double varying_block_error(bool* by_blocks) {
  int size, rank;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  const PetscInt n = kLocal * size, first = n - kVaryingSize;
  const auto in_block = [first](PetscInt i) { return i >= first; };
  const auto value = [&](PetscInt i, PetscInt j) {
    if (in_block(i) || in_block(j))
      return in_block(i) && in_block(j) ? varying_entry(i, j, first) : 0.0;
    return entry(i, j, false);
  };
  Mat J0 = make_matrix(n, value);
  Eigen::MatrixXd delta = Eigen::MatrixXd::Zero(kVaryingSize, kVaryingSize);
  for (PetscInt i = 0; i < kVaryingSize; ++i)
    for (PetscInt j = std::max<PetscInt>(0, i - 2); j < std::min(kVaryingSize, i + 3); ++j)
      delta(i, j) = 0.05 * std::cos(static_cast<double>(i - 2 * j));
  pcsim::assembly::BlockChange change;
  change.key = 1;
  change.first = first;
  change.size = static_cast<int>(kVaryingSize);
  if (rank == size - 1)  // the owner's values, row-major
    for (PetscInt i = 0; i < kVaryingSize; ++i)
      for (PetscInt j = 0; j < kVaryingSize; ++j) change.delta.push_back(delta(i, j));
  const std::vector<pcsim::assembly::RankOne> terms = {dense_term(1, n, 1.0, 3.0)};
  Vec x = solve_step(J0, "test_varying_", terms, {change}, by_blocks);
  Eigen::MatrixXd A(n, n);
  for (PetscInt i = 0; i < n; ++i)
    for (PetscInt j = 0; j < n; ++j) A(i, j) = value(i, j);
  A.bottomRightCorner(kVaryingSize, kVaryingSize) += delta;
  const double err = error_against_dense(A, terms, x);
  VecDestroy(&x);
  MatDestroy(&J0);
  return err;
}

// Two constant terms (dashpots) and a moving one (a contact): the contact
// moves, then a dashpot's coefficient changes, then a term leaves and
// another comes (every product formed again; the new term is given the
// vectors u and z of the one that left, every entry written anew), then the
// contact moves.
std::vector<std::vector<pcsim::assembly::RankOne>> changing_sets(PetscInt n) {
  const auto a = dense_term(1, n, 1.0, 3.0), b = dense_term(2, n, 2.0, 0.5);
  auto b2 = b;
  b2.coefficient = 0.7;
  std::vector<std::vector<pcsim::assembly::RankOne>> sets = {
      {a, b, dense_term(3, n, 3.0, 5.0)},
      {a, b, dense_term(3, n, 3.1, 5.0)},
      {a, b2, dense_term(3, n, 3.2, 5.0)},
      {a, dense_term(4, n, 4.0, 2.0), dense_term(3, n, 3.3, 5.0)},
      {a, dense_term(4, n, 4.0, 2.0), dense_term(3, n, 3.4, 5.0)}};
  return sets;
}

Sequence changed_terms_sequence(bool symmetric) {
  PetscInt n;
  Mat J0 = make_j0(false, n, symmetric);
  const auto sets = changing_sets(n);
  Sequence s;
  for (std::size_t last = 1; last <= sets.size(); ++last) {
    const std::vector<std::vector<pcsim::assembly::RankOne>> head(sets.begin(),
                                                                  sets.begin() + last);
    const auto kept = solve_sequence(J0, head);
    const auto fresh = solve_sequence(J0, {sets[last - 1]});
    s.kept.insert(s.kept.end(), kept.begin(), kept.end());
    s.fresh.insert(s.fresh.end(), fresh.begin(), fresh.end());
  }
  MatDestroy(&J0);
  return s;
}

TEST(BlockDiagonalJ0, WoodburyWithBlockInverseIsExact) {
  bool by_blocks = false;
  const double err = solve_error(false, &by_blocks);
  PetscPrintf(PETSC_COMM_WORLD, "  block-diagonal J0: relative error %.2e\n", err);
  EXPECT_TRUE(by_blocks);
  EXPECT_LT(err, 1e-12);
}

TEST(BlockDiagonalJ0, CoupledJ0FallsBackToTheFactorisation) {
  bool by_blocks = true;
  const double err = solve_error(true, &by_blocks);
  PetscPrintf(PETSC_COMM_WORLD, "  coupled J0: relative error %.2e\n", err);
  EXPECT_FALSE(by_blocks);
  EXPECT_LT(err, 1e-12);
}

TEST(BlockDiagonalJ0, VaryingBlockOfAnySizeIsLeftToItsOwnLU) {
  bool by_blocks = false;
  const double err = varying_block_error(&by_blocks);
  PetscPrintf(PETSC_COMM_WORLD, "  J0 with a varying block of %d rows: relative error %.2e\n",
              static_cast<int>(kVaryingSize), err);
  EXPECT_TRUE(by_blocks);
  EXPECT_LT(err, 1e-12);
}

TEST(BlockDiagonalJ0, ChangedTermsOnlyGiveTheSameBits) {
  for (bool symmetric : {false, true}) {
    const Sequence s = changed_terms_sequence(symmetric);
    ASSERT_EQ(s.kept.size(), s.fresh.size());
    int differing = 0;
    for (std::size_t i = 0; i < s.kept.size(); ++i) differing += s.kept[i] != s.fresh[i];
    MPI_Allreduce(MPI_IN_PLACE, &differing, 1, MPI_INT, MPI_SUM, PETSC_COMM_WORLD);
    EXPECT_EQ(differing, 0) << "symmetric J0: " << symmetric;  // the same products, same order
  }
}

// A J0 inverted by blocks and equal to its transpose: the capacitance forms
// each pair's product once, exact to round-off; a J0 factored whole (not
// checked) and an unsymmetric J0 (the other tests') form both.
TEST(BlockDiagonalJ0, SymmetricJ0FormsEachPairOnce) {
  for (bool coupled : {false, true}) {
    bool by_blocks = !coupled, symmetric_used = coupled;
    const double err = solve_error(coupled, &by_blocks, true, &symmetric_used);
    PetscPrintf(PETSC_COMM_WORLD, "  symmetric %s J0: relative error %.2e\n",
                coupled ? "coupled" : "block-diagonal", err);
    EXPECT_EQ(by_blocks, !coupled);
    EXPECT_EQ(symmetric_used, !coupled);
    EXPECT_LT(err, 1e-12);
  }
  bool by_blocks = false, symmetric_used = true;
  EXPECT_LT(solve_error(false, &by_blocks, false, &symmetric_used), 1e-12);
  EXPECT_FALSE(symmetric_used);
}

// The counts of the step-time report (simulation/step_timing.hpp): the set of
// active terms changes at the first solve and when a term leaves and another
// comes; the rows formed are 3 + 1 (the contact moved) + 1 (a coefficient
// alone changes no row) + 3 + 1.
TEST(BlockDiagonalJ0, CountsSetChangesAndCapacitanceRows) {
  PetscInt n;
  Mat J0 = make_j0(false, n);
  std::pair<long, long> counts;
  solve_sequence(J0, changing_sets(n), &counts);
  MatDestroy(&J0);
  EXPECT_EQ(counts.first, 2);
  EXPECT_EQ(counts.second, 9);
}

}  // namespace
