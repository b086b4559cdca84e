// The static configuration of a catenary design, the start of every command
// that solves one: the static solution (solvers/statics.hpp: SNES, with
// form-finding when asked), then the pull-off forces of the steady arms and
// the tensioning devices released with the anchors' forces
// (catenary/reactions.hpp), so that later systems (modes, dynamics) see them.
#pragma once

#include <mpi.h>
#include <petscsys.h>

#include <string>
#include <vector>

#include "pcsim/catenary/mesh.hpp"
#include "pcsim/catenary/results.hpp"

namespace pcsim::simulation {

// What the conditions (docs/conditions.md) did to the line built bare: the
// contact wires' height changes, the largest change of a tension segment's
// tension (fixed terminations change it, weights hold it), the tensioning
// devices' largest travel.
struct ConditionsEffect {
  double min_contact_dz_m = 0, max_contact_dz_m = 0;
  double max_tension_change_rel = 0;
  double max_device_travel_m = 0;
  double max_contact_dy_m = 0;  // the contact wires' largest lateral move (wind)
  int snes_iterations = 0;      // of the second static solution
};

// The design -> static configuration. The returned mesh has its tensioning
// devices released, the result the pull-off forces. Under conditions
// (mesh.conditions: ice, temperature), the line is form-found bare, its
// devices released, then changed (the wires' mass and weight, their
// unstressed lengths by alpha dT) and its statics solved again: the result
// and mesh are the changed line's; the form-finding errors stay the bare
// one's; a device beyond its travel is a warning.
struct StaticConfiguration {
  catenary::CatenaryMesh mesh;    // with the found unstressed lengths, bar equilibria
  catenary::StaticResult result;  // node values etc.
  std::vector<int> node_owner;    // the partition used (reusable by later systems)
  PetscInt catenary_dofs = 0;
  ConditionsEffect conditions;  // zero without conditions
};
StaticConfiguration static_configuration(MPI_Comm comm, const catenary::CatenaryMesh& design,
                                         bool form_finding, const char* options_prefix = nullptr);
// One line on what the conditions did ("" without any), for the console.
std::string conditions_summary(const StaticConfiguration& config);

// The catenary's modes about a static configuration (solvers/modes.hpp: nev
// modes, or every mode below max_frequency_hz > 0), on its own unknowns with
// the found unstressed lengths. Collective.
catenary::ModesResult catenary_modes(MPI_Comm comm, const StaticConfiguration& statics, int nev,
                                     double max_frequency_hz, bool want_shapes);

}  // namespace pcsim::simulation
