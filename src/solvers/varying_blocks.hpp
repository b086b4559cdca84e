// The 'block' terms of the cheap path's step matrix (assembly/term.hpp): small
// dense diagonal blocks of J0 (a nonlinear pantograph's unknowns) whose exact
// value J0_b + delta changes at every Newton iteration. J0 couples a block
// with no other unknown (checked at setup), so
//   (J0 + delta)^-1 r = J0^-1 r  with the block's rows replaced by (J0_b + delta)^-1 r_b:
// J0 stays factored once, each block is refactored per iteration: by a dense
// LU, or, for a large block with few entries (the flexible DSA-380's 150
// unknowns, 6 % of them), by a sparse LU whose ordering is kept while the
// entries stay where they were. A block whose change comes as its sparse
// value (BlockChange::value, a model's sparse step tangent) takes the sparse
// LU on that value's entries: no dense n x n is read or formed.
// Private to src/solvers (the low-rank step solver).
#pragma once

#include <petscmat.h>

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <map>
#include <utility>
#include <vector>

#include "klu_lu.hpp"
#include "pcsim/assembly/term.hpp"

namespace pcsim::solvers {

class VaryingBlocks {
 public:
  bool empty() const { return blocks_.empty(); }
  // The current changes (the same keys on every rank; values on the owner).
  // Refactors the owned blocks when J0's values are known.
  void set(const std::vector<assembly::BlockChange>& changes);
  // J0 was factored: reads each owned block of P, checks that P couples it
  // with no other unknown (collective; throws SolverError otherwise), refactors.
  void setup(Mat P);
  // J0 changed: its blocks are unknown until setup().
  void invalidate() { ready_ = false; }
  bool ready() const { return ready_; }
  // x's block rows = (J0_b + delta)^-1 r_b (x holds J0^-1 r elsewhere).
  void solve_rows(Vec r, Vec x) const;
  // y's block rows += delta x_b.
  void add_change(Vec x, Vec y) const;
  // Owned blocks factored by the sparse LU, and the sparse LUs' analyses of
  // a new pattern of entries so far.
  int sparse_blocks() const;
  // The global rows [first, first + size) of the blocks this rank owns.
  std::vector<std::pair<PetscInt, PetscInt>> owned_ranges() const;
  long pattern_analyses() const { return analyses_; }
  // The sparse blocks' factorisations, and those refactored in the pivot
  // order of J0's block (klu_lu.hpp).
  long sparse_factorisations() const { return sparse_factorisations_; }
  long kept_order_factorisations() const { return kept_order_; }

 private:
  using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  struct Block {
    PetscInt first = 0;
    int size = 0;
    bool owned = false;
    RowMatrix reference;                // J0's values (owner)
    std::vector<double> delta;          // the change, row-major (owner)
    Eigen::SparseMatrix<double> value;  // or the value itself, sparse (owner; delta empty)
    Eigen::PartialPivLU<Eigen::MatrixXd> lu;
    bool sparse = false;
    Eigen::SparseMatrix<double> matrix;  // J0_b + delta, on the pattern of the last analysis
    KluLU sparse_lu;                     // its factors (sparse)
    bool regular = false;                // the last factorisation's
    // J0's nonzeros off the pattern (sparse blocks): there the value is 0, the change -J0.
    std::vector<Eigen::Triplet<double>> reference_off_pattern;
  };
  void check_decoupled(Mat P) const;
  void refactor(Block& b);
  bool refactor_sparse(Block& b);
  void refactor_given(Block& b);
  static void keep_reference(Block& b);
  static void find_off_pattern(Block& b);

  std::map<int, Block> blocks_;
  bool ready_ = false;
  long analyses_ = 0;
  long sparse_factorisations_ = 0, kept_order_ = 0;
};

}  // namespace pcsim::solvers
