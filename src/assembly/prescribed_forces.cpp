#include "pcsim/assembly/prescribed_forces.hpp"

#include <mpi.h>

#include "pcsim/core/error.hpp"

namespace pcsim::assembly {

PrescribedHeadForces::PrescribedHeadForces(const std::vector<PantographSlot>& pantographs)
    : pantographs_(pantographs), force_(pantographs.size(), 0.0) {}

void PrescribedHeadForces::add_residual(const CoupledState& state, Vec F) {
  if (!state.on_last_rank()) return;
  for (std::size_t p = 0; p < pantographs_.size(); ++p) {
    if (force_[p] == 0) continue;
    const PetscInt dof = pantographs_[p].contact_dof();
    const double value = -force_[p];  // an upward load lowers the residual (R = M a + ... - f)
    PCSIM_PETSC(VecSetValues(F, 1, &dof, &value, ADD_VALUES));
  }
}

TermPower PrescribedHeadForces::power(const CoupledState& state) const {
  double local = 0;
  if (state.on_last_rank())
    for (std::size_t p = 0; p < pantographs_.size(); ++p)
      local += force_[p] * state.qd(p)[pantographs_[p].model->contact_dof()];
  TermPower power;
  MPI_Allreduce(&local, &power.external, 1, MPI_DOUBLE, MPI_SUM, state.catenary().comm());
  return power;
}

}  // namespace pcsim::assembly
