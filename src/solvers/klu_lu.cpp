#include "klu_lu.hpp"

#include <cmath>

#include "pcsim/core/error.hpp"

namespace pcsim::solvers {

namespace {
// KLU reads the index arrays without writing them (its API is not const).
int* indices(const int* p) {
  return const_cast<int*>(p);
}
}  // namespace

void KluLU::clear() {
  if (numeric_) klu_free_numeric(&numeric_, &common_);
  if (symbolic_) klu_free_symbolic(&symbolic_, &common_);
}

void KluLU::analyze(const Eigen::SparseMatrix<double>& a) {
  clear();
  symbolic_ = klu_analyze(static_cast<int>(a.rows()), indices(a.outerIndexPtr()),
                          indices(a.innerIndexPtr()), &common_);
  if (!symbolic_) throw SolverError("KLU could not analyse a varying block's pattern");
}

// A singular matrix stops klu_factor (halt_if_singular, KLU's default); one
// with an entry that is not finite gives a reciprocal condition estimate
// (smallest over largest pivot) that is not a positive finite number.
bool KluLU::factor(const Eigen::SparseMatrix<double>& a) {
  if (numeric_) klu_free_numeric(&numeric_, &common_);
  numeric_ = klu_factor(indices(a.outerIndexPtr()), indices(a.innerIndexPtr()),
                        const_cast<double*>(a.valuePtr()), symbolic_, &common_);
  if (!numeric_) return false;
  if (!klu_rcond(symbolic_, numeric_, &common_)) return false;
  return std::isfinite(common_.rcond) && common_.rcond > 0;
}

void KluLU::solve(const Eigen::Ref<const Eigen::VectorXd>& b, Eigen::Ref<Eigen::VectorXd> x) const {
  x = b;
  if (numeric_)
    klu_solve(symbolic_, numeric_, static_cast<int>(x.size()), 1, x.data(), &common_);
  else  // a refused factorisation (singular): no solution
    x.setConstant(std::nan(""));
}

}  // namespace pcsim::solvers
