// hht_get_acceleration returns the acceleration of the solution the next step
// starts from: the one given with hht_set_initial_acceleration (a moving
// window's shift, a restart) until that step, else the last step's. Until
// 2026-12-06 it returned the last step's, so a checkpoint written at a window's
// shift paired the shifted state with the acceleration from before the shift
// (tests/simulation/test_window_restart.sh: 1 % in the contact force after
// the restart).
#include <gtest/gtest.h>
#include <petscts.h>

#include "hht_test_models.hpp"
#include "pcsim/core/error.hpp"
#include "pcsim/solvers/hht.hpp"

using namespace hht_models;

namespace {

double acceleration_of(TS ts, Vec like) {
  Vec A;
  PCSIM_PETSC(VecDuplicate(like, &A));
  pcsim::solvers::hht_get_acceleration(ts, A);
  PetscScalar a;
  const PetscInt zero = 0;
  PCSIM_PETSC(VecGetValues(A, 1, &zero, &a));
  PCSIM_PETSC(VecDestroy(&A));
  return a;
}

void set_acceleration(TS ts, Vec like, double a) {
  Vec A;
  PCSIM_PETSC(VecDuplicate(like, &A));
  PCSIM_PETSC(VecSet(A, a));
  pcsim::solvers::hht_set_initial_acceleration(ts, A);
  PCSIM_PETSC(VecDestroy(&A));
}

}  // namespace

TEST(HHTAcceleration, TheOneSetForTheNextStepIsTheSolutions) {
  const Model model = nonlinear_pendulum(0.2, 4.0, 0.5);
  TsRun run(model, pcsim::solvers::kTSHHT, VectorXd::Constant(1, 1.0), VectorXd::Constant(1, 0.0),
            0.05);
  run.direct_solver(false, 1e-13);
  set_acceleration(run.ts, run.U, -2.5);  // before any step: the start's
  EXPECT_EQ(acceleration_of(run.ts, run.U), -2.5);
  run.solve_steps(4);
  const double stepped = acceleration_of(run.ts, run.U);
  EXPECT_NE(stepped, 0.75);
  // The solution replaced from outside with its acceleration (a window's shift).
  PCSIM_PETSC(VecSet(run.U, 0.3));
  PCSIM_PETSC(VecSet(run.V, -0.5));
  set_acceleration(run.ts, run.U, 0.75);
  EXPECT_EQ(acceleration_of(run.ts, run.U), 0.75);
  PetscReal t;
  PCSIM_PETSC(TSGetTime(run.ts, &t));
  // The next step takes it; then the step's own acceleration is returned.
  run.solve_steps(5);
  const double after = acceleration_of(run.ts, run.U);
  EXPECT_NE(after, 0.75);
  // The same step from the same state and acceleration: the same result.
  TsRun fresh(model, pcsim::solvers::kTSHHT, VectorXd::Constant(1, 0.3),
              VectorXd::Constant(1, -0.5), 0.05);
  fresh.direct_solver(false, 1e-13);
  PCSIM_PETSC(TSSetTime(fresh.ts, t));
  set_acceleration(fresh.ts, fresh.U, 0.75);
  fresh.solve_steps(1);
  EXPECT_EQ(acceleration_of(fresh.ts, fresh.U), after);
  EXPECT_EQ(fresh.u.back()(0), run.u.back()(0));
}
