// The HHT-alpha type's alpha-term taken from the previous step's last residual
// (-ts_hht_reuse_alpha_term, include/pcsim/solvers/hht.hpp). A step's residual at the
// converged U_{n+1} is
//   R = F(t_{n+1}, U_{n+1}, V_{n+1}, A_{n+1}/(1-α)) + α/(1-α) F0,
// so with F affine in A and dF/dA = M(t, U, V) (constant, or a configuration-
// dependent mass: the DSA-380's, thesis 3.27-3.30) the next step's alpha-term is
//   F(t_{n+1}, U_{n+1}, V_{n+1}, 0) = R - α/(1-α) F0 - M(U_{n+1}) A_{n+1}/(1-α):
// one product with M instead of a residual (equal up to round-off).
#include "hht_data.hpp"

namespace pcsim::solvers::hht_detail {

namespace {

PetscObjectState state_of(Vec v) {
  PetscObjectState state = 0;
  PetscObjectStateGet(reinterpret_cast<PetscObject>(v), &state);
  return state;
}

}  // namespace

PetscErrorCode stamp_next_alpha_term(TS ts) {
  HHTData* th = data_of(ts);
  PetscFunctionBeginUser;
  th->next_U = ts->vec_sol;
  th->next_V = ts->vec_dot;
  th->next_U_state = state_of(ts->vec_sol);
  th->next_V_state = state_of(ts->vec_dot);
  th->next_time = ts->ptime;
  th->next_valid = PETSC_TRUE;
  PetscFunctionReturn(0);
}

PetscBool next_alpha_term_current(TS ts) {
  const HHTData* th = data_of(ts);
  return th->next_valid && ts->vec_sol == th->next_U && ts->vec_dot == th->next_V &&
                 ts->ptime == th->next_time && state_of(ts->vec_sol) == th->next_U_state &&
                 state_of(ts->vec_dot) == th->next_V_state
             ? PETSC_TRUE
             : PETSC_FALSE;
}

// The step residual F at X (evaluated or updated): the next step's α-term may
// come from it (prepare_next_alpha_term) while both keep their states.
PetscErrorCode keep_last_residual(TS ts, Vec X, Vec F) {
  HHTData* th = data_of(ts);
  PetscFunctionBeginUser;
  th->last_F = F;
  th->last_X = X;
  th->last_F_state = state_of(F);
  th->last_X_state = state_of(X);
  PetscFunctionReturn(0);
}

// After an accepted step (the solution and its rate copied, the time set): only
// from a residual at exactly the step's result (no post-stage change, the SNES's
// line search not at another point) and the step's own end time (not a step
// clipped to the final time).
PetscErrorCode prepare_next_alpha_term(TS ts) {
  HHTData* th = data_of(ts);
  PetscFunctionBeginUser;
  th->next_valid = PETSC_FALSE;
  if (!th->inertia || !th->reuse_alpha_term || th->average_inertia) PetscFunctionReturn(0);
  if (th->t1 != ts->ptime || th->last_X != th->U1 || !th->last_F) PetscFunctionReturn(0);
  if (state_of(th->U1) != th->last_X_state || state_of(th->last_F) != th->last_F_state)
    PetscFunctionReturn(0);
  PetscCall(th->inertia(ts, th->t1, th->U1, th->V1, th->A1_arg, th->F0_next, th->inertia_ctx));
  PetscCall(VecAYPX(th->F0_next, -1.0, th->last_F));  // R - M A_arg
  PetscCall(VecAXPY(th->F0_next, -th->alpha / (1 - th->alpha), th->F0));
  PetscCall(stamp_next_alpha_term(ts));
  PetscFunctionReturn(0);
}

// At a step's start: F0 from the one prepared if the solution, its rate and the
// time are still those it was made for (swapped in, no copy).
PetscBool take_next_alpha_term(TS ts) {
  HHTData* th = data_of(ts);
  const PetscBool current = next_alpha_term_current(ts);
  th->next_valid = PETSC_FALSE;
  if (!current) return PETSC_FALSE;
  Vec previous = th->F0;
  th->F0 = th->F0_next;
  th->F0_next = previous;
  ++th->alpha_terms_reused;
  th->F0_reused = PETSC_TRUE;
  return PETSC_TRUE;
}

}  // namespace pcsim::solvers::hht_detail
