// The run pipeline: one dynamic run of a scene, from its static configuration
// to its results (docs/architecture.md, "The run pipeline"). `pcsim run`,
// `pcsim study accuracy`, the tests and the Python API all run a scene
// through simulation::run():
//   static configuration (of the line, or of a moving window) -> catenary model
//   (FE or modal, simulation/catenary_setup.hpp) and coupled system -> initial
//   state (or a checkpoint) -> accuracy estimate -> time integration
//   (simulation/run_session.hpp), every step streamed to results.h5 ->
//   statistics, line and energy results, summary.json.
// The caller makes the output folder and commits it (or keeps it partial).
// Re-entrant: nothing is kept between calls; a failure is an exception
// (InputError, SolverError, FailedOnOtherRank) on every rank of ctx.comm.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "pcsim/contact/records.hpp"
#include "pcsim/output/energy_results.hpp"
#include "pcsim/output/output_dir.hpp"
#include "pcsim/output/run_results.hpp"
#include "pcsim/scene/run_scene.hpp"
#include "pcsim/simulation/accuracy_estimate.hpp"
#include "pcsim/simulation/context.hpp"
#include "pcsim/simulation/run_checkpoint.hpp"

namespace pcsim::simulation {

// What a run needs besides its scene.
struct RunRequest {
  std::string name;                        // the scene's name (summary.json, results.h5)
  std::string scene_path;                  // as given (messages)
  std::vector<InputFile> inputs;           // fingerprint stored in checkpoints (run_input_files)
  const RunCheckpoint* restart = nullptr;  // continue from this checkpoint (load_run_checkpoint)
  std::string restart_dir;                 // the folder it came from
  bool stop_on_signal = true;  // SIGINT/SIGTERM stop the run at its next step, data kept
  bool scene_dt = false;       // the scene's dt over -ts_dt (the variants of a study)
  // -help: set up every solver (each lists the options it reads), then stop
  // before the time loop; nothing is written.
  bool stop_before_stepping = false;
  // The accuracy pilot's estimate (accuracy_pilot.hpp), into summary.json's
  // accuracy_estimate.pilot; null: none ran.
  nlohmann::json accuracy_pilot;
};

// Called on every rank after every accepted step (and for the start), in step
// order, with the step's record as results.h5 gets it (rank 0's complete).
class RunObserver {
 public:
  virtual ~RunObserver() = default;
  virtual void on_record(const contact::StepRecord& record) = 0;
};

struct RunOutcome {
  int signal = 0;             // the signal that stopped the run (0: it was not stopped)
  bool complete = false;      // not stopped by a signal: it reached its end time or -ts_max_steps
  bool checkpointed = false;  // a checkpoint at its last step (interrupted or stopped early)
  long steps = 0;
  double time = 0;            // simulated [s]
  double setup_s = 0;         // wall time before the time loop [s]
  bool statics_kept = false;  // the static configuration kept by an earlier run (setup_memory.hpp)
  output::RunSettings settings;
  nlohmann::json facts;          // summary.json's solver, performance and fidelity facts
  output::RunStatistics stats;   // complete runs, rank 0
  output::EnergyBalance energy;  // output.energy, complete runs, rank 0
  AccuracyEstimate estimate;
  std::string step_time_summary;  // the step-time distribution (step_timing.hpp), console lines
};

// Whether the scene's terms allow the cheap Jacobian path (every tangent
// constant, low rank or a block of its own): a linearised or modal catenary.
bool cheap_path_possible(const scene::RunScene& scene);

// Runs 'scene' (its pantograph models are moved out) into 'out'; collective
// on ctx.comm.
RunOutcome run(const Context& ctx, scene::RunScene& scene, const RunRequest& request,
               output::OutputDir& out, RunObserver* observer = nullptr);

}  // namespace pcsim::simulation
