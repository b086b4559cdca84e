#include "pcsim/simulation/statics.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "pcsim/assembly/catenary_system.hpp"
#include "pcsim/assembly/static_problem.hpp"
#include "pcsim/catenary/reactions.hpp"
#include "pcsim/catenary/wind.hpp"
#include "pcsim/core/error.hpp"
#include "pcsim/core/format.hpp"
#include "pcsim/solvers/modes.hpp"
#include "pcsim/solvers/statics.hpp"

namespace pcsim::simulation {

namespace {

// The conditions' changes of the bare line: ice on wires and stitch bars
// (mass and weight), the wires' unstressed lengths stretched by alpha dT,
// the mean wind's drag on the wires (a dead load like the weight).
void change_line(catenary::CatenaryMesh& mesh) {
  catenary::set_wind_loads(mesh);
  const auto& c = mesh.conditions;
  for (auto& wire : mesh.wires) wire.mass_per_length += c.ice.on(wire.kind);
  for (auto& bar : mesh.bars)
    if (bar.kind == catenary::BarKind::stitch) bar.mass += c.ice.stitch * bar.unstressed_length;
  for (auto& cable : mesh.cables)
    cable.unstressed_length *=
        1 + mesh.wires[cable.wire].thermal_expansion * c.temperature_change_k;
}

// What the conditions did: the contact wires' height changes, the tension
// segments' tension changes, each device's travel (beyond its own: a warning).
void measure_change(const catenary::CatenaryMesh& mesh, const catenary::StaticResult& bare,
                    catenary::StaticResult& now, ConditionsEffect& e) {
  const auto z = [](const catenary::StaticResult& r, int n) { return r.node_values[6 * n + 2]; };
  for (int w : mesh.contact_wire_list())
    for (int n : mesh.wires[w].nodes) {
      e.min_contact_dz_m = std::min(e.min_contact_dz_m, z(now, n) - z(bare, n));
      e.max_contact_dz_m = std::max(e.max_contact_dz_m, z(now, n) - z(bare, n));
      const double dx = now.node_values[6 * n] - bare.node_values[6 * n];
      const double dy = now.node_values[6 * n + 1] - bare.node_values[6 * n + 1];
      e.max_contact_dy_m = std::max(e.max_contact_dy_m, std::hypot(dx, dy));
    }
  for (std::size_t k = 0; k < bare.segment_tensions.size() && k < now.segment_tensions.size(); ++k)
    e.max_tension_change_rel = std::max(
        e.max_tension_change_rel, std::abs(now.segment_tensions[k] / bare.segment_tensions[k] - 1));
  for (const auto& dev : mesh.tensioning_devices) {
    Eigen::Vector3d move;
    for (int c = 0; c < 3; ++c)
      move[c] = now.node_values[6 * dev.node + c] - bare.node_values[6 * dev.node + c];
    const double along = move.dot(dev.direction);  // > 0: away from the wire
    e.max_device_travel_m = std::max(e.max_device_travel_m, std::abs(along));
    if (dev.travel > 0 && std::abs(along) > dev.travel)
      now.warnings.push_back("the tensioning device of wire '" + mesh.wires[dev.wire].name +
                             "' at node " + std::to_string(dev.node) + " needs " +
                             format_number(1e3 * along) + " mm of travel, beyond its " +
                             format_number(1e3 * dev.travel) +
                             " mm (tensioning.travel): it would be at its stop, the tension "
                             "no longer held");
  }
}

// A temperature change on a wire that a device tensions but whose stretch
// between two interior supports that hold it along the track (fixed
// messenger supports: no cantilever swing) has no device: that stretch
// changes tension as between fixed terminations. A midpoint anchor leaves a
// device on each side: no warning.
void warn_held_wires(const catenary::CatenaryMesh& mesh, catenary::StaticResult& now) {
  if (mesh.conditions.temperature_change_k == 0) return;
  std::vector<bool> device(mesh.nodes.size(), false), tensioned(mesh.wires.size(), false);
  for (const auto& dev : mesh.tensioning_devices) device[dev.node] = tensioned[dev.wire] = true;
  for (std::size_t w = 0; w < mesh.wires.size(); ++w) {
    if (!tensioned[w]) continue;
    const auto& nodes = mesh.wires[w].nodes;
    long held = 0;  // stretches between two holds, neither end a device
    int from = nodes.front();
    for (std::size_t k = 1; k < nodes.size(); ++k) {
      const int n = nodes[k];
      if (k + 1 < nodes.size() && !mesh.nodes[n].fixed[0]) continue;
      if (!device[from] && !device[n]) ++held;
      from = n;
    }
    if (held > 0)
      now.warnings.push_back(
          "wire '" + mesh.wires[w].name + "' has a tensioning device, but " + std::to_string(held) +
          " of its stretches lie between supports that hold it along the track (no cantilever "
          "swing): under the temperature change they change tension as between fixed "
          "terminations (docs/conditions.md)");
  }
}

// The bare line's configuration under its conditions: changed, and its
// statics solved again from there (no form-finding: the line was built bare).
void apply_conditions(MPI_Comm comm, StaticConfiguration& config, const char* options_prefix) {
  auto mesh = config.mesh;
  change_line(mesh);
  assembly::CatenarySystem system(comm, mesh, 0, &config.node_owner);
  Vec x = system.create_vector();
  assembly::set_state_from_node_values(system, config.result.node_values, x);
  catenary::StaticResult now;
  try {
    now = solvers::solve_static(system, x, false, options_prefix);
  } catch (...) {
    VecDestroy(&x);
    throw;
  }
  PCSIM_PETSC(VecDestroy(&x));
  const auto& bare = config.result;
  measure_change(system.mesh(), bare, now, config.conditions);
  warn_held_wires(system.mesh(), now);
  config.conditions.snes_iterations = now.snes_iterations;
  now.max_height_error_m = bare.max_height_error_m;  // of the form-finding
  now.max_tension_error_rel = bare.max_tension_error_rel;
  now.registration_forces = catenary::registration_forces(system.mesh(), now.node_values);
  if (system.mesh().conditions.wind.any())
    now.blow_off = catenary::measure_blow_off(system.mesh(), bare.node_values, now.node_values);
  config.mesh = system.mesh();
  config.result = std::move(now);
}

}  // namespace

std::string conditions_summary(const StaticConfiguration& config) {
  const auto& c = config.mesh.conditions;
  if (!c.any()) return "";
  std::string on;
  char text[400];
  const std::pair<const char*, double> kinds[] = {
      {"contact", c.ice.contact}, {"messenger", c.ice.messenger}, {"stitch", c.ice.stitch}};
  for (const auto& [kind, m] : kinds)
    if (m > 0) {
      std::snprintf(text, sizeof text, "%sice %g kg/m on the %s wires", on.empty() ? "" : ", ", m,
                    kind);
      on += text;
    }
  if (c.temperature_change_k != 0) {
    std::snprintf(text, sizeof text, "%s%+g K from the design temperature", on.empty() ? "" : ", ",
                  c.temperature_change_k);
    on += text;
  }
  const auto& e = config.conditions;
  if (c.wind.any()) {
    std::snprintf(text, sizeof text,
                  "%swind %g m/s at %g deg to the track (contact wires moved at most %.1f mm "
                  "horizontally)",
                  on.empty() ? "" : ", ", c.wind.speed, c.wind.direction_deg,
                  1e3 * e.max_contact_dy_m);
    on += text;
    const auto& t = c.wind.turbulence;
    if (t.on) {
      std::snprintf(text, sizeof text,
                    ", turbulence I_u %.3f, L_u %.1f m, seed %lu (dynamic runs, every level and "
                    "window)",
                    t.intensity, t.length_scale, t.seed);
      on += text;
    }
  }
  std::snprintf(text, sizeof text,
                "conditions: %s (after form-finding, %d Newton iterations): contact wire %+.1f .. "
                "%+.1f mm, tensions changed by at most %.2f %%, tensioning devices moved at most "
                "%.1f mm",
                on.c_str(), e.snes_iterations, 1e3 * e.min_contact_dz_m, 1e3 * e.max_contact_dz_m,
                100 * e.max_tension_change_rel, 1e3 * e.max_device_travel_m);
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
  if (config.mesh.conditions.any()) apply_conditions(comm, config, options_prefix);
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
