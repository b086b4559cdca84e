// Catenary modes about the static configuration (SLEPc).
//
// Generalised symmetric eigenproblem K_T phi = omega^2 M phi with the tangent
// stiffness K_T at the static configuration and the constant mass matrix M;
// constrained DOFs are not unknowns. Shift-and-invert about 0 (the lowest
// modes) or spectrum slicing over [0, (2 pi f_max)^2] when a maximum
// frequency is given. Every -eps_*, -st_* option applies.
#pragma once

#include <petscvec.h>

#include "pcsim/assembly/catenary_system.hpp"
#include "pcsim/catenary/results.hpp"

namespace pcsim::solvers {

// nev: number of modes (when max_frequency_hz <= 0); max_frequency_hz > 0:
// every mode below it. 'x' is the static configuration of 'system'.
catenary::ModesResult compute_modes(assembly::CatenarySystem& system, Vec x, int nev,
                                    double max_frequency_hz, bool want_shapes);

// The command-line overrides of the modes scene section, declared in the
// options database (listed by -help): -eps_nev (count) and -modes_fmax [Hz].
struct ModesRequest {
  int count = 20;
  double max_frequency_hz = 0;  // > 0: every mode below it
};
ModesRequest modes_request_from_options(MPI_Comm comm, ModesRequest scene_values);

}  // namespace pcsim::solvers
