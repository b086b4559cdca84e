// pcsim's own PETSc PC types (pcsimwoodbury: low_rank.cpp; pcsimschur:
// schur_dd.cpp), made through PETSc's private PC interface (its ops and
// data), as PETSc's own types are: registered once with PCRegister, so that
// -pc_type and -help know them.
#pragma once

#include <petsc/private/pcimpl.h>

#include <initializer_list>

namespace pcsim::solvers {

struct PCTypeOps {
  PetscErrorCode (*setup)(PC);
  PetscErrorCode (*apply)(PC, Vec, Vec);
  PetscErrorCode (*destroy)(PC);
  PetscErrorCode (*view)(PC, PetscViewer);
};

// A new PC of the type: these ops, no data yet.
inline void set_pc_type_ops(PC pc, const PCTypeOps& ops) {
  pc->data = nullptr;
  pc->ops->setup = ops.setup;
  pc->ops->apply = ops.apply;
  pc->ops->destroy = ops.destroy;
  pc->ops->view = ops.view;
}

// PCRegister(name, create) unless the type is known already.
void register_pc_type(const char* name, PetscErrorCode (*create)(PC));

// True when ksp applies its PC once (preonly) and that PC's type is one of
// pc_types (the step solvers' exactness checks).
bool preonly_with(KSP ksp, std::initializer_list<const char*> pc_types);

}  // namespace pcsim::solvers
