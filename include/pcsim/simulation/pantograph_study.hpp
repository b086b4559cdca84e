// Driver of the studies of the pantograph alone (`pcsim pantograph`, thesis chapter 2):
// the static equilibrium under (F0, h0), then the study: time responses (PETSc TS,
// pantograph_time.hpp), modes (SLEPc, pantograph_modes.hpp, cross-checked with Eigen),
// FRFs, nonlinear frequency sweeps, calibration. Serial (PETSC_COMM_SELF).
#pragma once

#include "pcsim/pantograph/study.hpp"

namespace pcsim::simulation {

// Sets what the equilibrium fixes in scene.model (bellows torque, height offset).
pantograph::StudyResult run_pantograph_study(pantograph::StudyScene& scene);

}  // namespace pcsim::simulation
