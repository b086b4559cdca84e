// HHT-α TS type (thesis 3.3.2). See include/pcsim/solvers/hht.hpp for the method.
//
// Design notes (after reading how PETSc's TSALPHA2 plugs into TS; no code taken from it):
//  - the TS owns the SNES; ts->ops->snesfunction/snesjacobian are called by it with the
//    unknown X = U_{n+1}; the stage vectors V_{n+1}, A_{n+1} follow from X by (3.18);
//  - TS2SetSolution/TS2GetSolution hold (U, V) in ts->vec_sol/ts->vec_dot;
//  - all work vectors are created at TSSetUp, so a step allocates nothing; the state at t_n
//    is kept in U0/V0/A0 so that TSRollBack can restore it.
#include "pcsim/solvers/hht.hpp"

#include <petsc/private/tsimpl.h>

#include <Eigen/Core>
#include <cmath>
#include <string>

#include "hht_data.hpp"
#include "pcsim/core/error.hpp"

namespace pcsim::solvers::hht_detail {

// V_{n+1}, A_{n+1} and A_{n+1}/(1-α) from the unknown X = U_{n+1} (3.16–3.18),
// in one pass over the local entries (each entry takes the operations, in
// order, of PETSc's WAXPY, AXPY, AXPBY, WAXPY, AXPY, Scale that wrote it
// before: the same rounding, a fifth of the passes). Kept while X (same
// vector, same state) and the step stay: a Jacobian or the end of a step at
// the last residual's X reuses them.
PetscErrorCode stage_vectors(TS ts, Vec X) {
  HHTData* th = data_of(ts);
  const PetscReal dt = th->dt, b = th->beta, g = th->gamma;
  // A1 = (X - U0 - dt V0 - dt²(1/2-β) A0) / (β dt²);  V1 = V0 + dt((1-γ) A0 + γ A1)
  const PetscReal a_old = -(0.5 - b) / b, a_new = 1.0 / (b * dt * dt);
  const PetscReal v_old = dt * (1 - g), v_new = dt * g;
  const PetscReal arg = th->average_inertia ? 1.0 : 1.0 / (1 - th->alpha);
  PetscObjectState state = 0;
  PetscInt n = 0;
  const PetscScalar *x, *u0, *v0, *a0;
  PetscScalar *a1, *v1, *a1_arg;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectStateGet(reinterpret_cast<PetscObject>(X), &state));
  if (X == th->stage_X && state == th->stage_state) PetscFunctionReturn(0);
  PetscCall(VecGetLocalSize(X, &n));
  PetscCall(VecGetArrayRead(X, &x));
  PetscCall(VecGetArrayRead(th->U0, &u0));
  PetscCall(VecGetArrayRead(th->V0, &v0));
  PetscCall(VecGetArrayRead(th->A0, &a0));
  PetscCall(VecGetArrayWrite(th->A1, &a1));
  PetscCall(VecGetArrayWrite(th->V1, &v1));
  PetscCall(VecGetArrayWrite(th->A1_arg, &a1_arg));
  using Array = Eigen::Map<Eigen::ArrayXd>;
  using ConstArray = Eigen::Map<const Eigen::ArrayXd>;
  const ConstArray X_(x, n), U0(u0, n), V0(v0, n), A0(a0, n);
  Array A1(a1, n), V1(v1, n), A1_arg(a1_arg, n);
  A1 = a_old * A0 + a_new * ((X_ - U0) + -dt * V0);
  V1 = (V0 + v_old * A0) + v_new * A1;
  if (arg == 1.0)
    A1_arg = A1;
  else
    A1_arg = arg * A1;
  PetscCall(VecRestoreArrayWrite(th->A1_arg, &a1_arg));
  PetscCall(VecRestoreArrayWrite(th->V1, &v1));
  PetscCall(VecRestoreArrayWrite(th->A1, &a1));
  PetscCall(VecRestoreArrayRead(th->A0, &a0));
  PetscCall(VecRestoreArrayRead(th->V0, &v0));
  PetscCall(VecRestoreArrayRead(th->U0, &u0));
  PetscCall(VecRestoreArrayRead(X, &x));
  th->stage_X = X;
  th->stage_state = state;
  PetscFunctionReturn(0);
}

