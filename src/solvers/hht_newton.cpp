// Newton of an HHT step (hht.hpp): through the TS's SNES, or the type's own
// iteration of the same method when nothing asks for the SNES.
//
// The own iteration is PETSc's default SNES (newtonls, basic line search of
// full steps, SNESConvergedDefault with the SNES's tolerances) written out:
// the same residual and Jacobian callbacks, the same KSP (so any -ksp_type and
// the cheap path's Woodbury solver work unchanged), the same norms and tests,
// hence the same iterates. It leaves out the SNES's per-iteration machinery
// (options lookups in SNESComputeJacobian, line-search norms of the solution
// and the update, logging and monitors), which measured ~10 % of a step of the
// reduced-order catenary (2747 unknowns, docs/fidelity.md). An -snes_ option
// in the options database (e.g. -snes_test_jacobian, -snes_monitor,
// -snes_linesearch_type), the energy-norm test, an SNES that is not newtonls
// with the basic line search, or -ts_hht_use_snes selects the SNES; the
// tolerances (-snes_atol, -snes_rtol, -snes_stol, -snes_max_it,
// -snes_max_funcs, -snes_divergence_tolerance) are the SNES's either way.
#include <petscsnes.h>

#include <cstring>
#include <string>

#include "hht_data.hpp"

namespace pcsim::solvers::hht_detail {

namespace {

// SNES options that the own iteration honours by reading the SNES's values.
bool tolerance_option(const std::string& name) {
  for (const char* known : {"atol", "rtol", "stol", "max_it", "max_funcs", "divergence_tolerance"})
    if (name == known) return true;
  return false;
}

// True when an option "-<prefix>snes_<name>" other than a tolerance is set.
PetscErrorCode snes_option_given(SNES snes, PetscBool* given) {
  const char* prefix = nullptr;
  char* all = nullptr;
  PetscFunctionBeginUser;
  *given = PETSC_FALSE;
  PetscCall(SNESGetOptionsPrefix(snes, &prefix));
  const std::string head = std::string("-") + (prefix ? prefix : "") + "snes_";
  PetscCall(PetscOptionsGetAll(nullptr, &all));
  const std::string options = all ? all : "";
  PetscCall(PetscFree(all));
  for (std::size_t at = options.find(head); at != std::string::npos;
       at = options.find(head, at + 1)) {
    if (at > 0 && options[at - 1] != ' ') continue;
    const std::size_t start = at + head.size();
    const std::string name = options.substr(start, options.find(' ', start) - start);
    if (!tolerance_option(name)) *given = PETSC_TRUE;
  }
  PetscFunctionReturn(0);
}

// Whether the SNES is the default one the own iteration reproduces.
PetscErrorCode choose_newton(TS ts) {
  HHTData* th = data_of(ts);
  SNES snes = ts->snes;
  SNESLineSearch line_search = nullptr;
  PetscBool newtonls = PETSC_FALSE, basic = PETSC_FALSE, npc = PETSC_FALSE, option = PETSC_FALSE;
  PetscInt lag_jacobian = 1, lag_preconditioner = 1;
  PetscReal damping = 1;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(snes), SNESNEWTONLS, &newtonls));
  PetscCall(SNESGetLineSearch(snes, &line_search));
  PetscCall(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(line_search), SNESLINESEARCHBASIC,
                                   &basic));
  PetscCall(SNESLineSearchGetDamping(line_search, &damping));
  PetscCall(SNESHasNPC(snes, &npc));
  PetscCall(SNESGetLagJacobian(snes, &lag_jacobian));
  PetscCall(SNESGetLagPreconditioner(snes, &lag_preconditioner));
  PetscCall(snes_option_given(snes, &option));
  th->own_newton = (!th->use_snes && th->energy_tol <= 0 && newtonls && basic && damping == 1 &&
                    !npc && lag_jacobian == 1 && lag_preconditioner == 1 && !option)
                       ? PETSC_TRUE
                       : PETSC_FALSE;
  th->newton_chosen = PETSC_TRUE;
  PetscCall(PetscInfo(ts, "HHT Newton: %s\n", th->own_newton ? "own iteration" : "SNES"));
  PetscFunctionReturn(0);
}

