#include "pcsim/assembly/subset_axpy.hpp"

#include "pcsim/core/error.hpp"

namespace pcsim::assembly {

namespace {

struct Blocks {
  Mat diagonal = nullptr, off_diagonal = nullptr;
  const PetscInt* off_columns = nullptr;  // global columns of the off-diagonal block
};

Blocks blocks_of(Mat A) {
  Blocks b;
  PetscBool mpi = PETSC_FALSE;
  PCSIM_PETSC(PetscObjectBaseTypeCompare(reinterpret_cast<PetscObject>(A), MATMPIAIJ, &mpi));
  if (mpi)
    PCSIM_PETSC(MatMPIAIJGetSeqAIJ(A, &b.diagonal, &b.off_diagonal, &b.off_columns));
  else
    b.diagonal = A;
  return b;
}

PetscInt stored_entries(Mat A) {
  const Blocks b = blocks_of(A);
  MatInfo info;
  PCSIM_PETSC(MatGetInfo(b.diagonal, MAT_LOCAL, &info));
  PetscInt n = static_cast<PetscInt>(info.nz_allocated);
  if (b.off_diagonal) {
    PCSIM_PETSC(MatGetInfo(b.off_diagonal, MAT_LOCAL, &info));
    n += static_cast<PetscInt>(info.nz_allocated);
  }
  return n;
}

// Position in y of every entry of x (two sorted column lists per row; the
// columns compared through the given global numbers, or as they are).
std::vector<PetscInt> entry_map(Mat y, const PetscInt* y_columns, Mat x,
                                const PetscInt* x_columns) {
  std::vector<PetscInt> map;
  if (!x) return map;
  PetscInt ny, nx;
  const PetscInt *yi, *yj, *xi, *xj;
  PetscBool done;
  PCSIM_PETSC(MatGetRowIJ(y, 0, PETSC_FALSE, PETSC_FALSE, &ny, &yi, &yj, &done));
  PCSIM_PETSC(MatGetRowIJ(x, 0, PETSC_FALSE, PETSC_FALSE, &nx, &xi, &xj, &done));
  map.resize(static_cast<std::size_t>(xi[nx]));
  auto global = [](const PetscInt* numbers, PetscInt c) { return numbers ? numbers[c] : c; };
  bool subset = ny == nx;
  for (PetscInt r = 0; r < nx && subset; ++r) {
    PetscInt p = yi[r];
    for (PetscInt k = xi[r]; k < xi[r + 1] && subset; ++k) {
      const PetscInt c = global(x_columns, xj[k]);
      while (p < yi[r + 1] && global(y_columns, yj[p]) < c) ++p;
      subset = p < yi[r + 1] && global(y_columns, yj[p]) == c;
      map[k] = p;
    }
  }
  PCSIM_PETSC(MatRestoreRowIJ(y, 0, PETSC_FALSE, PETSC_FALSE, &ny, &yi, &yj, &done));
  PCSIM_PETSC(MatRestoreRowIJ(x, 0, PETSC_FALSE, PETSC_FALSE, &nx, &xi, &xj, &done));
  if (!subset) throw SolverError("SubsetAxpy: the pattern of X is not a subset of Y's");
  return map;
}

void add_mapped(Mat y, PetscScalar a, Mat x, const std::vector<PetscInt>& map) {
  if (!x || map.empty()) return;
  PetscScalar* ya;
  const PetscScalar* xa;
  PCSIM_PETSC(MatSeqAIJGetArray(y, &ya));
  PCSIM_PETSC(MatSeqAIJGetArrayRead(x, &xa));
  for (std::size_t k = 0; k < map.size(); ++k) ya[map[k]] += a * xa[k];
  PCSIM_PETSC(MatSeqAIJRestoreArrayRead(x, &xa));
  PCSIM_PETSC(MatSeqAIJRestoreArray(y, &ya));
}

}  // namespace

void SubsetAxpy::map(Mat Y, Mat X) {
  const Blocks y = blocks_of(Y), x = blocks_of(X);
  diagonal_map_ = entry_map(y.diagonal, nullptr, x.diagonal, nullptr);
  off_diagonal_map_.clear();
  if (x.off_diagonal) {
    PetscInt rows, x_cols;
    PCSIM_PETSC(MatGetSize(x.off_diagonal, &rows, &x_cols));
    if (x_cols > 0)
      off_diagonal_map_ = entry_map(y.off_diagonal, y.off_columns, x.off_diagonal, x.off_columns);
  }
  y_ = Y;
  x_ = X;
  y_nonzeros_ = stored_entries(Y);
}

void SubsetAxpy::apply(Mat Y, PetscScalar a, Mat X) {
  // Every rank decides alike (no communication): a new pair or a new Y pattern.
  if (Y != y_ || X != x_ || stored_entries(Y) != y_nonzeros_) map(Y, X);
  const Blocks y = blocks_of(Y), x = blocks_of(X);
  add_mapped(y.diagonal, a, x.diagonal, diagonal_map_);
  add_mapped(y.off_diagonal, a, x.off_diagonal, off_diagonal_map_);
  if (y.off_diagonal) {  // the blocks' states changed, not the MPI matrix's: tell it
    PCSIM_PETSC(MatAssemblyBegin(Y, MAT_FINAL_ASSEMBLY));
    PCSIM_PETSC(MatAssemblyEnd(Y, MAT_FINAL_ASSEMBLY));
  }
}

}  // namespace pcsim::assembly