// SNES residual. Step: R/(1-α) = F(t1, X, V1, A1/(1-α)) + α/(1-α) F(t0, U0, V0, 0) (3.21);
// with averaged inertia F(t1, X, V1, A1) + α/(1-α) (F(t0, U0, V0, 0) + M(U0) A1).
// Initial acceleration: F(t0, U0, V0, X).
PetscErrorCode snes_function(SNES snes, Vec X, Vec F, TS ts) {
  HHTData* th = data_of(ts);
  PetscFunctionBeginUser;
  if (th->mode == SolveMode::kInitialAcceleration) {
    PetscCall(TSComputeI2Function(ts, th->t0, th->U0, th->V0, X, F));
    PetscFunctionReturn(0);
  }
  PetscCall(stage_vectors(ts, X));
  PetscCall(TSComputeI2Function(ts, th->t1, X, th->V1, th->A1_arg, F));
  PetscCall(VecAXPY(F, th->alpha / (1 - th->alpha), th->F0));
  if (th->average_inertia) {
    if (!th->work) PetscCall(VecDuplicate(F, &th->work));  // only here: one vector less
    PetscCall(MatMult(th->M0, th->A1, th->work));
    PetscCall(VecAXPY(F, th->alpha / (1 - th->alpha), th->work));
  }
  PetscCall(keep_last_residual(ts, X, F));
  PetscFunctionReturn(0);
}

namespace {

// dF/dA = M(U0) by differencing two I2Jacobian evaluations with acceleration shifts 0 and s;
// s is chosen so that s M dominates dF/dU and the difference loses no digits.
PetscErrorCode mass_matrix(TS ts, Vec A, Mat J, Mat P) {
  HHTData* th = data_of(ts);
  PetscReal norm_k = 0, norm_m = 0, shift = 1;
  PetscFunctionBeginUser;
  PetscCheck(J == P, PetscObjectComm((PetscObject)ts), PETSC_ERR_SUP,
             "HHT initial acceleration needs Amat == Pmat; set it with "
             "pcsim::solvers::hht_set_initial_acceleration()");
  PetscCall(TSComputeI2Jacobian(ts, th->t0, th->U0, th->V0, A, 0.0, 0.0, J, P));
  if (!th->K_work)
    PetscCall(MatDuplicate(P, MAT_COPY_VALUES, &th->K_work));
  else
    PetscCall(MatCopy(P, th->K_work, SAME_NONZERO_PATTERN));
  Mat K = th->K_work;
  PetscCall(TSComputeI2Jacobian(ts, th->t0, th->U0, th->V0, A, 0.0, 1.0, J, P));
  PetscCall(MatAXPY(P, -1.0, K, SUBSET_NONZERO_PATTERN));
  PetscCall(MatNorm(K, NORM_FROBENIUS, &norm_k));
  PetscCall(MatNorm(P, NORM_FROBENIUS, &norm_m));
  PetscCheck(norm_m > 0, PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_WRONG,
             "HHT: dF/dA is zero, no inertia to compute an initial acceleration");
  if (norm_k > norm_m) {
    shift = 1e3 * norm_k / norm_m;
    PetscCall(TSComputeI2Jacobian(ts, th->t0, th->U0, th->V0, A, 0.0, shift, J, P));
    PetscCall(MatAXPY(P, -1.0, K, SUBSET_NONZERO_PATTERN));
    PetscCall(MatScale(P, 1.0 / shift));
  }
  PetscFunctionReturn(0);
}

}  // namespace