struct Tolerances {
  PetscReal atol = 0, rtol = 0, stol = 0, divtol = 0;
  PetscInt max_it = 0, max_funcs = 0;
  PetscBool force_iteration = PETSC_FALSE;
};

// SNESConvergedDefault's test (reason stays SNES_CONVERGED_ITERATING otherwise).
SNESConvergedReason converged(const Tolerances& tol, PetscInt it, PetscInt nfuncs, PetscReal fnorm,
                              PetscReal ttol, PetscReal fnorm0, PetscReal xnorm, PetscReal ynorm) {
  if (PetscIsInfOrNanReal(fnorm)) return SNES_DIVERGED_FNORM_NAN;
  if (fnorm < tol.atol && (it || !tol.force_iteration)) return SNES_CONVERGED_FNORM_ABS;
  if (nfuncs >= tol.max_funcs && tol.max_funcs >= 0) return SNES_DIVERGED_FUNCTION_COUNT;
  if (!it) return SNES_CONVERGED_ITERATING;
  if (fnorm <= ttol) return SNES_CONVERGED_FNORM_RELATIVE;
  if (ynorm < tol.stol * xnorm) return SNES_CONVERGED_SNORM_RELATIVE;
  if (tol.divtol > 0 && fnorm > tol.divtol * fnorm0) return SNES_DIVERGED_DTOL;
  return SNES_CONVERGED_ITERATING;
}

// F = R(X) after the update X -= Y: from the problem's residual update when it
// gives it (the KSP's solve is exact: preonly with a factorisation or the cheap
// path's Woodbury solver), else evaluated; kept for the next step's α-term as
// snes_function() keeps it.
PetscErrorCode residual_after_update(SNES snes, TS ts, Vec X, Vec Y, Vec F) {
  HHTData* th = data_of(ts);
  PetscBool done = PETSC_FALSE;
  PetscFunctionBeginUser;
  if (th->residual_update && th->use_residual_update && !th->average_inertia) {
    PetscCall(stage_vectors(ts, X));
    PetscCall(th->residual_update(ts, th->t1, X, th->V1, th->A1_arg, Y, F, &done,
                                  th->residual_update_ctx));
  }
  if (!done) PetscFunctionReturn(snes_function(snes, X, F, ts));
  ++th->residuals_updated;
  if (th->check_residual_update) {  // work is free: no averaged inertia here
    PetscReal gap = 0;
    if (!th->work) PetscCall(VecDuplicate(F, &th->work));
    PetscCall(snes_function(snes, X, th->work, ts));
    PetscCall(VecAXPY(th->work, -1.0, F));
    PetscCall(VecNorm(th->work, NORM_INFINITY, &gap));
    th->residual_update_gap = PetscMax(th->residual_update_gap, gap);
  }
  PetscCall(keep_last_residual(ts, X, F));
  PetscFunctionReturn(0);
}

