// Exact linear solves for Newton: a KSP that applies one LU factorisation.
#pragma once

#include <petscksp.h>

namespace pcsim::solvers {

// KSPPREONLY + PCLU with the given factorisation package (MATSOLVERMUMPS,
// MATSOLVERPETSC, ...). Options given later (-ksp_type, -pc_type, ...) win.
void use_direct_lu(KSP ksp, MatSolverType package);

}  // namespace pcsim::solvers
