// Rank 0's data on every rank: a distributed vector's entries gathered on
// rank 0 and scattered back (checkpoints, the moving window's shift), and a
// text broadcast (outcomes decided on rank 0). Collective.
#pragma once

#include <petscvec.h>

#include <string>
#include <vector>

namespace pcsim {

// The entries of x in global order on rank 0, empty elsewhere.
std::vector<double> gather_to_root(Vec x);
// x from rank 0's entries in global order (other ranks' ignored); a
// SolverError on every rank if rank 0's count differs from x's size.
void scatter_from_root(const std::vector<double>& values, Vec x);
// Rank root's text, on every rank of comm.
std::string broadcast_text(MPI_Comm comm, std::string text, int root = 0);

}  // namespace pcsim
