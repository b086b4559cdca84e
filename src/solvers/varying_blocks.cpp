#include "varying_blocks.hpp"

#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>

#include "pcsim/core/error.hpp"

namespace pcsim::solvers {

void VaryingBlocks::set(const std::vector<assembly::BlockChange>& changes) {
  std::set<int> keys;
  for (const auto& change : changes) {
    keys.insert(change.key);
    auto [it, added] = blocks_.try_emplace(change.key);
    Block& b = it->second;
    if (added && ready_)  // its J0 values are not read yet: only setup() reads them
      throw SolverError("a varying block of the step matrix appeared after J0's setup");
    b.first = change.first;
    b.size = change.size;
    b.owned = change.given();
    if (b.owned) {
      b.delta = change.delta;  // keeps its storage from the last iteration
      b.value = change.value;
    }
    if (ready_ && b.owned) refactor(b);
  }
  for (auto it = blocks_.begin(); it != blocks_.end();)
    it = keys.count(it->first) ? std::next(it) : blocks_.erase(it);
}

void VaryingBlocks::setup(Mat P) {
  PetscInt lo, hi;
  PCSIM_PETSC(MatGetOwnershipRange(P, &lo, &hi));
  for (auto& [key, b] : blocks_) {
    const bool here = b.first >= lo && b.first + b.size <= hi;
    if (here != b.owned || (!here && b.first < hi && b.first + b.size > lo))
      throw SolverError("a varying block of the step matrix is not on the rank of its change");
    if (!b.owned) continue;
    b.reference = RowMatrix::Zero(b.size, b.size);
    for (PetscInt r = b.first; r < b.first + b.size; ++r) {
      PetscInt n;
      const PetscInt* cols;
      const PetscScalar* values;
      PCSIM_PETSC(MatGetRow(P, r, &n, &cols, &values));
      bool coupled = false;
      for (PetscInt k = 0; k < n; ++k) {
        if (cols[k] >= b.first && cols[k] < b.first + b.size)
          b.reference(r - b.first, cols[k] - b.first) = values[k];
        else
          coupled = coupled || values[k] != 0;
      }
      PCSIM_PETSC(MatRestoreRow(P, r, &n, &cols, &values));
      if (coupled)
        throw SolverError("J0 couples row " + std::to_string(r) +
                          " of a varying block with other unknowns");
    }
    if (b.sparse && b.matrix.rows() == b.size) keep_reference(b);  // J0's block anew
  }
  check_decoupled(P);
  ready_ = true;
  for (auto& [key, b] : blocks_)
    if (b.owned) refactor(b);
}

// Columns: P e_j has no entry outside the block of j (collective).
void VaryingBlocks::check_decoupled(Mat P) const {
  Vec e, y;
  PCSIM_PETSC(MatCreateVecs(P, &e, &y));
  PetscInt lo, hi;
  PCSIM_PETSC(VecGetOwnershipRange(y, &lo, &hi));
  bool coupled = false;
  for (const auto& [key, b] : blocks_)
    for (PetscInt j = b.first; j < b.first + b.size; ++j) {
      PCSIM_PETSC(VecSet(e, 0.0));
      if (b.owned) PCSIM_PETSC(VecSetValue(e, j, 1.0, INSERT_VALUES));
      PCSIM_PETSC(VecAssemblyBegin(e));
      PCSIM_PETSC(VecAssemblyEnd(e));
      PCSIM_PETSC(MatMult(P, e, y));
      PetscScalar* yy;
      PCSIM_PETSC(VecGetArray(y, &yy));
      if (b.owned) std::fill(yy + (b.first - lo), yy + (b.first + b.size - lo), 0.0);
      PCSIM_PETSC(VecRestoreArray(y, &yy));
      PetscReal outside;
      PCSIM_PETSC(VecNorm(y, NORM_INFINITY, &outside));
      coupled = coupled || outside != 0;
    }
  PCSIM_PETSC(VecDestroy(&e));
  PCSIM_PETSC(VecDestroy(&y));
  if (coupled) throw SolverError("J0 couples a varying block's column with other unknowns");
}

// Singular (or not finite) when a pivot of U is zero (or not finite): with
// partial pivoting a zero pivot means a column without a nonzero left. The
// pivots alone, not Eigen's rcond() estimate (a fifth of a flexible DSA-380
// step's refactoring: its own triangular solves).
void VaryingBlocks::refactor(Block& b) {
  bool regular = true;
  const bool given = b.value.size() > 0;
  if (given) refactor_given(b);
  if (given || refactor_sparse(b)) {
    regular = b.regular;  // KLU's: a zero or not finite pivot refused (klu_lu.hpp)
    ++sparse_factorisations_;
    kept_order_ += b.sparse_lu.refactored() ? 1 : 0;
  } else {
    b.lu.compute(b.reference + Eigen::Map<const RowMatrix>(b.delta.data(), b.size, b.size));
    const auto pivots = b.lu.matrixLU().diagonal().array();
    regular = pivots.isFinite().all() && (pivots != 0.0).all();
  }
  if (!regular)
    throw SolverError("the step matrix has a singular varying block at row " +
                      std::to_string(b.first));
}

// A block of at least kSparseSize unknowns with at most kSparseFill of its
// entries nonzero takes the sparse LU (the flexible DSA-380: 150 unknowns,
// 1310 entries, where the dense LU was a quarter of its modal step:
// docs/benchmarks.md, "The flexible DSA-380's block"). Its ordering (KLU's)
// and symbolic analysis are kept while its nonzeros are those analysed: the
// factors are a function of the block's value alone, so a restarted run
// computes the same ones as an uninterrupted run. No dense n x n value is
// formed unless the pattern is analysed anew. False: dense.
bool VaryingBlocks::refactor_sparse(Block& b) {
  constexpr int kSparseSize = 32;
  constexpr double kSparseFill = 0.2;
  if (b.size < kSparseSize) return false;
  const int n = b.size;
  const Eigen::Map<const RowMatrix> delta(b.delta.data(), n, n);
  const long nonzeros = ((b.reference.array() + delta.array()) != 0.0).count();
  long on_pattern = 0;
  if (b.sparse && b.matrix.rows() == n) {
    for (Eigen::Index j = 0; j < b.matrix.outerSize(); ++j)
      for (Eigen::SparseMatrix<double>::InnerIterator it(b.matrix, j); it; ++it) {
        it.valueRef() = b.reference(it.row(), it.col()) + delta(it.row(), it.col());
        on_pattern += it.value() != 0.0;
      }
  }
  // Not analysed yet, an entry off the pattern, or one of it now zero.
  if (!b.sparse || on_pattern != nonzeros || on_pattern != b.matrix.nonZeros()) {
    b.sparse = nonzeros <= kSparseFill * n * n;
    if (!b.sparse) return false;
    const RowMatrix value = b.reference + delta;
    b.matrix = value.sparseView(0.0, 0.0);  // exact zeros left out only
    b.sparse_lu.analyze(b.matrix);
    ++analyses_;
    keep_reference(b);
  }
  b.regular = b.sparse_lu.factor(b.matrix);
  return true;
}

// A block given as its sparse value (a model's sparse step tangent: the
// flexible DSA-380's 150 unknowns, no dense n x n formed): the value's
// entries are the pattern, its analysis kept while they are those analysed.
// The factors are a function of the value (entries and pattern) alone.
void VaryingBlocks::refactor_given(Block& b) {
  const Eigen::SparseMatrix<double>& v = b.value;
  const Eigen::Index nnz = v.nonZeros(), outer = v.outerSize();
  const bool analysed =
      b.sparse && b.matrix.rows() == v.rows() && b.matrix.nonZeros() == nnz &&
      std::equal(v.outerIndexPtr(), v.outerIndexPtr() + outer + 1, b.matrix.outerIndexPtr()) &&
      std::equal(v.innerIndexPtr(), v.innerIndexPtr() + nnz, b.matrix.innerIndexPtr());
  if (analysed) {
    std::copy(v.valuePtr(), v.valuePtr() + nnz, b.matrix.valuePtr());
  } else {
    b.sparse = true;
    b.matrix = v;
    b.sparse_lu.analyze(b.matrix);
    ++analyses_;
    keep_reference(b);
  }
  b.regular = b.sparse_lu.factor(b.matrix);
}

// What a sparse block keeps of J0's block, after a new analysis and when J0
// is read anew: its entries off the pattern, and the pivot order of J0's
// block on the pattern (klu_lu.hpp), which every later factorisation of the
// block refactors in while it stays stable: the factors then depend on the
// value and J0 alone, as a restarted run needs.
void VaryingBlocks::keep_reference(Block& b) {
  find_off_pattern(b);
  Eigen::SparseMatrix<double> reference = b.matrix;
  for (Eigen::Index j = 0; j < reference.outerSize(); ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(reference, j); it; ++it)
      it.valueRef() = b.reference(it.row(), it.col());
  b.sparse_lu.keep_pivots_of(reference);
}

// J0's entries of a sparse block off its pattern (b.matrix's): the value is
// 0 there and the change -J0.
void VaryingBlocks::find_off_pattern(Block& b) {
  Eigen::Matrix<bool, Eigen::Dynamic, Eigen::Dynamic> on(b.size, b.size);
  on.setConstant(false);
  for (Eigen::Index j = 0; j < b.matrix.outerSize(); ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(b.matrix, j); it; ++it)
      on(it.row(), it.col()) = true;
  b.reference_off_pattern.clear();
  for (int i = 0; i < b.size; ++i)
    for (int j = 0; j < b.size; ++j)
      if (!on(i, j) && b.reference(i, j) != 0.0)
        b.reference_off_pattern.emplace_back(i, j, b.reference(i, j));
}

std::vector<std::pair<PetscInt, PetscInt>> VaryingBlocks::owned_ranges() const {
  std::vector<std::pair<PetscInt, PetscInt>> ranges;
  for (const auto& [key, b] : blocks_)
    if (b.owned) ranges.emplace_back(b.first, b.size);
  return ranges;
}

int VaryingBlocks::sparse_blocks() const {
  int count = 0;
  for (const auto& [key, b] : blocks_) count += b.owned && b.sparse;
  return count;
}

namespace {

// f(block, its rows of 'in', its rows of 'out') for every block this rank owns.
template <class Blocks, class F>
void each_owned_block(const Blocks& blocks, Vec in, Vec out, F&& f) {
  PetscInt lo, hi;
  PCSIM_PETSC(VecGetOwnershipRange(out, &lo, &hi));
  const PetscScalar* ii;
  PetscScalar* oo;
  PCSIM_PETSC(VecGetArrayRead(in, &ii));
  PCSIM_PETSC(VecGetArray(out, &oo));
  for (const auto& [key, b] : blocks) {
    if (!b.owned) continue;
    f(b, Eigen::Map<const Eigen::VectorXd>(ii + (b.first - lo), b.size),
      Eigen::Map<Eigen::VectorXd>(oo + (b.first - lo), b.size));
  }
  PCSIM_PETSC(VecRestoreArray(out, &oo));
  PCSIM_PETSC(VecRestoreArrayRead(in, &ii));
}

}  // namespace

void VaryingBlocks::solve_rows(Vec r, Vec x) const {
  each_owned_block(blocks_, r, x, [](const auto& b, const auto& rb, auto xb) {
    if (b.sparse)
      b.sparse_lu.solve(rb, xb);
    else
      xb = b.lu.solve(rb);
  });
}

// A sparse block's change is its value less J0 on the pattern, and -J0 where
// J0 has an entry off it (the value is 0 there while the pattern holds).
void VaryingBlocks::add_change(Vec x, Vec y) const {
  each_owned_block(blocks_, x, y, [](const auto& b, const auto& xb, auto yb) {
    if (!b.sparse) {
      yb += Eigen::Map<const RowMatrix>(b.delta.data(), b.size, b.size) * xb;
      return;
    }
    for (Eigen::Index j = 0; j < b.matrix.outerSize(); ++j)
      for (Eigen::SparseMatrix<double>::InnerIterator it(b.matrix, j); it; ++it)
        yb[it.row()] += (it.value() - b.reference(it.row(), it.col())) * xb[j];
    for (const auto& e : b.reference_off_pattern) yb[e.row()] -= e.value() * xb[e.col()];
  });
}

}  // namespace pcsim::solvers
