// Static elasticity of a catenary (EN 50119): for every station x, the static
// configuration under an upward force F on the lowest contact wire at x (the
// point-load static problem of the static start, Newton from the unloaded
// configuration), and the uplift of the wire at x. Options prefix
// -elasticity_ for the SNES.
#pragma once

#include <vector>

#include "pcsim/catenary/results.hpp"
#include "pcsim/simulation/statics.hpp"
#include "pcsim/solvers/statics.hpp"

namespace pcsim::simulation {

catenary::ElasticityResult static_elasticity(MPI_Comm comm,
                                             const simulation::StaticConfiguration& statics,
                                             const std::vector<double>& x, double force);

}  // namespace pcsim::simulation
