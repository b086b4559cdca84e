#include "interface_solve.hpp"

#include <algorithm>
#include <cstdlib>

#include "pcsim/core/error.hpp"
#include "pcsim/core/profiling.hpp"

namespace pcsim::solvers {

std::vector<int> offsets_of(const std::vector<int>& counts) {
  std::vector<int> offsets(counts.size() + 1, 0);
  for (std::size_t r = 0; r < counts.size(); ++r) offsets[r + 1] = offsets[r] + counts[r];
  return offsets;
}

namespace {

// max |p(i) - p(j)| over S's entries; order[k] = the row put k-th.
PetscInt bandwidth_of(const InterfaceRows& S, IS order) {
  const PetscInt n = S.rows();
  const PetscInt* old_of;
  PCSIM_PETSC(ISGetIndices(order, &old_of));
  std::vector<PetscInt> p(static_cast<std::size_t>(n));
  for (PetscInt k = 0; k < n; ++k) p[static_cast<std::size_t>(old_of[k])] = k;
  PCSIM_PETSC(ISRestoreIndices(order, &old_of));
  PetscInt band = 0;
  for (PetscInt i = 0; i < n; ++i)
    for (PetscInt k = S.starts[i]; k < S.starts[i + 1]; ++k)
      band = std::max(band, std::abs(p[i] - p[S.columns[k]]));
  return band;
}

// As PCLU's defaults: no shift, a pivot below 100 eps (relative) is an error.
MatFactorInfo lu_options() {
  MatFactorInfo info;
  PCSIM_PETSC(MatFactorInfoInitialize(&info));
  info.fill = 5.0;
  info.dtcol = 1e-6;
  info.zeropivot = 100.0 * PETSC_MACHINE_EPSILON;
  info.pivotinblocks = 1.0;
  return info;
}

}  // namespace

InterfaceFactor::~InterfaceFactor() {
  release();
}

void InterfaceFactor::release() {
  for (Mat* m : {&S_, &F_}) MatDestroy(m);
  for (Vec* v : {&b_, &x_}) VecDestroy(v);
  size_ = bandwidth_ = nonzeros_ = 0;
}

// S as a MATSEQAIJ, its reverse Cuthill-McKee ordering (PETSc's, on the
// symmetrised pattern) and symbolic LU.
void InterfaceFactor::order_and_analyse(const InterfaceRows& S) {
  size_ = S.rows();
  nonzeros_ = static_cast<PetscInt>(S.columns.size());
  PCSIM_PETSC(MatCreate(PETSC_COMM_SELF, &S_));
  PCSIM_PETSC(MatSetSizes(S_, size_, size_, size_, size_));
  PCSIM_PETSC(MatSetType(S_, MATSEQAIJ));
  PCSIM_PETSC(MatSeqAIJSetPreallocationCSR(S_, S.starts.data(), S.columns.data(), S.values.data()));
  IS rows, cols;
  PCSIM_PETSC(MatGetOrdering(S_, MATORDERINGRCM, &rows, &cols));
  bandwidth_ = bandwidth_of(S, rows);
  PCSIM_PETSC(MatGetFactor(S_, MATSOLVERPETSC, MAT_FACTOR_LU, &F_));
  const MatFactorInfo info = lu_options();
  PCSIM_PETSC(MatLUFactorSymbolic(F_, S_, rows, cols, &info));
  PCSIM_PETSC(ISDestroy(&rows));
  PCSIM_PETSC(ISDestroy(&cols));
  PCSIM_PETSC(VecCreateSeqWithArray(PETSC_COMM_SELF, 1, size_, nullptr, &b_));
  PCSIM_PETSC(VecCreateSeqWithArray(PETSC_COMM_SELF, 1, size_, nullptr, &x_));
}

void InterfaceFactor::factor(const InterfaceRows& S, bool same_pattern) {
  if (!same_pattern || !S_) {
    release();
    if (S.rows() == 0) return;
    order_and_analyse(S);
  } else {  // the stored values are S's, in the same (row, ascending column) order
    PetscScalar* a;
    PCSIM_PETSC(MatSeqAIJGetArray(S_, &a));
    std::copy(S.values.begin(), S.values.end(), a);
    PCSIM_PETSC(MatSeqAIJRestoreArray(S_, &a));
  }
  const MatFactorInfo info = lu_options();
  PCSIM_PETSC(MatLUFactorNumeric(F_, S_, &info));
}

void InterfaceFactor::solve(const PetscScalar* b, PetscScalar* x) const {
  if (size_ == 0) return;
  PCSIM_PETSC(VecPlaceArray(b_, b));
  PCSIM_PETSC(VecPlaceArray(x_, x));
  PCSIM_PETSC(MatSolve(F_, b_, x_));
  PCSIM_PETSC(VecResetArray(x_));
  PCSIM_PETSC(VecResetArray(b_));
}

double InterfaceFactor::factor_nonzeros() const {
  if (!F_) return 0;
  MatInfo info;
  PCSIM_PETSC(MatGetInfo(F_, MAT_LOCAL, &info));
  return info.nz_used;
}

// The rows' lengths and columns of all ranks, when some rank's pattern (or
// the split) changed since the last call. Returns whether it did.
bool InterfaceSystem::gather_pattern(const InterfaceRows& mine, const std::vector<int>& counts) {
  int changed = counts != counts_ || mine.starts != mine_.starts || mine.columns != mine_.columns;
  MPI_Allreduce(MPI_IN_PLACE, &changed, 1, MPI_INT, MPI_MAX, comm_);
  if (!changed) return false;
  mine_.starts = mine.starts;
  mine_.columns = mine.columns;
  counts_ = counts;
  offsets_ = offsets_of(counts_);
  std::vector<PetscInt> lengths(static_cast<std::size_t>(mine.rows()));
  for (PetscInt i = 0; i < mine.rows(); ++i) lengths[i] = mine.starts[i + 1] - mine.starts[i];
  std::vector<PetscInt> all_lengths(static_cast<std::size_t>(offsets_.back()));
  MPI_Allgatherv(lengths.data(), static_cast<int>(lengths.size()), MPIU_INT, all_lengths.data(),
                 counts_.data(), offsets_.data(), MPIU_INT, comm_);
  all_.starts.assign(1, 0);
  for (PetscInt l : all_lengths) all_.starts.push_back(all_.starts.back() + l);
  value_counts_.assign(counts_.size(), 0);
  value_offsets_.assign(counts_.size(), 0);
  for (std::size_t r = 0; r < counts_.size(); ++r) {
    value_offsets_[r] = static_cast<int>(all_.starts[offsets_[r]]);
    value_counts_[r] = static_cast<int>(all_.starts[offsets_[r + 1]]) - value_offsets_[r];
  }
  all_.columns.resize(static_cast<std::size_t>(all_.starts.back()));
  MPI_Allgatherv(mine.columns.data(), static_cast<int>(mine.columns.size()), MPIU_INT,
                 all_.columns.data(), value_counts_.data(), value_offsets_.data(), MPIU_INT, comm_);
  all_.values.resize(all_.columns.size());
  return true;
}

void InterfaceSystem::factor(const InterfaceRows& mine, const std::vector<int>& counts) {
  const bool new_pattern = gather_pattern(mine, counts);
  MPI_Allgatherv(mine.values.data(), static_cast<int>(mine.values.size()), MPIU_SCALAR,
                 all_.values.data(), value_counts_.data(), value_offsets_.data(), MPIU_SCALAR,
                 comm_);
  lu_.factor(all_, !new_pattern);
}

void InterfaceSystem::solve(const PetscScalar* g_mine, std::vector<PetscScalar>& x) {
  int rank;
  MPI_Comm_rank(comm_, &rank);
  g_.resize(static_cast<std::size_t>(offsets_.back()));
  MPI_Allgatherv(g_mine, counts_[rank], MPIU_SCALAR, g_.data(), counts_.data(), offsets_.data(),
                 MPIU_SCALAR, comm_);
  x.resize(g_.size());
  const ScopedEvent timed(log_events().dd_interface);
  lu_.solve(g_.data(), x.data());
}

}  // namespace pcsim::solvers
