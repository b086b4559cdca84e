// The terms of a moving window's ends (assembly/catenary_terms.hpp): dashpots
// and pins from nodes to the ground.
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

NodeDashpots::~NodeDashpots() {
  MatDestroy(&C_);
}

TermPower NodeDashpots::power(const CoupledState& state) const {
  TermPower p;
  if (state.V) p.dissipative = -quadratic_form(C_, state.V);
  return p;
}

template <class F>
void NodePins::for_owned_active(F f) const {
  const auto& layout = catenary_.system().layout();
  const auto& values = catenary_.static_node_values();
  for (const auto& pin : catenary_.mesh().pins) {
    if (!pin.active || layout.owner(pin.node) != layout.rank()) continue;
    const PetscInt g = layout.global_dof(pin.node, pin.dof);
    if (g < 0) throw SolverError("node pin on a fixed DOF (node " + std::to_string(pin.node) + ")");
    f(g - layout.first_owned(), g, pin.stiffness, values[catenary::kNodeDofs * pin.node + pin.dof]);
  }
}

void NodePins::add_residual(const CoupledState& state, Vec F) {
  const PetscScalar* u;
  PetscScalar* f;
  PCSIM_PETSC(VecGetArrayRead(state.U, &u));
  PCSIM_PETSC(VecGetArray(F, &f));
  for_owned_active(
      [&](PetscInt local, PetscInt, double k, double u0) { f[local] += k * (u[local] - u0); });
  PCSIM_PETSC(VecRestoreArray(F, &f));
  PCSIM_PETSC(VecRestoreArrayRead(state.U, &u));
}

void NodePins::add_tangent(const CoupledState&, Shifts, Mat J) {
  for_owned_active([&](PetscInt, PetscInt g, double k, double) {
    PCSIM_PETSC(MatSetValue(J, g, g, k, ADD_VALUES));
  });
}

double NodePins::energy(const CoupledState& state) const {
  const PetscScalar* u;
  PCSIM_PETSC(VecGetArrayRead(state.U, &u));
  double e = 0;
  for_owned_active([&](PetscInt local, PetscInt, double k, double u0) {
    e += 0.5 * k * (u[local] - u0) * (u[local] - u0);
  });
  PCSIM_PETSC(VecRestoreArrayRead(state.U, &u));
  MPI_Allreduce(MPI_IN_PLACE, &e, 1, MPI_DOUBLE, MPI_SUM, catenary_.comm());
  return e;
}

}  // namespace pcsim::assembly
