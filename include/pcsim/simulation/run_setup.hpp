// The set-up every dynamic run of a scene shares, simulation::run() and the
// step-wise Stepper: the static configuration of the line (or of its moving
// window, ends released), kept in memory across the runs of a process
// (setup_memory.hpp), and the coupled system on it, each with its console
// lines. The callers then take the initial state and build the solver with
// make_run_solver, the one place that constructs a run's dynamic solver.
#pragma once

#include <memory>

#include "pcsim/assembly/coupled_system.hpp"
#include "pcsim/core/profiling.hpp"
#include "pcsim/scene/run_scene.hpp"
#include "pcsim/simulation/catenary_setup.hpp"
#include "pcsim/simulation/context.hpp"
#include "pcsim/simulation/statics.hpp"
#include "pcsim/solvers/dynamics.hpp"

namespace pcsim::simulation {

struct RunSetup {
  StaticConfiguration statics;
  bool statics_kept = false;  // from an earlier run of this process
  CatenarySetup catenary;     // the catenary model's facts (its model is in system)
  std::unique_ptr<assembly::CoupledSystem> system;
};

// stage (or null): -log_view's phases, "Form-finding" here, then "Static start".
RunSetup set_up_run(const Context& ctx, scene::RunScene& scene, LogStage* stage);

// The dynamic solver of a run of the scene on its coupled system: HHT (or
// -ts_type) with the scene's dt, duration and alpha, on the path and step
// solver the options database chooses (solvers/dynamics.hpp).
std::unique_ptr<solvers::DynamicSolver> make_run_solver(const scene::RunScene& scene,
                                                        assembly::CoupledSystem& system);

}  // namespace pcsim::simulation
