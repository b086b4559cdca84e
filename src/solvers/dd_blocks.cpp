#include "dd_blocks.hpp"

#include "pcsim/core/error.hpp"

namespace pcsim::solvers {

LocalBlocks local_blocks(Mat A) {
  LocalBlocks b;
  PetscBool mpi = PETSC_FALSE;
  PCSIM_PETSC(PetscObjectBaseTypeCompare(reinterpret_cast<PetscObject>(A), MATMPIAIJ, &mpi));
  if (!mpi) {
    b.diagonal = A;
    return b;
  }
  PCSIM_PETSC(MatMPIAIJGetSeqAIJ(A, &b.diagonal, &b.off_diagonal, &b.off_columns));
  PetscInt rows;
  PCSIM_PETSC(MatGetSize(b.off_diagonal, &rows, &b.n_off_columns));
  return b;
}

std::vector<int> all_counts(MPI_Comm comm, int mine) {
  int size;
  MPI_Comm_size(comm, &size);
  std::vector<int> counts(size);
  MPI_Allgather(&mine, 1, MPI_INT, counts.data(), 1, MPI_INT, comm);
  return counts;
}

}  // namespace pcsim::solvers
