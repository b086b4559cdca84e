// Exact domain-decomposition solve of a distributed sparse matrix
// (docs/scaling.md "The parallel step"): every rank's owned unknowns are
// split into interior ones I_r (coupled only to unknowns of the same rank)
// and interface ones G_r (coupled to another rank's). In the order
// [I_1 .. I_p, G] the matrix is block-arrowhead, and
//
//   S = A_GG - sum_r A_{G I_r} A_{I_r I_r}^-1 A_{I_r G}      (Schur complement)
//
// is small (a few unknowns per cut of the quasi-1D catenary). Set-up, once per
// matrix: each rank factors A_{I_r I_r} (sequential LU, options prefix
// pcsim_dd_: -pcsim_dd_pc_factor_mat_ordering_type ...), forms
// X_r = A_{I_r I_r}^-1 A_{I_r G_r} and its rows of S (their nonzeros); one
// MPI_Allgatherv of those rows puts the sparse S on every rank, ordered
// banded (reverse Cuthill-McKee: the cuts follow each other along the track)
// and LU-factored by PETSc (src/solvers/interface_solve.hpp).
// Solve: y = A_II^-1 r_I (local), g = r_G - A_GI y (local), one
// MPI_Allgatherv of g, x_G = S^-1 g (replicated), x_I = y - X x_G (local).
// The result is the exact solution (round-off only).
#pragma once

#include <petscksp.h>

namespace pcsim::solvers {

// The PC type of this solve (-pc_type pcsimschur, -cheap_pc_type ...): it
// owns its factors (freed with the PC).
inline constexpr const char* kPCSchur = "pcsimschur";
void register_schur_pc();  // PCRegister once (idempotent)

// Makes the KSP apply the exact domain-decomposition solve: KSPPREONLY + a
// pcsimschur PC. Options given later win.
void use_schur_domain_decomposition(KSP ksp);

// Nonzeros of the interior factors summed over the ranks, and the Schur
// complement's size, bandwidth (in the order it is factored in) and entries,
// of a KSP set up with use_schur_domain_decomposition (zeros for any other).
struct DomainDecompositionInfo {
  double factor_nonzeros = 0;
  PetscInt interface_size = 0;
  PetscInt interface_bandwidth = 0;  // max |i - j| over S's entries, ordered
  PetscInt interface_nonzeros = 0;   // S's entries (gathered at each set-up)
  // X = A_II^-1 A_IG: its entries on all ranks, and those stored (its
  // negligible ones left out where that halves them: src/solvers/negligible_entries.hpp).
  double correction_entries = 0, correction_stored = 0;
};
DomainDecompositionInfo domain_decomposition_info(KSP ksp);

}  // namespace pcsim::solvers
