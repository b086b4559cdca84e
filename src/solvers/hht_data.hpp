// Private data of the HHT-alpha TS type (src/solvers/hht.cpp: the method,
// src/solvers/hht_api.cpp: the public functions of pcsim/solvers/hht.hpp).
#pragma once

#include <petsc/private/tsimpl.h>

#include "pcsim/solvers/hht.hpp"

namespace pcsim::solvers::hht_detail {

enum class SolveMode { kStep, kInitialAcceleration };

struct HHTData {
  // Method parameters (3.24 with η = α).
  PetscReal alpha = 0.1;
  PetscReal gamma = 0.6;
  PetscReal beta = 0.3025;
  PetscReal energy_tol = 0;  // <= 0: energy-norm test off
  PetscInt max_reject = 8;
  PetscInt regrow_steps = 4;
  // Inertia at the new level M(U_{n+1}) A_{n+1} (thesis) or averaged
  // ((1-α) M(U_{n+1}) + α M(U_n)) A_{n+1} (second order when M depends on U).
  PetscBool average_inertia = PETSC_FALSE;

  // State at t_n, stage/new state, work vectors (created at setup).
  Vec U0 = nullptr, V0 = nullptr, A0 = nullptr;
  Vec U1 = nullptr, V1 = nullptr, A1 = nullptr;
  Vec A1_arg = nullptr;  // A_{n+1}/(1-α): the acceleration argument of F
  Vec F0 = nullptr;      // F(t_n, U_n, V_n, 0): non-inertial force at the old level
  Vec zero = nullptr;    // zero vector (acceleration argument of F0)
  Vec R_prev = nullptr;  // SNES residual the last Newton update was computed from (energy test)
  Vec A_user = nullptr;  // user-supplied initial acceleration
  Vec work = nullptr;    // M(U_n) A_{n+1} (averaged inertia; created where first needed)
  Vec newton_F = nullptr, newton_Y = nullptr;  // residual and update of the own Newton
  Mat M0 = nullptr;      // M(U_n) (averaged inertia), created at the first step
  Mat K_work = nullptr;  // dF/dU while extracting a mass matrix
  PetscBool user_accel_pending = PETSC_FALSE;

  // A1 is the acceleration of (vec_sol, vec_dot) at accel_time when accel_valid.
  PetscBool accel_valid = PETSC_FALSE;
  PetscReal accel_time = 0;

  // Newton of a step: the TS's SNES, or the type's own iteration of the same
  // method (hht_newton.cpp) when no SNES feature is asked for.
  PetscBool use_snes = PETSC_FALSE;  // -ts_hht_use_snes: always the SNES
  PetscBool newton_chosen = PETSC_FALSE, own_newton = PETSC_FALSE;  // decided at the first step

  // V1, A1, A1_arg belong to stage_X at its state stage_state (nullptr: stale).
  Vec stage_X = nullptr;
  PetscObjectState stage_state = 0;

  // The α-term from the last residual (-ts_hht_reuse_alpha_term, hht_set_inertia_product):
  // F0_next is F(t_n, U_n, V_n, 0) of the solution next_U, rate next_V at their states and
  // time next_time, when next_valid. last_F: the last step residual, at last_X's state.
  HHTInertiaProduct inertia = nullptr;
  void* inertia_ctx = nullptr;
  PetscBool reuse_alpha_term = PETSC_TRUE;
  Vec F0_next = nullptr;
  PetscBool next_valid = PETSC_FALSE;
  PetscBool F0_reused = PETSC_FALSE;  // this step's F0 came from the last residual
  Vec next_U = nullptr, next_V = nullptr;
  PetscObjectState next_U_state = 0, next_V_state = 0;
  PetscReal next_time = 0;
  Vec last_F = nullptr, last_X = nullptr;
  PetscObjectState last_F_state = 0, last_X_state = 0;
  PetscInt alpha_terms_reused = 0, alpha_terms_evaluated = 0;

  // The residual after a Newton update from the problem (hht_set_residual_update).
  HHTResidualUpdate residual_update = nullptr;
  void* residual_update_ctx = nullptr;
  PetscBool use_residual_update = PETSC_TRUE;
  PetscBool check_residual_update = PETSC_FALSE;  // each also evaluated, the gap kept
  PetscInt residuals_updated = 0;
  PetscReal residual_update_gap = 0;  // max |R_updated - R_evaluated| (check on)

  // Current solve.
  SolveMode mode = SolveMode::kStep;
  PetscReal t0 = 0, t1 = 0, dt = 0;

  // Step-size control after rejections.
  PetscReal dt_user = 0;       // the Δt to grow back to
  PetscReal dt_last_set = -1;  // Δt this type left in ts->time_step (detects user changes)
  PetscInt accepted_since_cut = 0;

  // Diagnostics.
  PetscReal last_energy_norm = 0;
  PetscBool converged_by_energy = PETSC_FALSE;
  PetscInt accepted = 0, rejected = 0;
};

inline void set_alpha(HHTData* th, PetscReal alpha) {
  th->alpha = alpha;
  th->gamma = 0.5 + alpha;                      // (3.24)
  th->beta = 0.25 * (1 + alpha) * (1 + alpha);  // (3.24)
}

inline HHTData* data_of(TS ts) {
  return static_cast<HHTData*>(ts->data);
}

// The TS type's constructor (TSRegister) and the SNES test with the energy norm.
PetscErrorCode ts_create_hht(TS ts);
// V1, A1 and A1_arg of the unknown X (kept while X and the step stay; hht.cpp).
PetscErrorCode stage_vectors(TS ts, Vec X);
// -ts_hht_residual_update and its check (hht_newton.cpp), read by the type's options.
PetscErrorCode residual_update_options(TS ts, PetscOptionItems* PetscOptionsObject);
// The SNES callbacks of a step (hht.cpp).
PetscErrorCode snes_function(SNES snes, Vec X, Vec F, TS ts);
PetscErrorCode snes_jacobian(SNES snes, Vec X, Mat J, Mat P, TS ts);
// Solves a step's equations for X (initial guess in X) with the SNES or the
// own Newton, leaves the reason and iteration count in the SNES and adds the
// iterations to the TS's counts (hht_newton.cpp).
PetscErrorCode newton_solve(TS ts, Vec X);
// The α-term: after an accepted step, F0_next from the step's last residual if it can
// be (prepare); at a step's start, F0 from it if it still belongs to the solution
// (take: true), hht.cpp.
PetscErrorCode prepare_next_alpha_term(TS ts);
// Marks F as the step residual at X (hht_alpha_term.cpp).
PetscErrorCode keep_last_residual(TS ts, Vec X, Vec F);
PetscBool take_next_alpha_term(TS ts);
// Marks F0_next as belonging to the current solution, rate and time; whether it still does.
PetscErrorCode stamp_next_alpha_term(TS ts);
PetscBool next_alpha_term_current(TS ts);
PetscErrorCode converged_energy(SNES snes, PetscInt it, PetscReal xnorm, PetscReal snorm,
                                PetscReal fnorm, SNESConvergedReason* reason, void* ctx);

}  // namespace pcsim::solvers::hht_detail
