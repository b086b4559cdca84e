// What the exact domain decomposition (schur_dd.cpp) reads of a distributed
// matrix, and the ranks' counts it gathers.
#pragma once

#include <petscmat.h>

#include <vector>

namespace pcsim::solvers {

// The matrix's diagonal block (owned rows and columns), its off-diagonal
// block and the global numbers of that block's columns.
struct LocalBlocks {
  Mat diagonal = nullptr, off_diagonal = nullptr;
  const PetscInt* off_columns = nullptr;
  PetscInt n_off_columns = 0;
};
LocalBlocks local_blocks(Mat A);

// Every rank's 'mine', in rank order (collective).
std::vector<int> all_counts(MPI_Comm comm, int mine);

}  // namespace pcsim::solvers