// SNES Jacobian. Step: I2Jacobian with dV/dU = γ/(βΔt), dA_arg/dU = 1/(βΔt²(1-α)) (3.22–3.23).
PetscErrorCode snes_jacobian(SNES snes, Vec X, Mat J, Mat P, TS ts) {
  HHTData* th = data_of(ts);
  PetscFunctionBeginUser;
  if (th->mode == SolveMode::kInitialAcceleration) {
    PetscCall(mass_matrix(ts, X, J, P));
    PetscFunctionReturn(0);
  }
  const PetscReal dt = th->dt;
  PetscCall(stage_vectors(ts, X));
  const PetscReal shift_a = 1.0 / (th->beta * dt * dt);
  PetscCall(TSComputeI2Jacobian(ts, th->t1, X, th->V1, th->A1_arg, th->gamma / (th->beta * dt),
                                th->average_inertia ? shift_a : shift_a / (1 - th->alpha), J, P));
  if (th->average_inertia) {
    PetscCheck(J == P, PetscObjectComm((PetscObject)ts), PETSC_ERR_SUP,
               "HHT averaged inertia needs Amat == Pmat");
    PetscCall(MatAXPY(P, th->alpha / (1 - th->alpha) * shift_a, th->M0, SUBSET_NONZERO_PATTERN));
  }
  PetscFunctionReturn(0);
}

// Usual SNES tests plus the thesis energy norm |Δqᵀ R| (3.3.2). The SNES residual is
// R/(1-α), hence the factor (1-α).
PetscErrorCode converged_energy(SNES snes, PetscInt it, PetscReal xnorm, PetscReal snorm,
                                PetscReal fnorm, SNESConvergedReason* reason, void* ctx) {
  TS ts = static_cast<TS>(ctx);
  HHTData* th = data_of(ts);
  PetscFunctionBeginUser;
  PetscCall(SNESConvergedDefault(snes, it, xnorm, snorm, fnorm, reason, nullptr));
  if (th->mode != SolveMode::kStep || th->energy_tol <= 0) PetscFunctionReturn(0);
  Vec F = nullptr;
  PetscCall(SNESGetFunction(snes, &F, nullptr, nullptr));
  if (it == 0) {
    th->last_energy_norm = 0;
    th->converged_by_energy = PETSC_FALSE;
  } else {
    Vec dq = nullptr;
    PetscScalar dot = 0;
    PetscCall(SNESGetSolutionUpdate(snes, &dq));
    PetscCall(VecDot(dq, th->R_prev, &dot));
    th->last_energy_norm = (1 - th->alpha) * PetscAbsScalar(dot);
    if (*reason == SNES_CONVERGED_ITERATING && th->last_energy_norm < th->energy_tol) {
      // PETSc 3.18 has no "user" reason; FNORM_ABS stands for this absolute test.
      *reason = SNES_CONVERGED_FNORM_ABS;
      th->converged_by_energy = PETSC_TRUE;
    }
  }
  if (!th->R_prev) PetscCall(VecDuplicate(F, &th->R_prev));
  PetscCall(VecCopy(F, th->R_prev));
  PetscFunctionReturn(0);
}

