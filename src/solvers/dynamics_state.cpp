// Checkpoint/restart of a dynamic run (DynamicSolver::save_state and
// restore_state): the TS's state and step, the HHT step-size control, the
// state J0 was assembled at, and the terms' own state.
#include <petscts.h>

#include "pcsim/core/error.hpp"
#include "pcsim/core/vec_root.hpp"
#include "pcsim/solvers/dynamics.hpp"
#include "pcsim/solvers/hht.hpp"

namespace pcsim::solvers {

namespace {

void require_hht(TS ts) {
  TSType type;
  PCSIM_PETSC(TSGetType(ts, &type));
  if (std::string(type) != kTSHHT)
    throw InputError("command line", "-ts_type",
                     std::string("checkpoints and restarts need the TS type hht, not ") + type);
}

}  // namespace

DynamicState DynamicSolver::save_state() const {
  require_hht(ts_);
  DynamicState s;
  PetscInt step;
  PetscReal t, dt;
  PCSIM_PETSC(TSGetStepNumber(ts_, &step));
  PCSIM_PETSC(TSGetTime(ts_, &t));
  PCSIM_PETSC(TSGetTimeStep(ts_, &dt));
  s.step = step;
  s.t = t;
  s.time_step = dt;
  const HHTStepControl control = hht_get_step_control(ts_);
  s.user_time_step = control.user_time_step;
  s.accepted_since_cut = control.accepted_since_cut;
  Vec U, V, A = system_.create_vector();
  PCSIM_PETSC(TS2GetSolution(ts_, &U, &V));
  hht_get_acceleration(ts_, A);
  s.U = gather_to_root(U);
  s.V = gather_to_root(V);
  s.A = gather_to_root(A);
  PCSIM_PETSC(VecDestroy(&A));
  s.has_reference = low_rank_ && cached_shift_a_ >= 0;
  if (s.has_reference) {
    s.reference_t = reference_t_;
    s.shift_v = cached_shift_v_;
    s.shift_a = cached_shift_a_;
    s.reference_U = gather_to_root(reference_U_);
    s.reference_V = gather_to_root(reference_V_);
    s.reference_A = gather_to_root(reference_A_);
  }
  Vec F0 = system_.create_vector();
  s.has_alpha_term = hht_get_alpha_term(ts_, F0);  // the same on every rank
  if (s.has_alpha_term) s.alpha_term = gather_to_root(F0);
  PCSIM_PETSC(VecDestroy(&F0));
  s.terms = system_.checkpoint_terms();
  for (const auto& slot : system_.pantographs()) s.head_offsets.push_back(slot.head_offset);
  return s;
}

void DynamicSolver::restore_state(const DynamicState& s) {
  require_hht(ts_);
  auto& pantographs = system_.pantographs();
  if (s.head_offsets.size() != pantographs.size())
    throw SolverError("restore: a state of " + std::to_string(s.head_offsets.size()) +
                      " pantographs for " + std::to_string(pantographs.size()));
  for (std::size_t p = 0; p < pantographs.size(); ++p)
    pantographs[p].head_offset = s.head_offsets[p];
  Vec U = system_.create_vector(), V = system_.create_vector(), A = system_.create_vector();
  scatter_from_root(s.U, U);
  scatter_from_root(s.V, V);
  scatter_from_root(s.A, A);
  PCSIM_PETSC(TS2SetSolution(ts_, U, V));
  PCSIM_PETSC(TSSetTime(ts_, s.t));
  PCSIM_PETSC(TSSetStepNumber(ts_, s.step));
  PCSIM_PETSC(TSSetTimeStep(ts_, s.time_step));
  hht_set_step_control(ts_, {s.user_time_step, static_cast<PetscInt>(s.accepted_since_cut)});
  hht_set_initial_acceleration(ts_, A);
  if (low_rank_ && s.has_reference) {
    // J0 rebuilt at the state it was assembled at: bitwise the same matrix.
    const std::pair<const std::vector<double>*, Vec*> vectors[] = {{&s.reference_U, &reference_U_},
                                                                   {&s.reference_V, &reference_V_},
                                                                   {&s.reference_A, &reference_A_}};
    for (const auto& [values, vec] : vectors) {
      if (!*vec) *vec = system_.create_vector();
      scatter_from_root(*values, *vec);
    }
    reference_t_ = s.reference_t;
    cached_shift_v_ = s.shift_v;
    cached_shift_a_ = s.shift_a;
    system_.reference_jacobian(reference_t_, reference_U_, reference_V_, reference_A_,
                               {s.shift_v, s.shift_a}, P_);
    low_rank_->invalidate();
  }
  // After the reference tangent: the terms' state refers to it.
  system_.restore_terms(s.terms);
  if (s.has_alpha_term) {  // last: it belongs to the solution and time set above
    Vec F0 = system_.create_vector();
    scatter_from_root(s.alpha_term, F0);
    hht_set_alpha_term(ts_, F0);
    PCSIM_PETSC(VecDestroy(&F0));
  }
  PCSIM_PETSC(VecDestroy(&U));
  PCSIM_PETSC(VecDestroy(&V));
  PCSIM_PETSC(VecDestroy(&A));
}

void DynamicSolver::replace_state(const std::vector<double>& U, const std::vector<double>& V,
                                  const std::vector<double>& A) {
  require_hht(ts_);
  Vec Ut, Vt, At = system_.create_vector();
  PCSIM_PETSC(TS2GetSolution(ts_, &Ut, &Vt));
  scatter_from_root(U, Ut);
  scatter_from_root(V, Vt);
  scatter_from_root(A, At);
  hht_set_initial_acceleration(ts_, At);  // the next step starts from it
  PCSIM_PETSC(VecDestroy(&At));
  // A new J0 at the next Jacobian (the bars' frozen switches refer to the old one).
  cached_shift_v_ = cached_shift_a_ = -1;
}

}  // namespace pcsim::solvers
