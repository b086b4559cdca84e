#include "pcsim/solvers/direct.hpp"

#include <cstring>

#include "pcsim/core/error.hpp"

namespace pcsim::solvers {

void use_direct_lu(KSP ksp, MatSolverType package) {
  PC pc;
  PCSIM_PETSC(KSPSetType(ksp, KSPPREONLY));
  PCSIM_PETSC(KSPGetPC(ksp, &pc));
  PCSIM_PETSC(PCSetType(pc, PCLU));
  PCSIM_PETSC(PCFactorSetMatSolverType(pc, package));
}

void use_step_lu(KSP ksp) {
  PetscMPIInt size;
  MPI_Comm_size(PetscObjectComm(reinterpret_cast<PetscObject>(ksp)), &size);
  if (size > 1) {
    use_direct_lu(ksp, MATSOLVERMUMPS);
    return;
  }
  use_direct_lu(ksp, MATSOLVERPETSC);
  PC pc;
  PCSIM_PETSC(KSPGetPC(ksp, &pc));
  PCSIM_PETSC(PCFactorSetMatOrderingType(pc, MATORDERINGQMD));
}

void set_mumps_metis_ordering(KSP ksp) {
  PC pc;
  PCSIM_PETSC(KSPGetPC(ksp, &pc));
  PetscBool is_lu = PETSC_FALSE;
  PCSIM_PETSC(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(pc), PCLU, &is_lu));
  if (!is_lu) return;
  MatSolverType package = nullptr;
  PCSIM_PETSC(PCFactorGetMatSolverType(pc, &package));
  if (!package || std::strcmp(package, MATSOLVERMUMPS) != 0) return;
  PCSIM_PETSC(PCFactorSetUpMatSolverType(pc));
  Mat F;
  PCSIM_PETSC(PCFactorGetMatrix(pc, &F));
  // MUMPS reads -mat_mumps_icntl_7 at the symbolic factorisation, with this
  // value as the default: a user's option still wins.
  PCSIM_PETSC(MatMumpsSetIcntl(F, 7, 5));
}

}  // namespace pcsim::solvers
