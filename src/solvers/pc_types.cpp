#include "pc_types.hpp"

#include <cstring>

#include "pcsim/core/error.hpp"

namespace pcsim::solvers {

void register_pc_type(const char* name, PetscErrorCode (*create)(PC)) {
  PCSIM_PETSC(PCInitializePackage());
  PetscErrorCode (*existing)(PC) = nullptr;
  PCSIM_PETSC(PetscFunctionListFind(PCList, name, &existing));
  if (!existing) PCSIM_PETSC(PCRegister(name, create));
}

bool preonly_with(KSP ksp, std::initializer_list<const char*> pc_types) {
  KSPType ksp_type;
  PCType pc_type;
  PC pc;
  PCSIM_PETSC(KSPGetType(ksp, &ksp_type));
  PCSIM_PETSC(KSPGetPC(ksp, &pc));
  PCSIM_PETSC(PCGetType(pc, &pc_type));
  if (!ksp_type || !pc_type || std::strcmp(ksp_type, KSPPREONLY) != 0) return false;
  for (const char* type : pc_types)
    if (std::strcmp(pc_type, type) == 0) return true;
  return false;
}

}  // namespace pcsim::solvers
