#include "pcsim/solvers/direct.hpp"

#include "pcsim/error.hpp"

namespace pcsim::solvers {

void use_direct_lu(KSP ksp, MatSolverType package) {
  PC pc;
  PCSIM_PETSC(KSPSetType(ksp, KSPPREONLY));
  PCSIM_PETSC(KSPGetPC(ksp, &pc));
  PCSIM_PETSC(PCSetType(pc, PCLU));
  PCSIM_PETSC(PCFactorSetMatSolverType(pc, package));
}

}  // namespace pcsim::solvers
