// The acceleration a dynamic run starts with (thesis 3.3.1), from the coupled
// system's residual and the pantographs' mass matrices.
#pragma once

#include <petscvec.h>

#include "pcsim/assembly/coupled_system.hpp"

namespace pcsim::assembly {

// The acceleration at (0, U0, V0): zero for the catenary (in static
// equilibrium, untouched at t = 0) and for pantographs that start in
// equilibrium (static and ramp starts); M_p^-1 (-R_p) for a pantograph with a
// gap start (below the wire with its full uplift), R_p its rows of
// F(0, U0, V0, 0) (collective).
void initial_acceleration(CoupledSystem& system, Vec U0, Vec V0, Vec A0);

}  // namespace pcsim::assembly
