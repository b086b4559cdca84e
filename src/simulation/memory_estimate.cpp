#include "pcsim/simulation/memory_estimate.hpp"

#include <petscsys.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "pcsim/core/error.hpp"

namespace pcsim::simulation {

namespace {

// Calibration (docs/catenary.md, "Memory estimate"): peak resident memory of
// `pcsim static` on EN 50318 lines, 1 and 2 ranks: 10 spans 67 / 60+61 MB,
// 100 spans 226 / 159+180 MB, 1000 spans 1770 MB on 1 rank.
constexpr double kRankBase = 52e6;              // libraries, measured on a 240-DOF design
constexpr double kBytesPerNodePerRank = 2.5e3;  // mesh, node values, MUMPS analysis
constexpr double kBytesPerMatrixEntry = 12;     // AIJ: value + column index
constexpr double kFactorFill = 1.61;            // MUMPS INFOG(29) / nonzeros, 10 and 100 spans
constexpr double kBytesPerFactorEntry = 10;     // value + MUMPS's integer share
// Vectors a Newton step or an eigensolver holds (SNES work vectors, line search).
constexpr double kWorkVectors = 12;

// Nonzeros of the static tangent: 6x6 blocks of a cable node with itself and
// its neighbours, 3x3 blocks of the bars, the dense rows and columns of the
// tension segments and the height rows of form-finding.
double matrix_nonzeros(const catenary::MeshSize& s) {
  const double bar_only_nodes = static_cast<double>(s.nodes - s.cable_nodes);
  double nnz = 36.0 * s.cable_nodes + 72.0 * s.cables + 18.0 * s.bars + 9.0 * bar_only_nodes;
  if (s.form_finding_unknowns > 0) nnz += 12.0 * s.cable_nodes + 16.0 * s.form_finding_unknowns;
  return nnz;
}

// What a command may hold of the machine's memory before it is refused.
constexpr double kMachineShare = 0.9;

// The ranks of 'ranks' on this machine: 'ranks_here' as counted (0: not
// counted, all of them).
int ranks_on_machine(int ranks, int ranks_here) {
  return ranks_here > 0 ? std::min(ranks_here, ranks) : ranks;
}

}  // namespace

MemoryEstimate estimate_memory(const catenary::MeshSize& size, MemoryUse use, int modes) {
  MemoryEstimate e;
  e.nodes = size.nodes;
  e.dofs = size.dofs() + size.form_finding_unknowns;
  e.form_finding_unknowns = size.form_finding_unknowns;
  e.matrix_nonzeros = matrix_nonzeros(size);
  e.factor_entries = kFactorFill * e.matrix_nonzeros;
  const double nnz = e.matrix_nonzeros, dofs = static_cast<double>(e.dofs);
  e.bytes_per_rank = kRankBase + kBytesPerNodePerRank * size.nodes;
  // Statics: the Jacobian, MUMPS's copy of it, the factors, Newton's vectors.
  const double factor = kBytesPerFactorEntry * e.factor_entries;
  double shared = 2 * kBytesPerMatrixEntry * nnz + factor + 8 * kWorkVectors * dofs;
  if (use == MemoryUse::modes) {
    // K, M, the Krylov basis (ncv = max(2 nev, nev + 15) vectors), the mode
    // shapes every rank keeps (3 per node); the factor and the factored
    // copy of K, on several ranks whole on every rank.
    const double ncv = std::max(2.0 * modes, modes + 15.0);
    shared = 2 * kBytesPerMatrixEntry * nnz + 8 * (ncv + kWorkVectors) * dofs;
    e.replicated_bytes = kBytesPerMatrixEntry * nnz + factor;
    e.bytes_per_rank += 24.0 * modes * size.nodes;
  } else if (use == MemoryUse::run) {
    // Step matrix, M, K0 and C, the step matrix's factors (twice MUMPS's fill:
    // PETSc's LU on one rank), HHT's and the low-rank solver's vectors.
    shared = 5 * kBytesPerMatrixEntry * nnz + 2 * factor + 8 * 3 * kWorkVectors * dofs;
  }
  e.shared_bytes = shared;
  return e;
}

double machine_memory_bytes() {
  PetscBool initialized = PETSC_FALSE, given = PETSC_FALSE;
  PetscReal mb = 0;
  if (PetscInitialized(&initialized) == 0 && initialized &&
      PetscOptionsGetReal(nullptr, nullptr, "-pcsim_debug_machine_memory_mb", &mb, &given) == 0 &&
      given)
    return mb * 1024.0 * 1024.0;
  std::ifstream meminfo("/proc/meminfo");
  std::string line;
  while (std::getline(meminfo, line)) {
    std::istringstream in(line);
    std::string key;
    double kib = 0;
    if (in >> key >> kib && key == "MemTotal:") return kib * 1024.0;
  }
  return 0;
}

void check_memory(const catenary::MeshSize& size, MemoryUse use, int ranks, double machine_bytes,
                  int modes, int ranks_here) {
  if (machine_bytes <= 0) return;
  const MemoryEstimate e = estimate_memory(size, use, modes);
  const int here = ranks_on_machine(ranks, ranks_here);
  const double need = e.node_bytes(ranks, here), limit = kMachineShare * machine_bytes;
  if (need <= limit) return;
  char ranks_text[64];
  if (here == ranks)
    std::snprintf(ranks_text, sizeof ranks_text, "%d rank(s)", ranks);
  else
    std::snprintf(ranks_text, sizeof ranks_text, "the %d of %d ranks on this machine", here, ranks);
  char text[480];
  std::snprintf(text, sizeof text,
                "the mesh is too large for this machine: %ld nodes, %ld unknowns, %.3g matrix "
                "nonzeros and %.3g factor entries need an estimated %.1f GB on %s, more "
                "than 90%% of the machine's %.1f GB (/proc/meminfo MemTotal); use fewer spans or "
                "longer elements",
                e.nodes, e.dofs, e.matrix_nonzeros, e.factor_entries, need / 1e9, ranks_text,
                machine_bytes / 1e9);
  throw InputError(size.file, size.key, text);
}

double resident_memory_bytes() {
  std::ifstream statm("/proc/self/statm");
  double pages = 0, resident = 0;
  if (!(statm >> pages >> resident)) return 0;
  return resident * static_cast<double>(sysconf(_SC_PAGESIZE));
}

double modal_basis_bytes(const ModalMemoryNeed& need) {
  const double v = static_cast<double>(need.vectors);
  const double lower = static_cast<double>(std::max(need.modes - need.computed, 0L));
  const double rows = 8.0 * static_cast<double>(need.rows) * (v + lower);
  const double chunk = std::min(kEigensolverVectors,
                                kEigensolverVectorsPerMode * static_cast<double>(need.computed));
  return rows + 8.0 * chunk * static_cast<double>(need.dofs) + (need.window ? 8.0 * v * v : 0.0);
}

void check_modal_memory(const ModalMemoryNeed& need, double resident_bytes, int ranks,
                        int ranks_here, double machine_bytes, const std::string& file,
                        const std::string& key) {
  if (machine_bytes <= 0) return;
  const double basis = modal_basis_bytes(need);
  const int here = ranks_on_machine(ranks, ranks_here);
  const double total = here * (resident_bytes + basis), limit = kMachineShare * machine_bytes;
  if (total <= limit) return;
  char text[512];
  std::snprintf(text, sizeof text,
                "%ld vectors (%ld modes below %.1f Hz and the droppers' shapes) over %ld kept rows "
                "need about %.2f GB while the basis is formed, beside the %.2f GB in use, on each "
                "of %d rank(s) here: %.2f GB, more than 90%% of the machine's %.2f GB",
                need.vectors, need.modes, need.cutoff_hz, need.rows, basis / 1e9,
                resident_bytes / 1e9, here, total / 1e9, machine_bytes / 1e9);
  throw ModalMemoryError(file, key,
                         std::string("the modal level's basis would not fit in this machine's "
                                     "memory: ") +
                             text +
                             "; use catenary.model: linear, a lower catenary.max_frequency_hz "
                             "or fewer spans",
                         text);
}

}  // namespace pcsim::simulation
