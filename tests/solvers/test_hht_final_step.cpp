// Regression: with -ts_exact_final_time matchstep, thousands of steps leave a
// floating-point remainder (~1e-12 s) before the final time; the HHT step
// must fold it into the last step instead of attempting a step that short
// (whose Newton matrix M/(beta dt^2) swamps everything else).
#include <gtest/gtest.h>
#include <petscts.h>

#include "pcsim/solvers/hht.hpp"

namespace {

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

TEST(HHTFinalStep, FloatingPointRemainderJoinsTheLastStep) {
  pcsim::solvers::register_hht_ts();
  TS ts;
  Vec U, V, F;
  Mat J;
  ASSERT_EQ(TSCreate(PETSC_COMM_SELF, &ts), 0);
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
  // 16992 steps of 0.5 ms: the sum of the steps misses 8.496 s by ~1e-12 s.
  const PetscReal dt = 5e-4, final_time = 16992 * 5e-4;
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
  ASSERT_EQ(TSSolve(ts, nullptr), 0);
  TSConvergedReason reason;
  TSGetConvergedReason(ts, &reason);
  EXPECT_GT(reason, 0);
  PetscInt steps;
  PetscReal t;
  TSGetStepNumber(ts, &steps);
  TSGetTime(ts, &t);
  EXPECT_EQ(steps, 16992);  // no extra sliver step
  EXPECT_DOUBLE_EQ(t, final_time);
  // 8.496 periods of a 1 Hz oscillator: u = cos(2 pi t) up to HHT's damping/phase error.
  const PetscScalar* u;
  VecGetArrayRead(U, &u);
  EXPECT_NEAR(u[0], std::cos(2 * M_PI * final_time), 5e-2);
  VecRestoreArrayRead(U, &u);
  TSDestroy(&ts);
  VecDestroy(&U);
  VecDestroy(&V);
  VecDestroy(&F);
  MatDestroy(&J);
}
