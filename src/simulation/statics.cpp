#include "pcsim/simulation/statics.hpp"

#include "pcsim/assembly/catenary_system.hpp"
#include "pcsim/assembly/static_problem.hpp"
#include "pcsim/catenary/reactions.hpp"
#include "pcsim/core/error.hpp"
#include "pcsim/solvers/modes.hpp"
#include "pcsim/solvers/statics.hpp"

namespace pcsim::simulation {

StaticConfiguration static_configuration(MPI_Comm comm, const catenary::CatenaryMesh& design,
                                         bool form_finding, const char* options_prefix) {
  const PetscInt extra = form_finding ? assembly::form_finding_unknowns(design) : 0;
  assembly::CatenarySystem system(comm, design, extra);
  Vec x = system.create_vector();
  system.design_state(x);
  StaticConfiguration config;
  try {
    config.result = solvers::solve_static(system, x, form_finding, options_prefix);
  } catch (...) {
    VecDestroy(&x);
    throw;
  }
  PCSIM_PETSC(VecDestroy(&x));
  config.mesh = system.mesh();
  // Pull-off forces, and the tensioning devices released with the anchors'
  // forces: later systems (modes, dynamics) see the devices.
  config.result.registration_forces =
      catenary::registration_forces(config.mesh, config.result.node_values);
  catenary::release_tensioning_devices(config.mesh, config.result.node_values);
  config.node_owner = system.layout().node_owner();
  config.catenary_dofs = system.layout().catenary_dofs();
  return config;
}

catenary::ModesResult catenary_modes(MPI_Comm comm, const StaticConfiguration& statics, int nev,
                                     double max_frequency_hz, bool want_shapes) {
  assembly::CatenarySystem system(comm, statics.mesh, 0, &statics.node_owner);
  Vec x = system.create_vector();
  assembly::set_state_from_node_values(system, statics.result.node_values, x);
  auto modes = solvers::compute_modes(system, x, nev, max_frequency_hz, want_shapes);
  PCSIM_PETSC(VecDestroy(&x));
  return modes;
}

}  // namespace pcsim::simulation
