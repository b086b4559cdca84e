#include "pcsim/simulation/statics.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "pcsim/assembly/catenary_system.hpp"
#include "pcsim/assembly/static_problem.hpp"
#include "pcsim/catenary/reactions.hpp"
#include "pcsim/core/error.hpp"
#include "pcsim/solvers/modes.hpp"
#include "pcsim/solvers/statics.hpp"

namespace pcsim::simulation {

namespace {

// The ice added to the bare line's configuration and its statics solved
// again from there (no form-finding: the line was built bare).
void load_ice(MPI_Comm comm, StaticConfiguration& config, const char* options_prefix) {
  auto& mesh = config.mesh;
  for (auto& wire : mesh.wires) wire.mass_per_length += mesh.ice.on(wire.kind);
  assembly::CatenarySystem system(comm, mesh, 0, &config.node_owner);
  Vec x = system.create_vector();
  assembly::set_state_from_node_values(system, config.result.node_values, x);
  catenary::StaticResult iced;
  try {
    iced = solvers::solve_static(system, x, false, options_prefix);
  } catch (...) {
    VecDestroy(&x);
    throw;
  }
  PCSIM_PETSC(VecDestroy(&x));
  const auto& bare = config.result;
  for (int w : mesh.contact_wire_list())
    for (int n : mesh.wires[w].nodes)
      config.ice.max_contact_drop_m = std::max(
          config.ice.max_contact_drop_m, bare.node_values[6 * n + 2] - iced.node_values[6 * n + 2]);
  for (std::size_t k = 0; k < bare.segment_tensions.size() && k < iced.segment_tensions.size(); ++k)
    config.ice.max_tension_change_rel =
        std::max(config.ice.max_tension_change_rel,
                 std::abs(iced.segment_tensions[k] / bare.segment_tensions[k] - 1.0));
  config.ice.snes_iterations = iced.snes_iterations;
  iced.max_height_error_m = bare.max_height_error_m;  // of the form-finding
  iced.max_tension_error_rel = bare.max_tension_error_rel;
  iced.registration_forces = catenary::registration_forces(system.mesh(), iced.node_values);
  config.mesh = system.mesh();
  config.result = std::move(iced);
}

}  // namespace

std::string ice_summary(const StaticConfiguration& config) {
  const auto& ice = config.mesh.ice;
  if (!ice.any()) return "";
  std::string on;
  char text[320];
  const std::pair<const char*, double> kinds[] = {
      {"contact", ice.contact}, {"messenger", ice.messenger}, {"stitch", ice.stitch}};
  for (const auto& [kind, m] : kinds)
    if (m > 0) {
      std::snprintf(text, sizeof text, "%s%g kg/m on the %s wires", on.empty() ? "" : ", ", m,
                    kind);
      on += text;
    }
  std::snprintf(text, sizeof text,
                "ice: %s (after form-finding, %d Newton iterations): contact wire down by at "
                "most %.1f mm, tensions changed by at most %.2f %%",
                on.c_str(), config.ice.snes_iterations, 1e3 * config.ice.max_contact_drop_m,
                100 * config.ice.max_tension_change_rel);
  return text;
}

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
  if (config.mesh.ice.any()) load_ice(comm, config, options_prefix);
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
