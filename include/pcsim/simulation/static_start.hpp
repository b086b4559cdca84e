// The initial state of a dynamic run (thesis 3.3.1):
//  - every pantograph in its own static equilibrium with its contact point at
//    the wire (ramp start: zero contact force at t = 0, the head's force ramps
//    up over ramp_distance), or pressing it with F0 (static start);
//  - with static starts (any pantographs, each at its start point), the coupled
//    static equilibrium F(0, U, 0, 0) = 0 of the dynamic model itself, by SNES
//    with the exact Jacobian, so that nothing drifts at t = 0. Its guess is the
//    catenary under the point loads F0 of those pantographs (options prefix
//    -start_load_); the coupled solve takes -start_. Ramp and gap starts are
//    held at their start state, clear of the wire, while it runs, and then
//    follow the solved wire (touching it, or their gap below it).
#pragma once

#include <petscvec.h>

#include "pcsim/assembly/coupled_system.hpp"

namespace pcsim::simulation {

struct StartInfo {
  PetscInt guess_iterations = 0;    // Newton iterations of the point-load guess
  PetscInt coupled_iterations = 0;  // of the coupled equilibrium (0: ramp start)
};

// Fills U0, V0 (V0 = 0) and sets every pantograph's head offset (the base
// height that puts its contact point at the wire).
StartInfo initial_state(assembly::CoupledSystem& system, Vec U0, Vec V0);

}  // namespace pcsim::simulation
