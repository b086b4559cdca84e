// Dashpots from nodes to the ground (assembly/catenary_terms.hpp).
#include "pcsim/assembly/catenary_terms.hpp"
#include "pcsim/assembly/coupled_state.hpp"
#include "pcsim/core/error.hpp"

namespace pcsim::assembly {

NodeDashpots::NodeDashpots(FECatenary& catenary) {
  const auto& layout = catenary.system().layout();
  C_ = layout.create_matrix();  // the catenary's pattern: its diagonal is in the Jacobian's
  for (const auto& d : catenary.mesh().dashpots) {
    const PetscInt g = layout.global_dof(d.node, d.dof);
    if (g < 0)
      throw SolverError("node dashpot on a fixed DOF (node " + std::to_string(d.node) + ")");
    if (layout.owner(d.node) == layout.rank())
      PCSIM_PETSC(MatSetValue(C_, g, g, d.coefficient, ADD_VALUES));
  }
  PCSIM_PETSC(MatAssemblyBegin(C_, MAT_FINAL_ASSEMBLY));
  PCSIM_PETSC(MatAssemblyEnd(C_, MAT_FINAL_ASSEMBLY));
}

NodeDashpots::~NodeDashpots() { MatDestroy(&C_); }

TermPower NodeDashpots::power(const CoupledState& state) const {
  TermPower p;
  if (!state.V) return p;
  Vec CV;
  PCSIM_PETSC(VecDuplicate(state.V, &CV));
  PCSIM_PETSC(MatMult(C_, state.V, CV));
  PetscScalar vcv = 0;
  PCSIM_PETSC(VecDot(state.V, CV, &vcv));
  p.dissipative = -vcv;
  PCSIM_PETSC(VecDestroy(&CV));
  return p;
}

}  // namespace pcsim::assembly
