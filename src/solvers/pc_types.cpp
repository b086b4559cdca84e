#include "pc_types.hpp"

#include "pcsim/core/error.hpp"

namespace pcsim::solvers {

void register_pc_type(const char* name, PetscErrorCode (*create)(PC)) {
  PCSIM_PETSC(PCInitializePackage());
  PetscErrorCode (*existing)(PC) = nullptr;
  PCSIM_PETSC(PetscFunctionListFind(PCList, name, &existing));
  if (!existing) PCSIM_PETSC(PCRegister(name, create));
}

}  // namespace pcsim::solvers
