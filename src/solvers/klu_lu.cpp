#include "klu_lu.hpp"

#include <cmath>

#include "pcsim/core/error.hpp"

namespace pcsim::solvers {

namespace {
// KLU reads the index arrays without writing them (its API is not const).
int* indices(const int* p) {
  return const_cast<int*>(p);
}
double* values(const double* p) {
  return const_cast<double*>(p);
}
}  // namespace

void KluLU::clear() {
  if (kept_) klu_free_numeric(&kept_, &common_);
  if (fresh_) klu_free_numeric(&fresh_, &common_);
  if (symbolic_) klu_free_symbolic(&symbolic_, &common_);
  current_ = nullptr;
}

void KluLU::analyze(const Eigen::SparseMatrix<double>& a) {
  clear();
  symbolic_ = klu_analyze(static_cast<int>(a.rows()), indices(a.outerIndexPtr()),
                          indices(a.innerIndexPtr()), &common_);
  if (!symbolic_) throw SolverError("KLU could not analyse a varying block's pattern");
}

// A reciprocal condition estimate (smallest over largest pivot) that is a
// positive finite number: no zero and no entry that is not finite.
bool KluLU::regular(klu_numeric* numeric) {
  if (!klu_rcond(symbolic_, numeric, &common_)) return false;
  return std::isfinite(common_.rcond) && common_.rcond > 0;
}

void KluLU::keep_pivots_of(const Eigen::SparseMatrix<double>& reference) {
  if (kept_) klu_free_numeric(&kept_, &common_);
  current_ = nullptr;
  int* ap = indices(reference.outerIndexPtr());
  int* ai = indices(reference.innerIndexPtr());
  double* ax = values(reference.valuePtr());
  kept_ = klu_factor(ap, ai, ax, symbolic_, &common_);
  if (kept_ && !(regular(kept_) && klu_rgrowth(ap, ai, ax, symbolic_, kept_, &common_)))
    klu_free_numeric(&kept_, &common_);
  kept_growth_ = kept_ ? common_.rgrowth : 0;
}

// A singular matrix stops klu_factor and klu_refactor (halt_if_singular,
// KLU's default; a refactorisation's values are then partly undefined, its
// pivot order kept for the next one).
bool KluLU::factor(const Eigen::SparseMatrix<double>& a) {
  int* ap = indices(a.outerIndexPtr());
  int* ai = indices(a.innerIndexPtr());
  double* ax = values(a.valuePtr());
  if (kept_ && klu_refactor(ap, ai, ax, symbolic_, kept_, &common_) && regular(kept_) &&
      klu_rgrowth(ap, ai, ax, symbolic_, kept_, &common_) &&
      common_.rgrowth >= kRefactorGrowth * kept_growth_) {
    current_ = kept_;
    return true;
  }

  if (fresh_) klu_free_numeric(&fresh_, &common_);
  current_ = nullptr;
  fresh_ = klu_factor(ap, ai, ax, symbolic_, &common_);
  if (!fresh_ || !regular(fresh_)) return false;
  current_ = fresh_;
  return true;
}

void KluLU::solve(const Eigen::Ref<const Eigen::VectorXd>& b, Eigen::Ref<Eigen::VectorXd> x) const {
  x = b;
  if (current_)
    klu_solve(symbolic_, current_, static_cast<int>(x.size()), 1, x.data(), &common_);
  else  // a refused factorisation (singular): no solution
    x.setConstant(std::nan(""));
}

}  // namespace pcsim::solvers
