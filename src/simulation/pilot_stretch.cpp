// Where the accuracy pilot runs (accuracy_pilot.hpp, PilotStretch), and the
// run's options it sets aside (RunStopsSetAside).
#include <petscsys.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "pcsim/core/error.hpp"
#include "pcsim/simulation/accuracy_pilot.hpp"

namespace pcsim::simulation {

PilotStretch pilot_stretch(const scene::RunScene& run) {
  const auto& support_x = run.catenary.mesh.support_x;
  PilotStretch s;
  s.from_span = run.analysis_from_span;
  // Two spans stand for the others where every span is alike; elsewhere the
  // whole section, at most kPilotMaxSpans of it.
  s.spans_alike = run.catenary.mesh.identical_spans;
  const int spans = s.spans_alike ? 2 : kPilotMaxSpans;
  s.to_span = std::min(run.analysis_to_span, run.analysis_from_span + spans - 1);
  s.from_x = support_x[s.from_span - 1];
  s.to_x = support_x[s.to_span];
  // The train starts where the run starts it, however far along the stretch
  // lies: the figures of a stretch are those of the trajectory that reaches
  // it (a train started two spans before it missed the reduction error of
  // the run's own trajectory: docs/benchmarks.md, "A pilot's train where
  // the run starts it").
  double rear = run.pantographs.front().start_x;
  for (const auto& p : run.pantographs) rear = std::min(rear, p.start_x);
  const double edge = 3 / run.cutoff_hz * run.speed;  // scene/run_scene_edges.cpp
  // The rearmost pantograph passes to_x by the filter's edge and a metre
  // (end_x is where the scene's first pantograph stops).
  s.end_x = std::min(run.end_x, s.to_x + edge + 1.0 + (run.pantographs.front().start_x - rear));
  return s;
}

// Why the pilot's stretch is what it is, where the line's spans differ.
std::string pilot_stretch_note(const PilotStretch& s, const scene::RunScene& run) {
  if (s.spans_alike) return "";
  if (s.to_span == run.analysis_to_span) return " (the spans differ: the whole analysis section)";
  return " (the spans differ: the section's first " + std::to_string(kPilotMaxSpans) + " of " +
         std::to_string(run.analysis_to_span - run.analysis_from_span + 1) + " spans)";
}

namespace {
constexpr const char* kRunStops[] = {"-ts_max_steps", "-ts_max_time", "-pcsim_debug_signal_step",
                                     "-pcsim_debug_signal_rank"};
}  // namespace

bool run_stop_option(const std::string& name) {
  for (const char* stop : kRunStops)
    if (name == stop + 1) return true;
  return false;
}

RunStopsSetAside::RunStopsSetAside() {
  for (const char* name : kRunStops) {
    char value[256] = "";
    PetscBool given = PETSC_FALSE;
    PCSIM_PETSC(PetscOptionsGetString(nullptr, nullptr, name, value, sizeof value, &given));
    if (!given) continue;
    kept_.emplace_back(name, value);
    PCSIM_PETSC(PetscOptionsClearValue(nullptr, name));
  }
}

RunStopsSetAside::~RunStopsSetAside() {
  for (const auto& [name, value] : kept_)
    PetscOptionsSetValue(nullptr, name.c_str(), value.empty() ? nullptr : value.c_str());
}

void check_pilot_without_jacobian_test() {
  for (const char* option : {"-snes_test_jacobian", "-snes_fd", "-snes_fd_color"}) {
    PetscBool given = PETSC_FALSE;
    PCSIM_PETSC(PetscOptionsHasName(nullptr, nullptr, option, &given));
    if (given)
      throw SolverError(std::string("the accuracy pilot: ") + option +
                        " would difference every Jacobian of its runs (the run's own still are; "
                        "-pcsim_accuracy_pilot false skips the pilot)");
  }
}

}  // namespace pcsim::simulation
