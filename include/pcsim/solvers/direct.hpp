// Exact linear solves for Newton: a KSP that applies one LU factorisation.
#pragma once

#include <petscksp.h>

#include <string>

namespace pcsim::solvers {

// KSPPREONLY + PCLU with the given factorisation package (MATSOLVERMUMPS,
// MATSOLVERPETSC, ...). Options given later (-ksp_type, -pc_type, ...) win.
void use_direct_lu(KSP ksp, MatSolverType package);

// The step matrices' exact solver, -pcsim_step_solver dd|lu|mumps: the exact
// domain decomposition of schur_dd.hpp (dd, the default; on one rank the LU
// of the whole matrix), PETSc's own LU with QMD ordering (lu, one rank) or
// MUMPS. Call before KSPSetFromOptions (options win).
void use_step_lu(KSP ksp);
// The -pcsim_step_solver choice (checked; default dd).
std::string step_solver_choice(MPI_Comm comm);
// Nonzeros of the factors a set-up step KSP applies, summed over the ranks
// (LU, MUMPS or the domain decomposition's interior factors); 0 if none.
double step_factor_nonzeros(KSP ksp);
// After KSPSetFromOptions and KSPSetOperators: if the KSP factors with MUMPS,
// METIS ordering (ICNTL(7) = 5) unless -<prefix>mat_mumps_icntl_7 says
// otherwise (MatMumpsSetIcntl, not the options database).
void set_mumps_metis_ordering(KSP ksp);

}  // namespace pcsim::solvers
