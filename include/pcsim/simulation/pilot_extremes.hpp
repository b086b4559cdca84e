// The run's extremes against its accuracy pilot's stretch (docs/fidelity.md,
// "Where the extremes fall"). The pilot compares the levels over a stretch of
// the analysis section, starting the train where the run does: over that
// stretch its runs are the run and its reference. Its estimate of the actual
// maximum or minimum thus speaks for the run's own extreme only where that
// falls in the stretch; elsewhere it comes from another span's extreme. So
// does its estimate of the loss of contact, counted where the contact is lost.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "pcsim/output/run_results.hpp"

namespace pcsim::simulation {

struct ExtremeOutsidePilot {
  std::string pantograph;
  // Index into kPilotFigureKeys: actual maximum, minimum, uplift or loss of contact.
  int figure = 0;
  double at_x = 0;  // where the run's extreme falls; a loss: its first sample outside [m]
  // A loss of contact: its samples outside the stretch, of all its samples in the section.
  std::size_t samples_outside = 0, samples = 0;
};

// The complete pantographs' actual maxima and minima that fall outside the
// stretch [from_x, to_x] [m], for each the line's largest uplift at a
// support (each pantograph's uplift figure) where its support does, and
// each pantograph's loss of contact where a sample of it does.
std::vector<ExtremeOutsidePilot> extremes_outside_pilot(const output::RunStatistics& stats,
                                                        double from_x, double to_x);

// facts["accuracy_estimate"]["extremes_outside_pilot"] (an array, empty when
// every extreme falls in the stretch), where the run has a pilot's estimate
// (facts["accuracy_estimate"]["pilot"] with its stretch); else nothing.
void add_extremes_outside_pilot(const output::RunStatistics& stats, nlohmann::json& facts);

// The console's lines for them ("" when there are none).
std::string extremes_outside_pilot_text(const nlohmann::json& facts);

}  // namespace pcsim::simulation
