// A sparse LU of a small unsymmetric matrix by SuiteSparse's KLU (the
// cheap path's varying blocks, varying_blocks.hpp): the symbolic analysis of
// a pattern (block triangular form, AMD ordering) is kept, and each numeric
// factorisation pivots anew, so the factors are a function of the matrix
// alone. On the flexible DSA-380's block (150 unknowns, 1318 entries) a
// factorisation took 19 us against 40 us for Eigen's SparseLU
// (docs/benchmarks.md, "The flexible DSA-380's block as a sparse value").
// Private to src/solvers.
#pragma once

#include <klu.h>

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace pcsim::solvers {

class KluLU {
 public:
  KluLU() { klu_defaults(&common_); }
  ~KluLU() { clear(); }
  KluLU(const KluLU&) = delete;
  KluLU& operator=(const KluLU&) = delete;

  // The pattern of a (compressed, column-major, square).
  void analyze(const Eigen::SparseMatrix<double>& a);
  // The factors of a, whose pattern is the analysed one. False: a is
  // singular or has an entry that is not finite (no factors then).
  bool factor(const Eigen::SparseMatrix<double>& a);
  // x = A^-1 b with the last factors.
  void solve(const Eigen::Ref<const Eigen::VectorXd>& b, Eigen::Ref<Eigen::VectorXd> x) const;

 private:
  void clear();
  mutable klu_common common_;
  klu_symbolic* symbolic_ = nullptr;
  klu_numeric* numeric_ = nullptr;
};

}  // namespace pcsim::solvers
