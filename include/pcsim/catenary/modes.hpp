// Catenary modes about the static configuration (SLEPc).
//
// Generalised symmetric eigenproblem K_T phi = omega^2 M phi with the tangent
// stiffness K_T at the static configuration and the constant mass matrix M;
// constrained DOFs are not unknowns. Shift-and-invert about 0 (the lowest
// modes) or spectrum slicing over [0, (2 pi f_max)^2] when a maximum
// frequency is given. Every -eps_*, -st_* option applies.
#pragma once

#include <petscvec.h>

#include <string>
#include <vector>

#include "pcsim/assembly/catenary_system.hpp"

namespace pcsim::catenary {

struct ModesResult {
  std::vector<double> frequencies_hz;  // ascending
  // Mode shapes as node displacements (3 per node, all nodes), mass-normalised;
  // filled on every rank when requested.
  std::vector<std::vector<double>> shapes;
  int requested = 0;
  int converged = 0;
  double max_relative_residual = 0;  // ||K phi - w^2 M phi|| / (w^2 ||M phi||)
  double wall_time_s = 0;
};

// nev: number of modes (when max_frequency_hz <= 0); max_frequency_hz > 0:
// every mode below it. 'x' is the static configuration of 'system'.
ModesResult compute_modes(assembly::CatenarySystem& system, Vec x, int nev, double max_frequency_hz,
                          bool want_shapes);

}  // namespace pcsim::catenary