namespace {

// Solves F(t0, U0, V0, A0) = 0 for A0 with the TS's SNES (U0, V0, t0 already set).
PetscErrorCode initial_acceleration(TS ts) {
  HHTData* th = data_of(ts);
  SNESConvergedReason reason;
  PetscFunctionBeginUser;
  th->mode = SolveMode::kInitialAcceleration;
  PetscCall(VecZeroEntries(th->A0));
  PetscCall(newton_solve(ts, th->A0));
  th->mode = SolveMode::kStep;
  PetscCall(SNESGetConvergedReason(ts->snes, &reason));
  PetscCheck(reason > 0, PetscObjectComm((PetscObject)ts), PETSC_ERR_NOT_CONVERGED,
             "HHT: solve for the initial acceleration failed (SNES reason %s)",
             SNESConvergedReasons[reason]);
  PetscFunctionReturn(0);
}

// Start of a step: U_n, V_n, A_n and F(t_n, U_n, V_n, 0) (and M(U_n) for
// the averaged inertia).
PetscErrorCode begin_step(TS ts) {
  HHTData* th = data_of(ts);
  const PetscReal t_n = ts->ptime;
  PetscFunctionBeginUser;
  if (!ts->steprollback) {
    if (ts->time_step != th->dt_last_set) {  // first step or Δt changed from outside
      th->dt_user = ts->time_step;
      th->accepted_since_cut = 0;
    }
    th->stage_X = nullptr;
    PetscCall(VecCopy(ts->vec_sol, th->U0));
    PetscCall(VecCopy(ts->vec_dot, th->V0));
    th->t0 = t_n;
    if (th->user_accel_pending) {
      PetscCall(VecCopy(th->A_user, th->A0));
      th->user_accel_pending = PETSC_FALSE;
    } else if (th->accel_valid && th->accel_time == t_n) {
      PetscCall(VecCopy(th->A1, th->A0));
    } else {
      PetscCall(initial_acceleration(ts));
    }
  }
  th->t0 = t_n;
  // After a rollback the step's own alpha-term stays if it came from the last
  // residual (the step is then taken again bit for bit).
  if (ts->steprollback ? !th->F0_reused : !take_next_alpha_term(ts)) {
    PetscCall(TSComputeI2Function(ts, t_n, th->U0, th->V0, th->zero, th->F0));
    ++th->alpha_terms_evaluated;
    th->F0_reused = PETSC_FALSE;
  }
  if (th->average_inertia) {  // M(U_n), once per step
    Mat J = nullptr, P = nullptr;
    PetscCall(SNESGetJacobian(ts->snes, &J, &P, nullptr, nullptr));
    PetscCall(mass_matrix(ts, th->A0, J, P));
    if (!th->M0)
      PetscCall(MatDuplicate(P, MAT_COPY_VALUES, &th->M0));
    else
      PetscCall(MatCopy(P, th->M0, SAME_NONZERO_PATTERN));
  }
  PetscFunctionReturn(0);
}

// One attempt with step dt from t_n; *converged tells whether Newton did.
PetscErrorCode attempt_step(TS ts, PetscReal dt, PetscBool* converged) {
  HHTData* th = data_of(ts);
  const PetscReal t_n = ts->ptime;
  PetscFunctionBeginUser;
  PetscReal dt_step = dt;
  PetscBool hits_final_time = PETSC_FALSE;
  // The last step ends on the final time. What is left within 1e-6 Δt of Δt
  // (sums of thousands of steps leave ~1e-12 s) takes Δt itself: a Δt off by
  // round-off would have the cheap path refactor J0 for it alone. A step much
  // shorter than Δt makes M/(beta dt^2) swamp the rest of the Newton matrix
  // (3.7e-5 Δt diverged): less than 1.5 Δt left is shared by the last two.
  if (ts->exact_final_time == TS_EXACTFINALTIME_MATCHSTEP) {
    const PetscReal left = ts->max_time - t_n;
    if (std::abs(left - dt_step) <= 1e-6 * dt_step) {
      hits_final_time = PETSC_TRUE;
    } else if (left < dt_step) {
      dt_step = left;
      hits_final_time = PETSC_TRUE;
    } else if (left < 1.5 * dt_step) {
      dt_step = 0.5 * left;
    }
  }
  th->dt = dt_step;
  th->t1 = hits_final_time ? ts->max_time : t_n + dt_step;
  th->stage_X = nullptr;
  // Predictor (3.17): A_{n+1} = 0.
  PetscCall(VecWAXPY(th->U1, dt_step, th->V0, th->U0));
  PetscCall(VecAXPY(th->U1, dt_step * dt_step * (0.5 - th->beta), th->A0));
  PetscCall(TSPreStage(ts, th->t1));
  PetscCall(newton_solve(ts, th->U1));
  SNESConvergedReason reason;
  PetscCall(SNESGetConvergedReason(ts->snes, &reason));
  *converged = reason > 0 ? PETSC_TRUE : PETSC_FALSE;
  if (!*converged) {
    PetscCall(PetscInfo(ts, "HHT step at t=%g with dt=%g rejected (SNES %s)\n", (double)t_n,
                        (double)dt_step, SNESConvergedReasons[reason]));
    PetscFunctionReturn(0);
  }
  PetscCall(TSPostStage(ts, th->t1, 0, &th->U1));
  PetscCall(stage_vectors(ts, th->U1));
  PetscCall(VecCopy(th->U1, ts->vec_sol));
  PetscCall(VecCopy(th->V1, ts->vec_dot));
  ts->ptime = th->t1;
  th->accel_valid = PETSC_TRUE;
  th->accel_time = ts->ptime;
  PetscCall(prepare_next_alpha_term(ts));
  PetscFunctionReturn(0);
}

// A step: retried with Δt halved after a Newton failure (at most max_reject
// times); Δt doubles back after regrow_steps accepted steps. Δt never falls
// below the scene's Δt / 2^max_reject: steps that each fail once and pass at
// half their Δt would otherwise shrink it step after step, the run creeping
// at t = 0 for ever (seen with -ksp_type cg -pc_type none -ksp_max_it 2).
PetscErrorCode ts_step(TS ts) {
  HHTData* th = data_of(ts);
  PetscFunctionBeginUser;
  PetscCall(begin_step(ts));
  PetscReal dt = ts->time_step;
  PetscInt rejections = 0;
  for (;;) {
    PetscBool converged = PETSC_FALSE;
    PetscCall(attempt_step(ts, dt, &converged));
    if (converged) {
      ++th->accepted;
      if (dt < th->dt_user && ++th->accepted_since_cut >= th->regrow_steps) {
        dt = PetscMin(2 * dt, th->dt_user);
        th->accepted_since_cut = 0;
      }
      break;
    }
    ++ts->reject;
    ++ts->num_snes_failures;
    ++th->rejected;
    th->accepted_since_cut = 0;
    const PetscReal smallest_dt = th->dt_user > 0 ? std::ldexp(th->dt_user, -th->max_reject) : 0;
    if (++rejections > th->max_reject || 0.5 * dt < smallest_dt * (1 - 1e-12)) {
      ts->reason = TS_DIVERGED_NONLINEAR_SOLVE;
      break;
    }
    dt *= 0.5;
  }
  ts->time_step = dt;
  th->dt_last_set = dt;
  PetscFunctionReturn(0);
}

PetscErrorCode ts_rollback(TS ts) {
  HHTData* th = data_of(ts);
  PetscFunctionBeginUser;
  PetscCall(VecCopy(th->U0, ts->vec_sol));
  PetscCall(VecCopy(th->V0, ts->vec_dot));
  PetscCall(VecCopy(th->A0, th->A1));
  th->stage_X = nullptr;
  th->accel_time = th->t0;
  PetscFunctionReturn(0);
}

PetscErrorCode ts_reset(TS ts) {
  HHTData* th = data_of(ts);
  PetscFunctionBeginUser;
  for (Vec* v : {&th->U0, &th->V0, &th->A0, &th->U1, &th->V1, &th->A1, &th->A1_arg, &th->F0,
                 &th->F0_next, &th->zero, &th->R_prev, &th->work, &th->newton_F, &th->newton_Y})
    PetscCall(VecDestroy(v));
  PetscCall(MatDestroy(&th->M0));
  PetscCall(MatDestroy(&th->K_work));
  th->accel_valid = PETSC_FALSE;
  PetscFunctionReturn(0);
}

PetscErrorCode ts_destroy(TS ts) {
  PetscFunctionBeginUser;
  PetscCall(ts_reset(ts));
  HHTData* th = data_of(ts);
  PetscCall(VecDestroy(&th->A_user));
  delete th;
  ts->data = nullptr;
  PetscFunctionReturn(0);
}

PetscErrorCode ts_setup(TS ts) {
  HHTData* th = data_of(ts);
  PetscFunctionBeginUser;
  PetscCheck(ts->vec_dot, PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_WRONGSTATE,
             "TS type hht needs the velocity: call TS2SetSolution(ts, U, V)");
  for (Vec* v : {&th->U0, &th->V0, &th->A0, &th->U1, &th->V1, &th->A1, &th->A1_arg, &th->F0,
                 &th->F0_next, &th->zero, &th->newton_F, &th->newton_Y})
    if (!*v) PetscCall(VecDuplicate(ts->vec_sol, v));
  PetscCall(VecZeroEntries(th->zero));
  PetscCall(TSGetAdapt(ts, &ts->adapt));
  PetscCall(TSAdaptCandidatesClear(ts->adapt));
  PetscCall(TSGetSNES(ts, &ts->snes));
  if (th->energy_tol > 0)
    PetscCall(SNESSetConvergenceTest(ts->snes, converged_energy, ts, nullptr));
  th->accel_valid = PETSC_FALSE;
  th->stage_X = nullptr;
  th->newton_chosen = PETSC_FALSE;
  th->dt_last_set = -1;
  th->accepted = th->rejected = 0;
  th->next_valid = PETSC_FALSE;
  th->last_F = th->last_X = nullptr;
  PetscFunctionReturn(0);
}

PetscErrorCode ts_set_from_options(TS ts, PetscOptionItems* PetscOptionsObject) {
  HHTData* th = data_of(ts);
  PetscReal alpha = th->alpha;
  PetscBool set = PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscOptionsHeadBegin(PetscOptionsObject, "HHT-alpha options");
  PetscCall(PetscOptionsReal("-ts_hht_alpha", "HHT alpha in [0, 1/3]", "hht_set_alpha", alpha,
                             &alpha, &set));
  if (set) {
    PetscCheck(alpha >= 0 && alpha <= 1.0 / 3.0 + 1e-14, PetscObjectComm((PetscObject)ts),
               PETSC_ERR_ARG_OUTOFRANGE, "-ts_hht_alpha %g not in [0, 1/3]", (double)alpha);
    set_alpha(th, alpha);
  }
  PetscCall(PetscOptionsReal("-ts_hht_energy_norm_tol",
                             "Newton also stops when |dq^T R| < tol (0: off)",
                             "hht_set_energy_norm_tol", th->energy_tol, &th->energy_tol, nullptr));
  PetscCall(PetscOptionsInt("-ts_hht_max_reject", "Max step halvings after SNES failures", "",
                            th->max_reject, &th->max_reject, nullptr));
  PetscCall(PetscOptionsBool("-ts_hht_average_inertia",
                             "Average the inertia (1-a) M(U1) A1 + a M(U0) A1 (order 2 when M "
                             "depends on U) instead of M(U1) A1",
                             "", th->average_inertia, &th->average_inertia, nullptr));
  PetscCall(
      PetscOptionsBool("-ts_hht_use_snes",
                       "Newton through the SNES object (default: only when an -snes_ option "
                       "or the energy-norm test needs it; else the same iteration without it)",
                       "", th->use_snes, &th->use_snes, nullptr));
  PetscCall(PetscOptionsInt("-ts_hht_regrow_steps",
                            "Accepted steps before a reduced dt doubles again", "",
                            th->regrow_steps, &th->regrow_steps, nullptr));
  PetscCall(PetscOptionsBool("-ts_hht_reuse_alpha_term",
                             "A step's alpha-term F(t_n, U_n, V_n, 0) from the last residual "
                             "minus its inertia (when the problem gives it; 0: evaluated)",
                             "hht_set_inertia_product", th->reuse_alpha_term, &th->reuse_alpha_term,
                             nullptr));
  PetscCall(residual_update_options(ts, PetscOptionsObject));
  PetscOptionsHeadEnd();
  PetscFunctionReturn(0);
}

PetscErrorCode ts_view(TS ts, PetscViewer viewer) {
  HHTData* th = data_of(ts);
  PetscBool ascii = PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &ascii));
  if (ascii) {
    PetscCall(PetscViewerASCIIPrintf(
        viewer, "  HHT-alpha: alpha=%g, gamma=%g, beta=%g (spectral radius at infinity %g)\n",
        (double)th->alpha, (double)th->gamma, (double)th->beta,
        (double)((1 - th->alpha) / (1 + th->alpha))));
    PetscCall(PetscViewerASCIIPrintf(viewer,
                                     "  energy-norm tol=%g, max rejections per step=%" PetscInt_FMT
                                     ", regrow after %" PetscInt_FMT " steps\n",
                                     (double)th->energy_tol, th->max_reject, th->regrow_steps));
    PetscCall(PetscViewerASCIIPrintf(viewer, "  inertia: %s\n",
                                     th->average_inertia ? "averaged (1-alpha) M(U_n+1) + alpha "
                                                           "M(U_n)"
                                                         : "M(U_n+1) at the new level"));
    PetscCall(PetscViewerASCIIPrintf(
        viewer, "  alpha-term: %s (%" PetscInt_FMT " steps from it, %" PetscInt_FMT " evaluated)\n",
        th->inertia && th->reuse_alpha_term && !th->average_inertia
            ? "from the previous step's last residual"
            : "evaluated",
        th->alpha_terms_reused, th->alpha_terms_evaluated));
  }
  PetscFunctionReturn(0);
}

}  // namespace

