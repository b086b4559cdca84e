#include "pcsim/solvers/direct.hpp"

#include <cstring>
#include <string>

#include "choice_option.hpp"
#include "pcsim/core/error.hpp"
#include "pcsim/solvers/schur_dd.hpp"

namespace pcsim::solvers {

void use_direct_lu(KSP ksp, MatSolverType package) {
  PC pc;
  PCSIM_PETSC(KSPSetType(ksp, KSPPREONLY));
  PCSIM_PETSC(KSPGetPC(ksp, &pc));
  PCSIM_PETSC(PCSetType(pc, PCLU));
  PCSIM_PETSC(PCFactorSetMatSolverType(pc, package));
}

std::string step_solver_choice(MPI_Comm comm) {
  PetscMPIInt size;
  MPI_Comm_size(comm, &size);
  const std::string choice = read_choice_option(
      comm, {"-pcsim_step_solver",
             "pcsim step solver",
             "exact solver of the step matrices: dd (LU of each rank's interior + Schur "
             "complement of the interface, docs/scaling.md), lu (PETSc's LU with QMD ordering, "
             "one rank), mumps",
             "dd",
             {"lu", "dd", "mumps"}});
  if (choice == "lu" && size > 1)
    throw InputError("command line", "-pcsim_step_solver",
                     "lu is PETSc's sequential LU: on several ranks use dd or mumps");
  return choice;
}

void use_step_lu(KSP ksp) {
  const std::string choice =
      step_solver_choice(PetscObjectComm(reinterpret_cast<PetscObject>(ksp)));
  if (choice == "mumps") {
    use_direct_lu(ksp, MATSOLVERMUMPS);
    return;
  }
  if (choice == "dd") {
    use_schur_domain_decomposition(ksp);
    return;
  }
  use_direct_lu(ksp, MATSOLVERPETSC);
  PC pc;
  PCSIM_PETSC(KSPGetPC(ksp, &pc));
  PCSIM_PETSC(PCFactorSetMatOrderingType(pc, MATORDERINGQMD));
}

double step_factor_nonzeros(KSP ksp) {
  PC pc;
  PCSIM_PETSC(KSPGetPC(ksp, &pc));
  PetscBool is_lu = PETSC_FALSE;
  PCSIM_PETSC(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(pc), PCLU, &is_lu));
  if (!is_lu) return domain_decomposition_info(ksp).factor_nonzeros;
  Mat F = nullptr;
  PCSIM_PETSC(PCFactorGetMatrix(pc, &F));
  if (!F) return 0;
  MatInfo info;
  PCSIM_PETSC(MatGetInfo(F, MAT_GLOBAL_SUM, &info));
  return info.nz_used;
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
