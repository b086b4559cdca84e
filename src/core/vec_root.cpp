#include "pcsim/core/vec_root.hpp"

#include <algorithm>
#include <string>

#include "pcsim/core/error.hpp"

namespace pcsim {

// The entries of x in global order on rank 0, empty elsewhere (collective).
std::vector<double> gather_to_root(Vec x) {
  VecScatter scatter;
  Vec all;
  PCSIM_PETSC(VecScatterCreateToZero(x, &scatter, &all));
  PCSIM_PETSC(VecScatterBegin(scatter, x, all, INSERT_VALUES, SCATTER_FORWARD));
  PCSIM_PETSC(VecScatterEnd(scatter, x, all, INSERT_VALUES, SCATTER_FORWARD));
  PetscInt n;
  PCSIM_PETSC(VecGetLocalSize(all, &n));
  const PetscScalar* a;
  PCSIM_PETSC(VecGetArrayRead(all, &a));
  std::vector<double> out(a, a + n);
  PCSIM_PETSC(VecRestoreArrayRead(all, &a));
  PCSIM_PETSC(VecScatterDestroy(&scatter));
  PCSIM_PETSC(VecDestroy(&all));
  return out;
}

// x from rank 0's entries in global order (collective; other ranks' ignored).
void scatter_from_root(const std::vector<double>& values, Vec x) {
  VecScatter scatter;
  Vec all;
  PCSIM_PETSC(VecScatterCreateToZero(x, &scatter, &all));
  PetscInt n;
  PCSIM_PETSC(VecGetLocalSize(all, &n));
  int bad = static_cast<std::size_t>(n) != values.size() ? 1 : 0;
  MPI_Bcast(&bad, 1, MPI_INT, 0, PetscObjectComm(reinterpret_cast<PetscObject>(x)));
  if (bad) {
    VecScatterDestroy(&scatter);
    VecDestroy(&all);
    throw SolverError("restore: a vector of " + std::to_string(values.size()) +
                      " values for a system of another size");
  }
  PetscScalar* a;
  PCSIM_PETSC(VecGetArray(all, &a));
  std::copy(values.begin(), values.end(), a);
  PCSIM_PETSC(VecRestoreArray(all, &a));
  PCSIM_PETSC(VecScatterBegin(scatter, all, x, INSERT_VALUES, SCATTER_REVERSE));
  PCSIM_PETSC(VecScatterEnd(scatter, all, x, INSERT_VALUES, SCATTER_REVERSE));
  PCSIM_PETSC(VecScatterDestroy(&scatter));
  PCSIM_PETSC(VecDestroy(&all));
}

std::string broadcast_text(MPI_Comm comm, std::string text, int root) {
  int size = static_cast<int>(text.size());
  MPI_Bcast(&size, 1, MPI_INT, root, comm);
  text.resize(static_cast<std::size_t>(size));
  MPI_Bcast(text.data(), size, MPI_CHAR, root, comm);
  return text;
}

}  // namespace pcsim
