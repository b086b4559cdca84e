// HHT-α time integrator as a PETSc TS type "hht" (thesis 3.3.2, eqs 3.16–3.24).
//
// The user states the second-order problem with TSSetI2Function/TSSetI2Jacobian as
//   F(t, U, V, A) = M(U) A + f(t, U, V) = 0        (affine in A),
// and sets the initial state with TS2SetSolution(ts, U0, V0). Each step solves, with the
// TS's SNES and the positions U_{n+1} as unknowns (Newton on positions, as the thesis does),
//   R = (1-α) F(t_{n+1}, U_{n+1}, V_{n+1}, A_{n+1}/(1-α)) + α F(t_n, U_n, V_n, 0) = 0,
// i.e. inertia M(U_{n+1}) A_{n+1} at the new level and every other force averaged
// (1-α) new + α old (3.19–3.21 with the known slip fixed: new-level weight 1-α). Newmark
// updates (3.16) with γ = 1/2 + α, β = (1+α)²/4; high-frequency spectral radius
// (1-α)/(1+α). The SNES residual is R/(1-α); its Jacobian is the user's I2Jacobian with
// shifts dV/dU = γ/(βΔt), dA/dU = 1/(βΔt²(1-α)) (3.23).
//
// Options (prefix of the TS):
//   -ts_hht_alpha <0.1>           α in [0, 1/3]. Default 0.1 (spectral radius 0.818):
//                                 enough to damp spurious high-frequency catenary modes,
//                                 small period error for the resolved ones.
//   -ts_hht_energy_norm_tol <0>   if > 0, Newton also stops when |Δqᵀ R| < tol (thesis
//                                 energy norm, R the residual the update Δq was computed
//                                 from); the usual SNES norms still apply.
//   -ts_hht_max_reject <8>        a step whose SNES fails is retried with Δt halved, at most
//                                 this many times; then the TS stops with
//                                 TS_DIVERGED_NONLINEAR_SOLVE.
//   -ts_hht_regrow_steps <4>      after this many accepted steps at a reduced Δt, Δt doubles
//                                 (never beyond the user's Δt).
//   -ts_hht_average_inertia <0>   inertia ((1-α) M(U_{n+1}) + α M(U_n)) A_{n+1} instead of the
//                                 thesis's M(U_{n+1}) A_{n+1}. Same result for constant M; with
//                                 configuration-dependent M the thesis form is only first-order
//                                 accurate (measured in tests/solvers/test_hht.cpp), the averaged
//                                 form second order. Costs M(U_n) once per step (extracted
//                                 from 2-3 I2Jacobian evaluations) and one MatMult per residual.
//   -ts_hht_use_snes <0>          Newton of the steps through the TS's SNES object. By default
//                                 the type runs the same iteration itself (SNESNEWTONLS with
//                                 full steps and SNESConvergedDefault, the SNES's tolerances
//                                 and KSP: the same iterates, src/solvers/hht_newton.cpp)
//                                 unless an -snes_ option other than the tolerances (e.g.
//                                 -snes_test_jacobian, -snes_monitor), the energy-norm test or
//                                 an SNES other than newtonls with the basic line search asks
//                                 for the SNES.
//   -ts_hht_reuse_alpha_term <1>  with hht_set_inertia_product(): the next step's α-term
//                                 F(t_n, U_n, V_n, 0) is the step's last residual (at the
//                                 converged U_n) minus its α-term and its inertia M(U_n) A_n/(1-α):
//                                 one inertia product instead of a residual per step. Equal to
//                                 evaluating it up to round-off; 0 evaluates it.
//   -ts_hht_residual_update <1>   with hht_set_residual_update(): the own Newton takes the
//                                 residual after each update from the problem's callback
//                                 when it gives it; 0 evaluates every residual.
//   -ts_hht_residual_update_check <0>  evaluates each updated residual as well and keeps the
//                                 largest difference (hht_get_info): a test, not for runs.
// The initial acceleration solves F(t0, U0, V0, A0) = 0 with the TS's SNES at the first step
// (and whenever the time differs from the end of the last step), unless
// hht_set_initial_acceleration() supplied it. With -ts_hht_energy_norm_tol the TS installs its
// own SNES convergence test (SNESConvergedDefault plus the energy test) at TSSetUp.
// TS_EXACTFINALTIME_MATCHSTEP clips the last step to the final time.
#pragma once

#include <petscts.h>

