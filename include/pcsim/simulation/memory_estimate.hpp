// Memory a command will need, estimated from the size of the catenary mesh
// before anything is allocated, and the check against the machine's memory.
//
// The model counts what grows with the mesh: per rank, the libraries (PETSc,
// SLEPc, MPI, MUMPS) and the data every rank holds for every node (the mesh,
// node values, MUMPS's analysis on the host); shared over the ranks, the
// sparse matrices (12 bytes per nonzero each) and the LU/Cholesky factors
// (fill measured with MUMPS's INFOG(29) on EN 50318 lines of 10 and 100 spans:
// 1.61 entries per matrix nonzero); the modes' factor whole on every rank. Calibrated against the
// peak resident memory of `pcsim static`, `modes` and `run` on 10, 100 and 1000 spans (README
// "Benchmarks"; the table is in docs/catenary.md, "Memory estimate").
#pragma once

#include <algorithm>
#include <string>

#include "pcsim/catenary/geometry.hpp"

namespace pcsim::simulation {

enum class MemoryUse { statics, modes, run };

struct MemoryEstimate {
  long nodes = 0;
  long dofs = 0;                   // catenary unknowns (+ form-finding unknowns)
  long form_finding_unknowns = 0;  // of these, the form-finding ones (static solution only)
  double matrix_nonzeros = 0;      // of the static tangent
  double factor_entries = 0;       // of its LU factors
  double bytes_per_rank = 0;       // held by every rank (libraries, per-node data)
  double shared_bytes = 0;         // divided among the ranks (matrices, factors, vectors)
  // Held once on one rank and whole by every rank on several (the modes'
  // factor, a copy on every rank: solvers/spectrum.hpp).
  double replicated_bytes = 0;
  double total_bytes(int ranks) const {
    return ranks * bytes_per_rank + shared_bytes + std::max(ranks, 1) * replicated_bytes;
  }
  // What the 'ranks_here' of a run's 'ranks' on one node hold: theirs and
  // their share of the shared data (total_bytes(ranks) when all are there).
  double node_bytes(int ranks, int ranks_here) const {
    return ranks_here * (bytes_per_rank + replicated_bytes) +
           shared_bytes * ranks_here / std::max(ranks, 1);
  }
};

// 'modes' is the number of modes asked for (MemoryUse::modes only).
MemoryEstimate estimate_memory(const catenary::MeshSize& size, MemoryUse use, int modes = 20);

// Total memory of this machine [bytes] (/proc/meminfo MemTotal); 0 if unknown.
double machine_memory_bytes();

// Throws InputError(size.file, size.key, ...) when the estimate for the
// 'ranks_here' of 'ranks' ranks on this machine (0: all of them) exceeds 90 %
// of 'machine_bytes' (skipped when machine_bytes is 0).
void check_memory(const catenary::MeshSize& size, MemoryUse use, int ranks, double machine_bytes,
                  int modes = 20, int ranks_here = 0);

}  // namespace pcsim::simulation
