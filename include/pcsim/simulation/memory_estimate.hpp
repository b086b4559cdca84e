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
#include <utility>

#include "pcsim/catenary/geometry.hpp"
#include "pcsim/core/error.hpp"

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
// The tests' -pcsim_debug_machine_memory_mb stands for it when given.
double machine_memory_bytes();

// This process's resident memory now [bytes] (/proc/self/statm); 0 if unknown.
double resident_memory_bytes();

// Throws InputError(size.file, size.key, ...) when the estimate for the
// 'ranks_here' of 'ranks' ranks on this machine (0: all of them) exceeds 90 %
// of 'machine_bytes' (skipped when machine_bytes is 0).
void check_memory(const catenary::MeshSize& size, MemoryUse use, int ranks, double machine_bytes,
                  int modes = 20, int ranks_here = 0);

struct ModalMemoryNeed {
  long rows = 0, vectors = 0, modes = 0;  // vectors: modes and shapes
  long computed = 0;  // of the modes, those computed now (the others kept from a lower cut-off)
  long dofs = 0;      // the catenary's unknowns (the eigensolver's vectors' length)
  double cutoff_hz = 0;
  bool window = false;
};

// The modal level's basis while it is formed (simulation/catenary_setup.cpp):
// its rows ('vectors' basis vectors over 'rows' kept rows, in double), stored
// once as the modes are computed and the basis formed in their storage
// (simulation/mode_row_store.hpp), and at a raised cut-off the lower one's
// rows (modes - computed) beside that room while they move into it (an
// accuracy pilot's raise, simulation/modal_basis.hpp); the eigensolver's
// vectors over the catenary's unknowns while it computes a chunk of about 800 modes
// (modal_basis_internal.hpp, kChunkModes): kEigensolverVectors, or
// kEigensolverVectorsPerMode for each mode computed where fewer; with a
// moving window the shift products (vectors^2 doubles, then P in floats).
// The eigensolver's counts are measured: first-run peaks against the
// estimate in docs/fidelity.md, "Memory of the modal basis".
constexpr double kEigensolverVectors = 2000;
constexpr double kEigensolverVectorsPerMode = 2.5;
double modal_basis_bytes(const ModalMemoryNeed& need);

// What check_modal_memory refuses: an InputError of the scene's key.
class ModalMemoryError : public InputError {
 public:
  ModalMemoryError(std::string file, std::string key, std::string reason, std::string needed)
      : InputError(std::move(file), std::move(key), std::move(reason)),
        needed_(std::move(needed)) {}
  // The need against the machine, without the advice (the pilot's raise).
  const std::string& needed() const { return needed_; }

 private:
  std::string needed_;
};

// Throws ModalMemoryError(file, key, ...) when the 'ranks_here' of 'ranks'
// ranks on this machine (0: all of them), each holding 'resident_bytes' now
// and the whole basis (every rank holds it), would exceed 90 % of
// 'machine_bytes' (skipped when it is 0), as check_memory.
void check_modal_memory(const ModalMemoryNeed& need, double resident_bytes, int ranks,
                        int ranks_here, double machine_bytes, const std::string& file,
                        const std::string& key);

}  // namespace pcsim::simulation
