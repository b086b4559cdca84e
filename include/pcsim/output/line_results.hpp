// Results of a run on a line of several tension sections (docs/lines.md):
// the EN 50318 contact-force statistics over each section's own stretch and
// over each overlap (the zones of the mesh), and the force of every
// pantograph on every contact wire (contact_wires.h5). Separate from
// run_results.hpp on purpose: it takes the histories as plain vectors.
// Called on rank 0.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "pcsim/catenary/mesh.hpp"
#include "pcsim/output/output_dir.hpp"
#include "pcsim/output/statistics.hpp"

namespace pcsim::output {

// One pantograph's history: one entry per accepted step.
struct ContactHistory {
  std::string name;
  std::vector<double> time, x, force;           // x: station; force: on the head
  std::vector<std::vector<double>> wire_force;  // per step: force on each contact wire
};

struct ZoneStatistics {
  catenary::LineZone zone;
  bool complete = false;  // the pantograph crossed the whole zone
  ForceStatistics force;  // of the force low-pass filtered at cutoff_hz
};

// Statistics of the pantograph's contact force over every zone.
std::vector<ZoneStatistics> zone_statistics(const std::vector<catenary::LineZone>& zones,
                                            const ContactHistory& history, double cutoff_hz);

// contact_wires.h5 (time, each pantograph's station, head force and force on
// each wire) and the zone statistics of every pantograph as JSON (for
// summary.json).
nlohmann::json write_line_results(const OutputDir& out, const catenary::CatenaryMesh& mesh,
                                  const std::vector<ContactHistory>& histories, double cutoff_hz);

}  // namespace pcsim::output
