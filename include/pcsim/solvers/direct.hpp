// Exact linear solves for Newton: a KSP that applies one LU factorisation.
#pragma once

#include <petscksp.h>

namespace pcsim::solvers {

// KSPPREONLY + PCLU with the given factorisation package (MATSOLVERMUMPS,
// MATSOLVERPETSC, ...). Options given later (-ksp_type, -pc_type, ...) win.
void use_direct_lu(KSP ksp, MatSolverType package);

// The step matrices' LU: PETSc's own with quotient-minimum-degree ordering on
// one rank, MUMPS in parallel. Call before KSPSetFromOptions (options win).
void use_step_lu(KSP ksp);
// After KSPSetFromOptions and KSPSetOperators: if the KSP factors with MUMPS,
// METIS ordering (ICNTL(7) = 5) unless -<prefix>mat_mumps_icntl_7 says
// otherwise (MatMumpsSetIcntl, not the options database).
void set_mumps_metis_ordering(KSP ksp);

}  // namespace pcsim::solvers
