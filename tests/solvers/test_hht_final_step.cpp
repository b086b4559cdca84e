// Regression: with -ts_exact_final_time matchstep, thousands of steps leave a
// floating-point remainder (~1e-12 s) before the final time; the HHT step
// must fold it into the last step instead of attempting a step that short
// (whose Newton matrix M/(beta dt^2) swamps everything else). A remainder
// that is not round-off (a duration that is no multiple of dt) is shared by
// the last two steps.
#include <gtest/gtest.h>
#include <petscts.h>

#include <cmath>
#include <vector>

#include "pcsim/solvers/hht.hpp"

namespace {

std::vector<PetscReal> shifts_seen;  // every Jacobian's shift_a, in order

// m u'' + k u = 0 with m = 1, k = (2 pi)^2.
PetscErrorCode residual(TS, PetscReal, Vec U, Vec V, Vec A, Vec F, void*) {
  const PetscScalar *u, *a;
  PetscScalar* f;
  PetscCall(VecGetArrayRead(U, &u));
  PetscCall(VecGetArrayRead(A, &a));
  PetscCall(VecGetArray(F, &f));
  f[0] = a[0] + 4 * M_PI * M_PI * u[0];
  PetscCall(VecRestoreArrayRead(U, &u));
  PetscCall(VecRestoreArrayRead(A, &a));
  PetscCall(VecRestoreArray(F, &f));
  return 0;
}

PetscErrorCode jacobian(TS, PetscReal, Vec, Vec, Vec, PetscReal, PetscReal shift_a, Mat J, Mat P,
                        void*) {
  shifts_seen.push_back(shift_a);
  PetscCall(MatSetValue(P, 0, 0, 4 * M_PI * M_PI + shift_a, INSERT_VALUES));
  PetscCall(MatAssemblyBegin(P, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(P, MAT_FINAL_ASSEMBLY));
  if (J != P) {
    PetscCall(MatAssemblyBegin(J, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(J, MAT_FINAL_ASSEMBLY));
  }
  return 0;
}

}  // namespace

struct Outcome {
  PetscInt steps = 0;
  PetscReal t = 0, u = 0;
  TSConvergedReason reason = TS_CONVERGED_ITERATING;
};

// The oscillator from u = 1, u' = 0 to final_time in steps of dt (matchstep).
Outcome integrate(PetscReal dt, PetscReal final_time) {
  pcsim::solvers::register_hht_ts();
  TS ts;
  Vec U, V, F;
  Mat J;
  Outcome out;
  shifts_seen.clear();
  TSCreate(PETSC_COMM_SELF, &ts);
  VecCreateSeq(PETSC_COMM_SELF, 1, &U);
  VecDuplicate(U, &V);
  VecDuplicate(U, &F);
  MatCreateSeqDense(PETSC_COMM_SELF, 1, 1, nullptr, &J);
  VecSet(U, 1.0);
  VecSet(V, 0.0);
  TSSetType(ts, pcsim::solvers::kTSHHT);
  TSSetI2Function(ts, F, residual, nullptr);
  TSSetI2Jacobian(ts, J, J, jacobian, nullptr);
  TS2SetSolution(ts, U, V);
  TSSetTimeStep(ts, dt);
  TSSetMaxTime(ts, final_time);
  TSSetMaxSteps(ts, 100000);
  TSSetExactFinalTime(ts, TS_EXACTFINALTIME_MATCHSTEP);
  SNES snes;
  KSP ksp;
  PC pc;
  TSGetSNES(ts, &snes);
  SNESGetKSP(snes, &ksp);
  KSPSetType(ksp, KSPPREONLY);
  KSPGetPC(ksp, &pc);
  PCSetType(pc, PCLU);
  if (TSSolve(ts, nullptr) == 0) {
    TSGetConvergedReason(ts, &out.reason);
    TSGetStepNumber(ts, &out.steps);
    TSGetTime(ts, &out.t);
    const PetscScalar* u;
    VecGetArrayRead(U, &u);
    out.u = u[0];
    VecRestoreArrayRead(U, &u);
  }
  TSDestroy(&ts);
  VecDestroy(&U);
  VecDestroy(&V);
  VecDestroy(&F);
  MatDestroy(&J);
  return out;
}

TEST(HHTFinalStep, FloatingPointRemainderJoinsTheLastStep) {
  // 16992 steps of 0.5 ms: the sum of the steps misses 8.496 s by ~1e-12 s.
  const PetscReal dt = 5e-4, final_time = 16992 * 5e-4;
  const Outcome out = integrate(dt, final_time);
  EXPECT_GT(out.reason, 0);
  EXPECT_EQ(out.steps, 16992);  // no extra sliver step
  EXPECT_DOUBLE_EQ(out.t, final_time);
  // 8.496 periods of a 1 Hz oscillator: u = cos(2 pi t) up to HHT's damping/phase error.
  EXPECT_NEAR(out.u, std::cos(2 * M_PI * final_time), 5e-2);
}

// The last step of a round-off remainder takes dt itself: its Newton matrix
// is every other step's (a cheap path keeps its J0), shift_a = 1/(beta dt^2)
// to the last bit, where the remainder's own length (dt - ~1e-12 s) gave a
// shift ~1e-9 apart.
TEST(HHTFinalStep, RoundOffRemainderKeepsTheTimeStep) {
  const PetscReal dt = 5e-4, final_time = 16992 * 5e-4;
  const Outcome out = integrate(dt, final_time);
  EXPECT_EQ(out.steps, 16992);
  EXPECT_DOUBLE_EQ(out.t, final_time);
  ASSERT_GE(shifts_seen.size(), 16992u);  // the start's own (initial acceleration) first
  const PetscReal step_shift = shifts_seen[shifts_seen.size() / 2];
  EXPECT_EQ(shifts_seen.back(), step_shift);
}

// A remainder of 3.7e-5 dt beyond a whole number of steps (a scene whose
// duration is not a multiple of dt: three-span-lumped at 237.749251 km/h
// diverged on that sliver step): the last two steps share 1.0000367 dt.
TEST(HHTFinalStep, ShortRemainderSharedByTheLastTwoSteps) {
  const PetscReal dt = 1e-3, final_time = 1.0130000367488015;
  const Outcome out = integrate(dt, final_time);
  EXPECT_GT(out.reason, 0);
  EXPECT_EQ(out.steps, 1014);  // 1012 steps of dt, then two of 0.50002 dt
  EXPECT_DOUBLE_EQ(out.t, final_time);
  EXPECT_NEAR(out.u, std::cos(2 * M_PI * final_time), 5e-2);
}
