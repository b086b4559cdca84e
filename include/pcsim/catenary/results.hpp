// Results of the catenary's static configuration (form-finding) and modes:
// plain data filled by the solver drivers (solvers/statics.hpp,
// solvers/modes.hpp) and written by the output writers.
#pragma once

#include <string>
#include <vector>

namespace pcsim::catenary {

// The contact wires' lateral position under wind (docs/conditions.md,
// "Blow-off"): at every support and mid-span, relative to the track's
// centre line (+ to the track's left, +y on straight track), under wind and
// on the bare line.
struct BlowOff {
  std::vector<double> x;             // station [m]
  std::vector<int> at_support;       // 1: a support, 0: a mid-span
  std::vector<int> wire;             // index into mesh.contact_wire_list()
  std::vector<double> lateral;       // under wind [m]
  std::vector<double> lateral_bare;  // before the conditions [m]
  double permissible_m = 0;          // working half width - sway - track tolerance
  double max_excursion_m = 0;        // largest |lateral| at any node of a contact wire
  double max_excursion_x = 0;        // its station
  bool empty() const { return x.empty(); }
};

struct StaticResult {
  bool converged = false;
  int snes_iterations = 0;
  int linear_iterations = 0;
  std::string converged_reason;
  std::vector<double> residual_history;  // ||R|| per Newton iteration
  double max_height_error_m = 0;         // over the height targets
  double max_tension_error_rel = 0;      // over the tension segments
  std::vector<double> target_heights;    // z of each target node
  std::vector<double> segment_tensions;  // mean axial force of each segment
  std::vector<double> bar_forces;        // axial force of every bar
  std::vector<double> bar_lengths;       // deformed length of every bar
  std::vector<double> node_values;       // 6 per node (r, r'), every rank
  // Lateral force of every steady arm on its wire (mesh.registrations) [N].
  std::vector<double> registration_forces;
  double wall_time_s = 0;
  double force_scale = 0;             // loads: max(total weight, largest design tension) [N]
  double residual_norm = 0;           // final ||R||_2 [N]
  int negative_eigenvalues = -1;      // of the static tangent (-1: not computed)
  std::vector<std::string> warnings;  // compression, unstable tangent (printed by the app)
  BlowOff blow_off;                   // under conditions.wind only
};

// Static elasticity of the contact wire (EN 50119): the uplift of the
// lowest contact wire under a vertical force at each point, from the static
// configuration.
struct ElasticityResult {
  double force = 0;            // [N], upward
  std::vector<double> x;       // stations [m]
  std::vector<double> uplift;  // [m]
  std::vector<int> wire;       // contact wire loaded (index into mesh.contact_wire_list())
};

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

}  // namespace pcsim::catenary