// Newton with full steps from X: F(X), J(X) Y = F(X), X -= Y, until the test.
PetscErrorCode own_newton(TS ts, Vec X, SNESConvergedReason* reason, PetscInt* its,
                          PetscInt* linear_its) {
  HHTData* th = data_of(ts);
  SNES snes = ts->snes;
  Vec F = th->newton_F, Y = th->newton_Y;
  Tolerances tol;
  Mat J = nullptr, P = nullptr;
  KSP ksp = nullptr;
  PetscFunctionBeginUser;
  PetscCall(SNESGetTolerances(snes, &tol.atol, &tol.rtol, &tol.stol, &tol.max_it, &tol.max_funcs));
  PetscCall(SNESGetDivergenceTolerance(snes, &tol.divtol));
  PetscCall(SNESGetForceIteration(snes, &tol.force_iteration));
  PetscCall(SNESGetJacobian(snes, &J, &P, nullptr, nullptr));
  PetscCall(SNESGetKSP(snes, &ksp));
  PetscInt nfuncs = 1;
  PetscReal fnorm = 0, xnorm = 0, ynorm = 0;
  PetscCall(snes_function(snes, X, F, ts));
  PetscCall(VecNorm(F, NORM_2, &fnorm));
  const PetscReal fnorm0 = fnorm, ttol = fnorm * tol.rtol;
  *its = *linear_its = 0;
  *reason = converged(tol, 0, nfuncs, fnorm, ttol, fnorm0, 0, 0);
  while (*reason == SNES_CONVERGED_ITERATING) {
    if (*its == tol.max_it) {
      *reason = SNES_DIVERGED_MAX_IT;
      break;
    }
    PetscCall(snes_jacobian(snes, X, J, P, ts));
    PetscCall(KSPSetOperators(ksp, J, P));
    PetscCall(KSPSolve(ksp, F, Y));
    KSPConvergedReason linear = KSP_CONVERGED_ITERATING;
    PetscInt lits = 0;
    PetscCall(KSPGetConvergedReason(ksp, &linear));
    PetscCall(KSPGetIterationNumber(ksp, &lits));
    *linear_its += lits;
    if (linear < 0) {
      *reason = SNES_DIVERGED_LINEAR_SOLVE;
      break;
    }
    PetscCall(VecAXPY(X, -1.0, Y));
    PetscCall(residual_after_update(snes, ts, X, Y, F));
    ++nfuncs;
    ++*its;
    // As the line search computes them (split reductions: not bitwise
    // VecNorm), here the three in one reduction.
    PetscCall(VecNormBegin(F, NORM_2, &fnorm));
    if (tol.stol > 0) {
      PetscCall(VecNormBegin(Y, NORM_2, &ynorm));
      PetscCall(VecNormBegin(X, NORM_2, &xnorm));
    }
    PetscCall(VecNormEnd(F, NORM_2, &fnorm));
    if (tol.stol > 0) {
      PetscCall(VecNormEnd(Y, NORM_2, &ynorm));
      PetscCall(VecNormEnd(X, NORM_2, &xnorm));
    }
    if (PetscIsInfOrNanReal(fnorm)) {
      *reason = SNES_DIVERGED_LINE_SEARCH;  // the basic line search's failure
      break;
    }
    *reason = converged(tol, *its, nfuncs, fnorm, ttol, fnorm0, xnorm, ynorm);
  }
  PetscFunctionReturn(0);
}

}  // namespace

PetscErrorCode residual_update_options(TS ts, PetscOptionItems* PetscOptionsObject) {
  HHTData* th = data_of(ts);
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsBool("-ts_hht_residual_update",
                             "The residual after a Newton update from the problem (when it gives "
                             "it; 0: evaluated)",
                             "hht_set_residual_update", th->use_residual_update,
                             &th->use_residual_update, nullptr));
  PetscCall(PetscOptionsBool("-ts_hht_residual_update_check",
                             "Evaluate each updated residual too and keep the largest difference "
                             "(a test of the update, not for production runs)",
                             "hht_get_info", th->check_residual_update, &th->check_residual_update,
                             nullptr));
  PetscFunctionReturn(0);
}

PetscErrorCode newton_solve(TS ts, Vec X) {
  HHTData* th = data_of(ts);
  PetscInt its = 0, linear_its = 0;
  PetscFunctionBeginUser;
  if (!th->newton_chosen) PetscCall(choose_newton(ts));
  if (th->own_newton && th->mode == SolveMode::kStep) {
    SNESConvergedReason reason = SNES_CONVERGED_ITERATING;
    PetscCall(own_newton(ts, X, &reason, &its, &linear_its));
    PetscCall(SNESSetIterationNumber(ts->snes, its));
    PetscCall(SNESSetConvergedReason(ts->snes, reason));
  } else {
    PetscCall(SNESSolve(ts->snes, nullptr, X));
    PetscCall(SNESGetIterationNumber(ts->snes, &its));
    PetscCall(SNESGetLinearSolveIterations(ts->snes, &linear_its));
  }
  ts->snes_its += its;
  ts->ksp_its += linear_its;
  PetscFunctionReturn(0);
}

}  // namespace pcsim::solvers::hht_detail