namespace pcsim::solvers {

inline constexpr const char* kTSHHT = "hht";

// Registers the TS type "hht" (TSRegister); safe to call any number of times.
void register_hht_ts();

// The following throw pcsim::SolverError if ts is not of type "hht".

// Uses A0 (copied) as acceleration at the start of the next step instead of solving for it.
void hht_set_initial_acceleration(TS ts, Vec A0);
// Makes the next step solve F(t, U, V, A) = 0 for its starting acceleration (call it after
// changing the solution from outside without changing the time; a new time does it anyway).
void hht_recompute_initial_acceleration(TS ts);
// Copies the acceleration belonging to the current solution: the one set with
// hht_set_initial_acceleration for the next step, else the last step's.
void hht_get_acceleration(TS ts, Vec A);
// Sets α (γ and β follow); α must lie in [0, 1/3].
void hht_set_alpha(TS ts, PetscReal alpha);
void hht_get_params(TS ts, PetscReal* alpha, PetscReal* gamma, PetscReal* beta);
// Sets the energy-norm tolerance (<= 0 disables the test); takes effect at TSSetUp.
void hht_set_energy_norm_tol(TS ts, PetscReal tol);

// The problem's inertia, when F is affine in A: MA = M A with M = dF/dA at the state
// (t, U, V) (constant, or a configuration-dependent mass; the type calls it at the state
// of the step's last residual). With it the type takes each step's α-term from the
// previous step's last residual
// (-ts_hht_reuse_alpha_term) while nothing but the steps changed the solution, its
// rate and the time; call hht_invalidate_alpha_term() when F itself changed between
// steps (e.g. a held load set from outside).
using HHTInertiaProduct = PetscErrorCode (*)(TS ts, PetscReal t, Vec U, Vec V, Vec A, Vec MA,
                                             void* ctx);
void hht_set_inertia_product(TS ts, HHTInertiaProduct product, void* ctx);
void hht_invalidate_alpha_term(TS ts);
// Checkpoint/restart: the α-term the next step will use, if the type holds one for the
// current solution (false: the next step evaluates it), and giving it back after the
// solution and time were restored (the restarted run then does the arithmetic of the
// uninterrupted one).
bool hht_get_alpha_term(TS ts, Vec F0);
void hht_set_alpha_term(TS ts, Vec F0);

// The residual after an exact Newton update, for problems that can give it for less than
// an evaluation (the type's own Newton, -ts_hht_residual_update): X has just become
// X_old - Y, where Y solved J Y = R(X_old) with the Jacobian set at X_old and a direct
// solve; V and A are the stage's rate and acceleration argument at the new X. The
// callback sets F = R(X) (F holds R(X_old)) and *done = PETSC_TRUE, or leaves F as it is
// with *done = PETSC_FALSE (then the residual is evaluated).
using HHTResidualUpdate = PetscErrorCode (*)(TS ts, PetscReal t, Vec X, Vec V, Vec A, Vec Y, Vec F,
                                             PetscBool* done, void* ctx);
void hht_set_residual_update(TS ts, HHTResidualUpdate update, void* ctx);

// Diagnostics of the most recent Newton solve of a step.
struct HHTNewtonInfo {
  PetscReal last_energy_norm = 0;  // |Δqᵀ R| of the last iteration (0 before any)
  PetscBool converged_by_energy = PETSC_FALSE;
  PetscInt accepted_steps = 0;   // since setup
  PetscInt rejected_steps = 0;   // since setup
  PetscReal user_time_step = 0;  // the Δt the step size grows back to
  // The steps' Newton: the type's own iteration (true) or the SNES (after the first step).
  PetscBool own_newton = PETSC_FALSE;
  // Steps whose α-term was taken from the previous step's last residual, and evaluated.
  PetscInt alpha_terms_reused = 0, alpha_terms_evaluated = 0;
  // Newton residuals given by the residual update (hht_set_residual_update), not evaluated.
  PetscInt residuals_updated = 0;
  // With -ts_hht_residual_update_check: the largest |R_updated - R_evaluated| (max norm).
  PetscReal residual_update_gap = 0;
  PetscBool residual_update_checked = PETSC_FALSE;
};
HHTNewtonInfo hht_get_info(TS ts);

// Step-size control between steps (checkpoint/restart): the Δt to grow back to
// after rejections and the accepted steps since the last cut.
struct HHTStepControl {
  PetscReal user_time_step = 0;
  PetscInt accepted_since_cut = 0;
};
HHTStepControl hht_get_step_control(TS ts);
// Restores it for the next step, whose Δt is the TS's time step (set it first,
// with the solution): sets the TS up if needed, so that the first step keeps it.
void hht_set_step_control(TS ts, HHTStepControl control);

}  // namespace pcsim::solvers