// -citations: the method and the thesis whose models and integrator pcsim
// follows (docs/thesis.md).
PetscErrorCode register_citations() {
  static PetscBool hht_cited = PETSC_FALSE, thesis_cited = PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscCall(PetscCitationsRegister(
      "@article{HilberHughesTaylor1977,\n"
      "  author  = {Hans M. Hilber and Thomas J. R. Hughes and Robert L. Taylor},\n"
      "  title   = {Improved numerical dissipation for time integration algorithms in "
      "structural dynamics},\n"
      "  journal = {Earthquake Engineering and Structural Dynamics},\n"
      "  volume  = {5}, number = {3}, pages = {283--292}, year = {1977},\n"
      "  doi     = {10.1002/eqe.4290050306}}\n",
      &hht_cited));
  PetscCall(PetscCitationsRegister(
      "@mastersthesis{pcsimThesis2014,\n"
      "  title  = {Modelado no lineal de pantógrafo. Interacción pantógrafo--catenaria},\n"
      "  school = {Universitat Politècnica de València}, year = {2014},\n"
      "  note   = {the models and the HHT scheme of pcsim (its docs/thesis.md)}}\n",
      &thesis_cited));
  PetscFunctionReturn(0);
}

PetscErrorCode ts_create_hht(TS ts) {
  PetscFunctionBeginUser;
  PetscCall(register_citations());
  ts->ops->reset = ts_reset;
  ts->ops->destroy = ts_destroy;
  ts->ops->view = ts_view;
  ts->ops->setup = ts_setup;
  ts->ops->setfromoptions = ts_set_from_options;
  ts->ops->step = ts_step;
  ts->ops->rollback = ts_rollback;
  ts->ops->snesfunction = snes_function;
  ts->ops->snesjacobian = snes_jacobian;
  ts->default_adapt_type = TSADAPTNONE;
  ts->usessnes = PETSC_TRUE;
  auto* th = new HHTData;
  set_alpha(th, 0.1);
  ts->data = th;
  PetscFunctionReturn(0);
}

}  // namespace pcsim::solvers::hht_detail
