#include "pcsim/assembly/coupled_state.hpp"

#include <mpi.h>

#include "pcsim/core/error.hpp"

namespace pcsim::assembly {

CoupledState::CoupledState(CatenaryModel& catenary, std::vector<PantographSlot>& pantographs)
    : catenary_(catenary), pantographs_(pantographs) {
  MPI_Comm_rank(catenary.comm(), &rank_);
  MPI_Comm_size(catenary.comm(), &size_);
  for (const auto& p : pantographs_) n_panto_dofs_ += p.dof_count();
  u_.assign(n_panto_dofs_, 0.0);
  v_.assign(n_panto_dofs_, 0.0);
  a_.assign(n_panto_dofs_, 0.0);
}

Eigen::VectorXd CoupledState::slice(const std::vector<double>& values, std::size_t p) const {
  const auto& slot = pantographs_[p];
  return Eigen::Map<const Eigen::VectorXd>(&values[slot.state_first], slot.dof_count());
}

double CoupledState::head_height(std::size_t p) const {
  const auto& slot = pantographs_[p];
  return u_[slot.state_first + slot.model->contact_dof()] + slot.model->contact_offset() +
         slot.head_offset + slot.model->frame_height(t);
}

void CoupledState::load(double time, Vec U_, Vec V_, Vec A_) {
  t = time;
  U = U_;
  V = V_;
  A = A_;
  catenary_.load_state(U_);
  // The pantographs' unknowns (extras, last rank) to every rank.
  std::vector<double> buffer(3 * n_panto_dofs_, 0.0);
  if (rank_ == size_ - 1) {
    Vec vecs[3] = {U_, V_, A_};
    for (int k = 0; k < 3; ++k) {
      if (!vecs[k]) continue;
      PetscInt lo, hi;
      PCSIM_PETSC(VecGetOwnershipRange(vecs[k], &lo, &hi));
      const PetscScalar* a;
      PCSIM_PETSC(VecGetArrayRead(vecs[k], &a));
      for (PetscInt i = 0; i < n_panto_dofs_; ++i)
        buffer[k * n_panto_dofs_ + i] = a[catenary_.extra_global(i) - lo];
      PCSIM_PETSC(VecRestoreArrayRead(vecs[k], &a));
    }
  }
  if (size_ > 1)
    MPI_Bcast(buffer.data(), static_cast<int>(buffer.size()), MPI_DOUBLE, size_ - 1,
              catenary_.comm());
  std::copy(buffer.begin(), buffer.begin() + n_panto_dofs_, u_.begin());
  std::copy(buffer.begin() + n_panto_dofs_, buffer.begin() + 2 * n_panto_dofs_, v_.begin());
  std::copy(buffer.begin() + 2 * n_panto_dofs_, buffer.end(), a_.begin());
}

}  // namespace pcsim::assembly
