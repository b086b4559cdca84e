// The state the terms of the coupled system read: time, the state vectors,
// the catenary model (loaded at U) and every pantograph's coordinates
// (replicated on all ranks; the pantographs' unknowns live on the last rank).
#pragma once

#include <petscvec.h>

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "pcsim/assembly/catenary_model.hpp"
#include "pcsim/contact/pantograph_run.hpp"
#include "pcsim/pantograph/model.hpp"

namespace pcsim::assembly {

// One pantograph of the run: how it travels, its model and where its
// unknowns are.
struct PantographSlot {
  contact::PantographRun run;
  std::unique_ptr<pantograph::PantographModel> model;
  PetscInt first_dof = 0;    // global index of q[0]
  PetscInt state_first = 0;  // index of q[0] in the replicated pantograph state
  // contact height = q[c] + model->contact_offset() + head_offset + model->frame_height(t)
  double head_offset = 0;

  PetscInt contact_dof() const { return first_dof + model->contact_dof(); }
  int dof_count() const { return model->dof_count(); }
};

class CoupledState {
 public:
  CoupledState(CatenaryModel& catenary, std::vector<PantographSlot>& pantographs);

  double t = 0;
  Vec U = nullptr, V = nullptr, A = nullptr;  // V and A may be null (records, energy)

  const CatenaryModel& catenary() const { return catenary_; }
  std::size_t pantograph_count() const { return pantographs_.size(); }
  const PantographSlot& pantograph(std::size_t p) const { return pantographs_[p]; }
  // q, q', q'' of pantograph p (zero where the vector was not given).
  Eigen::VectorXd q(std::size_t p) const { return slice(u_, p); }
  Eigen::VectorXd qd(std::size_t p) const { return slice(v_, p); }
  Eigen::VectorXd qdd(std::size_t p) const { return slice(a_, p); }
  // Height of pantograph p's contact point at t (a moving frame's z_b(t) included).
  double head_height(std::size_t p) const;
  bool on_last_rank() const { return rank_ == size_ - 1; }
  int rank() const { return rank_; }
  int size() const { return size_; }

  // Loads (t, U, V, A): the catenary model's state and the pantographs'
  // coordinates on every rank (collective).
  void load(double time, Vec U_, Vec V_, Vec A_);

 private:
  Eigen::VectorXd slice(const std::vector<double>& values, std::size_t p) const;
  CatenaryModel& catenary_;
  std::vector<PantographSlot>& pantographs_;
  PetscInt n_panto_dofs_ = 0;
  std::vector<double> u_, v_, a_;
  int rank_ = 0, size_ = 1;
};

}  // namespace pcsim::assembly
