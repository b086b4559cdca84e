#include "negligible_entries.hpp"

#include <cmath>
#include <vector>

#include "pcsim/core/error.hpp"

namespace pcsim::solvers {

namespace {
constexpr PetscReal kNegligibleRelative = 1e-18;
}  // namespace

void drop_negligible(Mat* X, double* entries, double* stored) {
  PetscInt rows = 0, cols = 0, lda = 0;
  const PetscScalar* a = nullptr;
  PCSIM_PETSC(MatGetSize(*X, &rows, &cols));
  PCSIM_PETSC(MatDenseGetLDA(*X, &lda));
  PCSIM_PETSC(MatDenseGetArrayRead(*X, &a));
  std::vector<PetscReal> floor(static_cast<std::size_t>(cols), 0.0);
  for (PetscInt j = 0; j < cols; ++j) {
    PetscReal largest = 0;
    for (PetscInt i = 0; i < rows; ++i) largest = std::fmax(largest, std::abs(a[i + j * lda]));
    floor[j] = kNegligibleRelative * largest;
  }
  std::vector<PetscInt> row_start(static_cast<std::size_t>(rows) + 1, 0), columns;
  std::vector<PetscScalar> values;
  for (PetscInt i = 0; i < rows; ++i) {
    for (PetscInt j = 0; j < cols; ++j) {
      const PetscScalar v = a[i + j * lda];
      if (std::abs(v) <= floor[j]) continue;
      columns.push_back(j);
      values.push_back(v);
    }
    row_start[i + 1] = static_cast<PetscInt>(columns.size());
  }
  PCSIM_PETSC(MatDenseRestoreArrayRead(*X, &a));
  *entries = static_cast<double>(rows) * static_cast<double>(cols);
  *stored = *entries;
  if (2 * values.size() > static_cast<std::size_t>(*entries)) return;
  Mat sparse = nullptr;
  PCSIM_PETSC(MatCreate(PETSC_COMM_SELF, &sparse));
  PCSIM_PETSC(MatSetSizes(sparse, rows, cols, rows, cols));
  PCSIM_PETSC(MatSetType(sparse, MATSEQAIJ));
  PCSIM_PETSC(
      MatSeqAIJSetPreallocationCSR(sparse, row_start.data(), columns.data(), values.data()));
  PCSIM_PETSC(MatDestroy(X));
  *X = sparse;
  *stored = static_cast<double>(values.size());
}

}  // namespace pcsim::solvers
