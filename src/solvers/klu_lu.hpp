// A sparse LU of a small unsymmetric matrix by SuiteSparse's KLU (the
// cheap path's varying blocks, varying_blocks.hpp): the symbolic analysis of
// a pattern (block triangular form, AMD ordering) is kept. On the flexible
// DSA-380's block (150 unknowns, 1318 entries) a factorisation took 19 us
// against 40 us for Eigen's SparseLU (docs/benchmarks.md, "The flexible
// DSA-380's block as a sparse value").
//
// Pivots. keep_pivots_of() factors a reference value on the pattern (the
// block's J0 value) with KLU's partial pivoting and keeps its pivot order;
// each later factor() refactors the value in that order (klu_refactor: no
// pivot search) and takes it where its pivots are regular and its pivot
// growth at most 1 / kRefactorGrowth times the reference's, else factors the
// value afresh (pivots of its own). The factors are a function of the value
// and the reference alone, never of the values factored before: a restarted
// run, whose J0 is rebuilt at the same state, computes the same bits
// (docs/benchmarks.md, "The flexible DSA-380's block in J0's pivot order").
// Private to src/solvers.
#pragma once

#include <klu.h>

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace pcsim::solvers {

class KluLU {
 public:
  // A refactorisation in the kept order is taken while its reciprocal pivot
  // growth (KLU's rgrowth: the smallest ratio over the columns of the largest
  // entry of the scaled matrix to the largest of U) is at least this times
  // the reference's: a growth up to 10 times the reference's, at most a
  // digit lost to it.
  static constexpr double kRefactorGrowth = 0.1;

  KluLU() { klu_defaults(&common_); }
  ~KluLU() { clear(); }
  KluLU(const KluLU&) = delete;
  KluLU& operator=(const KluLU&) = delete;

  // The pattern of a (compressed, column-major, square); no pivots kept.
  void analyze(const Eigen::SparseMatrix<double>& a);
  // Keeps the pivot order of KLU's factorisation of 'reference' (on the
  // analysed pattern); none if it is singular.
  void keep_pivots_of(const Eigen::SparseMatrix<double>& reference);
  // The factors of a, whose pattern is the analysed one. False: a is
  // singular or has an entry that is not finite (no factors then).
  bool factor(const Eigen::SparseMatrix<double>& a);
  // x = A^-1 b with the last factors.
  void solve(const Eigen::Ref<const Eigen::VectorXd>& b, Eigen::Ref<Eigen::VectorXd> x) const;
  // Whether the last factors came from the kept pivot order.
  bool refactored() const { return current_ != nullptr && current_ == kept_; }

 private:
  void clear();
  bool regular(klu_numeric* numeric);
  mutable klu_common common_;
  klu_symbolic* symbolic_ = nullptr;
  klu_numeric* kept_ = nullptr;     // the reference's pivot order, refactored in place
  double kept_growth_ = 0;          // the reference's reciprocal pivot growth
  klu_numeric* fresh_ = nullptr;    // a factorisation with pivots of its own
  klu_numeric* current_ = nullptr;  // the last factors: kept_, fresh_ or none
};

}  // namespace pcsim::solvers
