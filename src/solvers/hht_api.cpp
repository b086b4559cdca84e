// Public functions of the HHT-alpha TS type (include/pcsim/solvers/hht.hpp).
#include "hht_data.hpp"
#include "pcsim/core/error.hpp"
#include "pcsim/solvers/hht.hpp"

namespace pcsim::solvers {

using namespace hht_detail;

namespace {
HHTData* checked_data(TS ts) {
  PetscBool is_hht = PETSC_FALSE;
  PCSIM_PETSC(PetscObjectTypeCompare((PetscObject)ts, kTSHHT, &is_hht));
  if (!is_hht) throw SolverError("TS is not of type hht");
  return data_of(ts);
}

}  // namespace

void register_hht_ts() {
  PCSIM_PETSC(TSInitializePackage());
  void (*existing)(void) = nullptr;
  PCSIM_PETSC(PetscFunctionListFind(TSList, kTSHHT, &existing));
  if (!existing) PCSIM_PETSC(TSRegister(kTSHHT, ts_create_hht));
}

void hht_set_initial_acceleration(TS ts, Vec A0) {
  HHTData* th = checked_data(ts);
  if (!th->A_user) PCSIM_PETSC(VecDuplicate(A0, &th->A_user));
  PCSIM_PETSC(VecCopy(A0, th->A_user));
  th->user_accel_pending = PETSC_TRUE;
}

void hht_recompute_initial_acceleration(TS ts) {
  HHTData* th = checked_data(ts);
  th->accel_valid = PETSC_FALSE;
  th->user_accel_pending = PETSC_FALSE;
}

void hht_get_acceleration(TS ts, Vec A) {
  HHTData* th = checked_data(ts);
  // One set for the next step (a moving window's shift, a restart) is the
  // state's; until 2026-12-06 the last step's was returned, so a checkpoint at
  // a window's shift held the acceleration from before it.
  if (th->user_accel_pending) {
    PCSIM_PETSC(VecCopy(th->A_user, A));
    return;
  }
  if (!th->accel_valid) throw SolverError("hht_get_acceleration: no step taken yet");
  PCSIM_PETSC(VecCopy(th->A1, A));
}

void hht_set_alpha(TS ts, PetscReal alpha) {
  HHTData* th = checked_data(ts);
  if (!(alpha >= 0 && alpha <= 1.0 / 3.0 + 1e-14))
    throw SolverError("hht_set_alpha: alpha " + std::to_string(alpha) + " not in [0, 1/3]");
  set_alpha(th, alpha);
}

void hht_get_params(TS ts, PetscReal* alpha, PetscReal* gamma, PetscReal* beta) {
  HHTData* th = checked_data(ts);
  if (alpha) *alpha = th->alpha;
  if (gamma) *gamma = th->gamma;
  if (beta) *beta = th->beta;
}

void hht_set_energy_norm_tol(TS ts, PetscReal tol) {
  HHTData* th = checked_data(ts);
  th->energy_tol = tol;
  if (ts->setupcalled && tol > 0) {
    SNES snes = nullptr;
    PCSIM_PETSC(TSGetSNES(ts, &snes));
    PCSIM_PETSC(SNESSetConvergenceTest(snes, converged_energy, ts, nullptr));
  }
}

HHTNewtonInfo hht_get_info(TS ts) {
  HHTData* th = checked_data(ts);
  HHTNewtonInfo info;
  info.last_energy_norm = th->last_energy_norm;
  info.converged_by_energy = th->converged_by_energy;
  info.accepted_steps = th->accepted;
  info.rejected_steps = th->rejected;
  info.user_time_step = th->dt_user;
  info.own_newton = th->own_newton;
  info.alpha_terms_reused = th->alpha_terms_reused;
  info.alpha_terms_evaluated = th->alpha_terms_evaluated;
  info.residuals_updated = th->residuals_updated;
  info.residual_update_gap = th->residual_update_gap;
  info.residual_update_checked = th->check_residual_update;
  return info;
}

void hht_set_inertia_product(TS ts, HHTInertiaProduct product, void* ctx) {
  HHTData* th = checked_data(ts);
  th->inertia = product;
  th->inertia_ctx = ctx;
  th->next_valid = PETSC_FALSE;
}

void hht_set_residual_update(TS ts, HHTResidualUpdate update, void* ctx) {
  HHTData* th = checked_data(ts);
  th->residual_update = update;
  th->residual_update_ctx = ctx;
}

void hht_invalidate_alpha_term(TS ts) {
  checked_data(ts)->next_valid = PETSC_FALSE;
}

bool hht_get_alpha_term(TS ts, Vec F0) {
  HHTData* th = checked_data(ts);
  if (!next_alpha_term_current(ts)) return false;
  PCSIM_PETSC(VecCopy(th->F0_next, F0));
  return true;
}

void hht_set_alpha_term(TS ts, Vec F0) {
  HHTData* th = checked_data(ts);
  if (!th->F0_next) PCSIM_PETSC(VecDuplicate(F0, &th->F0_next));
  PCSIM_PETSC(VecCopy(F0, th->F0_next));
  PCSIM_PETSC(stamp_next_alpha_term(ts));
}

HHTStepControl hht_get_step_control(TS ts) {
  HHTData* th = checked_data(ts);
  return {th->dt_user, th->accepted_since_cut};
}

void hht_set_step_control(TS ts, HHTStepControl control) {
  HHTData* th = checked_data(ts);
  PCSIM_PETSC(TSSetUp(ts));  // its setup would forget the control
  th->dt_user = control.user_time_step;
  th->accepted_since_cut = control.accepted_since_cut;
  th->dt_last_set = ts->time_step;  // the next step's Δt is not a change from outside
}

}  // namespace pcsim::solvers
