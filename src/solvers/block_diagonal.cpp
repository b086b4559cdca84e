#include "block_diagonal.hpp"

#include <mpi.h>

#include <algorithm>
#include <string>

#include "pcsim/core/error.hpp"

namespace pcsim::solvers {

bool BlockDiagonalInverse::analyse(Mat P, PetscInt max_block, const std::vector<Range>& skipped) {
  PetscInt lo, hi;
  PCSIM_PETSC(MatGetOwnershipRange(P, &lo, &hi));
  sizes_.clear();
  int ok = 1;
  PetscInt start = lo, reach = lo;
  for (PetscInt r = lo; r < hi && ok; ++r) {
    const auto skip =
        std::find_if(skipped.begin(), skipped.end(), [r](const Range& s) { return s.first == r; });
    if (skip != skipped.end()) {  // its coupling is checked by its owner (VaryingBlocks)
      ok = start == r && r + skip->second <= hi;  // no open block reaches into it
      sizes_.push_back(-skip->second);
      r += skip->second - 1;
      start = reach = r + 1;
      continue;
    }
    PetscInt n;
    const PetscInt* cols;
    PCSIM_PETSC(MatGetRow(P, r, &n, &cols, nullptr));
    bool diagonal = false;
    for (PetscInt k = 0; k < n; ++k) {
      if (cols[k] < start || cols[k] >= hi) ok = 0;  // couples outside the block or rank
      reach = std::max(reach, cols[k]);
      diagonal = diagonal || cols[k] == r;
    }
    PCSIM_PETSC(MatRestoreRow(P, r, &n, &cols, nullptr));
    if (!diagonal) ok = 0;
    if (reach <= r) {  // the block start..r closes
      sizes_.push_back(r - start + 1);
      start = reach = r + 1;
    } else if (r - start + 1 >= max_block) {
      ok = 0;
    }
  }
  ok = ok && start == hi;
  MPI_Allreduce(MPI_IN_PLACE, &ok, 1, MPI_INT, MPI_MIN,
                PetscObjectComm(reinterpret_cast<PetscObject>(P)));
  if (!ok) sizes_.clear();
  return ok != 0;
}

void BlockDiagonalInverse::factor(Mat P) {
  PetscInt lo, hi;
  PCSIM_PETSC(MatGetOwnershipRange(P, &lo, &hi));
  inverse_diagonal_ = Eigen::ArrayXd::Zero(hi - lo);
  blocks_.clear();
  PetscInt first = lo;
  for (PetscInt size : sizes_) {
    if (size < 0) {  // skipped: its rows of inverse_diagonal_ stay 0
      first -= size;
      continue;
    }
    Eigen::MatrixXd block = Eigen::MatrixXd::Zero(size, size);
    for (PetscInt r = first; r < first + size; ++r) {
      PetscInt n;
      const PetscInt* cols;
      const PetscScalar* values;
      PCSIM_PETSC(MatGetRow(P, r, &n, &cols, &values));
      for (PetscInt k = 0; k < n; ++k) block(r - first, cols[k] - first) = values[k];
      PCSIM_PETSC(MatRestoreRow(P, r, &n, &cols, &values));
    }
    if (size == 1) {
      if (block(0, 0) == 0)
        throw SolverError("the step matrix J0 has a zero pivot in row " + std::to_string(first));
      inverse_diagonal_[first - lo] = 1.0 / block(0, 0);
    } else {
      Block b{first - lo, Eigen::PartialPivLU<Eigen::MatrixXd>(block)};
      if (b.lu.determinant() == 0)
        throw SolverError("the step matrix J0 has a singular block at row " +
                          std::to_string(first));
      blocks_.push_back(std::move(b));
    }
    first += size;
  }
}

void BlockDiagonalInverse::solve(Vec r, Vec x) const {
  PetscInt n;
  const PetscScalar* rr;
  PetscScalar* xx;
  PCSIM_PETSC(VecGetLocalSize(r, &n));
  PCSIM_PETSC(VecGetArrayRead(r, &rr));
  PCSIM_PETSC(VecGetArrayWrite(x, &xx));
  const Eigen::Map<const Eigen::ArrayXd> rhs(rr, n);
  Eigen::Map<Eigen::ArrayXd> solution(xx, n);
  solution = inverse_diagonal_ * rhs;
  for (const auto& b : blocks_) {
    const auto size = b.lu.rows();
    solution.segment(b.first, size) = b.lu.solve(rhs.segment(b.first, size).matrix()).array();
  }
  PCSIM_PETSC(VecRestoreArrayWrite(x, &xx));
  PCSIM_PETSC(VecRestoreArrayRead(r, &rr));
}

bool exactly_symmetric(Mat P) {
  PetscBool aij = PETSC_FALSE, symmetric = PETSC_FALSE;
  PCSIM_PETSC(
      PetscObjectTypeCompareAny(reinterpret_cast<PetscObject>(P), &aij, MATSEQAIJ, MATMPIAIJ, ""));
  if (aij) PCSIM_PETSC(MatIsSymmetric(P, 0.0, &symmetric));
  return symmetric == PETSC_TRUE;
}

}  // namespace pcsim::solvers
