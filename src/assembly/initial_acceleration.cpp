#include "pcsim/assembly/initial_acceleration.hpp"

#include <mpi.h>

#include <Eigen/Dense>

#include "pcsim/core/error.hpp"

namespace pcsim::assembly {

void initial_acceleration(assembly::CoupledSystem& system, Vec U0, Vec V0, Vec A0) {
  Vec F = system.create_vector();
  PCSIM_PETSC(VecSet(A0, 0.0));
  system.residual(0.0, U0, V0, A0, F);
  PetscInt lo, hi;
  PCSIM_PETSC(VecGetOwnershipRange(F, &lo, &hi));
  for (auto& slot : system.pantographs()) {
    if (slot.run.start_gap <= 0) continue;  // started in equilibrium: A0 = 0
    // The pantograph's rows of F, q and q' on every rank.
    const int n = slot.dof_count();
    Eigen::VectorXd rows[3] = {Eigen::VectorXd::Zero(n), Eigen::VectorXd::Zero(n),
                               Eigen::VectorXd::Zero(n)};
    Vec sources[3] = {F, U0, V0};
    for (int k = 0; k < 3; ++k)
      for (int i = 0; i < n; ++i)
        if (slot.first_dof + i >= lo && slot.first_dof + i < hi) {
          const PetscInt row = slot.first_dof + i;
          PCSIM_PETSC(VecGetValues(sources[k], 1, &row, &rows[k][i]));
        }
    for (auto& r : rows)
      MPI_Allreduce(MPI_IN_PLACE, r.data(), n, MPI_DOUBLE, MPI_SUM, system.comm());
    Eigen::MatrixXd dq(n, n), dqd(n, n), mass(n, n);
    slot.model->tangents(0.0, rows[1], rows[2], Eigen::VectorXd::Zero(n), dq, dqd, mass);
    const Eigen::VectorXd a0 = mass.lu().solve(-rows[0]);
    for (int i = 0; i < n; ++i)
      if (slot.first_dof + i >= lo && slot.first_dof + i < hi)
        PCSIM_PETSC(VecSetValue(A0, slot.first_dof + i, a0[i], INSERT_VALUES));
  }
  PCSIM_PETSC(VecAssemblyBegin(A0));
  PCSIM_PETSC(VecAssemblyEnd(A0));
  PCSIM_PETSC(VecDestroy(&F));
}

}  // namespace pcsim::assembly
