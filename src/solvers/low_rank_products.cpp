// The low-rank step solver's products with its operator (low_rank.hpp): J x
// for the shell matrix and the terms' change product of a residual update.
#include <mpi.h>

#include <vector>

#include "pcsim/core/error.hpp"
#include "pcsim/solvers/low_rank.hpp"
#include "varying_blocks.hpp"

namespace pcsim::solvers {

// y = J0 x + sum_k c_k u_k (u_k . x).
PetscErrorCode LowRankStepSolver::op_mult(Mat A, Vec x, Vec y) {
  PCSIM_CALLBACK_BEGIN
  LowRankStepSolver* self;
  PCSIM_PETSC(MatShellGetContext(A, &self));
  PCSIM_PETSC(MatMult(self->J0_, x, y));
  // Before the preconditioner's set-up (-snes_test_jacobian forms the operator
  // first): a block given as its value needs J0's block for its change.
  if (!self->varying_->empty() && !self->varying_->ready()) self->varying_->setup(self->J0_);
  self->varying_->add_change(x, y);
  std::vector<Vec> us;
  std::vector<PetscScalar> c;
  for (auto& [key, e] : self->entries_)
    if (e.term.coefficient != 0) {
      us.push_back(e.u);
      c.push_back(e.term.coefficient);
    }
  if (us.empty()) return 0;
  std::vector<PetscScalar> w(us.size());
  PCSIM_PETSC(VecMDot(x, static_cast<PetscInt>(us.size()), us.data(), w.data()));
  for (std::size_t j = 0; j < w.size(); ++j) w[j] *= c[j];
  PCSIM_PETSC(VecMAXPY(y, static_cast<PetscInt>(us.size()), w.data(), us.data()));
  PCSIM_CALLBACK_END
}

// u_k . x of the active terms from the last application, if x is its result
// unchanged and the terms are those it used.
bool LowRankStepSolver::products_of_last_apply(Vec x, std::vector<double>& dots) const {
  const LastApply& last = last_apply_;
  PetscObjectState state = 0;
  PCSIM_PETSC(PetscObjectStateGet(reinterpret_cast<PetscObject>(x), &state));
  const auto k = static_cast<long>(dots.size());
  if (x != last.x || state != last.state || capacitance_dirty_ || last.uy.size() != k ||
      products_.rows() != k || static_cast<long>(active_.size()) != k)
    return false;
  const Eigen::VectorXd ux = last.uy + products_ * last.s;
  std::copy(ux.data(), ux.data() + k, dots.begin());
  return true;
}

// y += sum_k c_k u_k (u_k . x) + the block changes' products, each u_k from
// its owned entries (every rank knows every index).
void LowRankStepSolver::add_change_product(Vec x, Vec y) const {
  varying_->add_change(x, y);
  std::vector<const Entry*> terms;
  for (const auto& [key, e] : entries_)
    if (e.term.coefficient != 0) terms.push_back(&e);
  if (terms.empty()) return;
  PetscInt lo, hi;
  PCSIM_PETSC(VecGetOwnershipRange(x, &lo, &hi));
  std::vector<double> dots(terms.size(), 0.0);
  if (!products_of_last_apply(x, dots)) {
    const PetscScalar* xs;
    PCSIM_PETSC(VecGetArrayRead(x, &xs));
    for (std::size_t k = 0; k < terms.size(); ++k) {
      const auto& t = terms[k]->term;
      for (std::size_t i = 0; i < t.index.size(); ++i)
        if (t.index[i] >= lo && t.index[i] < hi) dots[k] += t.weight[i] * xs[t.index[i] - lo];
    }
    PCSIM_PETSC(VecRestoreArrayRead(x, &xs));
    MPI_Comm comm = PetscObjectComm(reinterpret_cast<PetscObject>(x));
    MPI_Allreduce(MPI_IN_PLACE, dots.data(), static_cast<int>(dots.size()), MPI_DOUBLE, MPI_SUM,
                  comm);
  }
  PetscScalar* ys;
  PCSIM_PETSC(VecGetArray(y, &ys));
  for (std::size_t k = 0; k < terms.size(); ++k) {
    const auto& t = terms[k]->term;
    const double scale = t.coefficient * dots[k];
    for (std::size_t i = 0; i < t.index.size(); ++i)
      if (t.index[i] >= lo && t.index[i] < hi) ys[t.index[i] - lo] += scale * t.weight[i];
  }
  PCSIM_PETSC(VecRestoreArray(y, &ys));
}

}  // namespace pcsim::solvers
