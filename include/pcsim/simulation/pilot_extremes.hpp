// The run's extremes against its accuracy pilot's stretch (docs/fidelity.md,
// "Where the extremes fall"). The pilot compares the levels over a stretch of
// the analysis section, starting the train where the run does: over that
// stretch its runs are the run and its reference. Its estimate of the actual
// maximum or minimum thus speaks for the run's own extreme only where that
// falls in the stretch; elsewhere it comes from another span's extreme.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "pcsim/output/run_results.hpp"

namespace pcsim::simulation {

struct ExtremeOutsidePilot {
  std::string pantograph;
  int figure = 0;   // index into kPilotFigureKeys: actual maximum, minimum or uplift
  double at_x = 0;  // where the run's extreme falls [m]
};

// The complete pantographs' actual maxima and minima that fall outside the
// stretch [from_x, to_x] [m], and for each the line's largest uplift at a
// support (each pantograph's uplift figure) where its support does.
std::vector<ExtremeOutsidePilot> extremes_outside_pilot(const output::RunStatistics& stats,
                                                        double from_x, double to_x);

// facts["accuracy_estimate"]["extremes_outside_pilot"] (an array, empty when
// every extreme falls in the stretch), where the run has a pilot's estimate
// (facts["accuracy_estimate"]["pilot"] with its stretch); else nothing.
void add_extremes_outside_pilot(const output::RunStatistics& stats, nlohmann::json& facts);

// The console's lines for them ("" when there are none).
std::string extremes_outside_pilot_text(const nlohmann::json& facts);

}  // namespace pcsim::simulation
