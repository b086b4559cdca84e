// Checkpoint/restart of `pcsim run` (README "Interrupted runs and restarts",
// docs/results-format.md): what a checkpoint holds beyond the solver's state,
// the fingerprint of the input files, and the checks a restart makes.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "pcsim/output/provenance.hpp"
#include "pcsim/scene/yaml_input.hpp"
#include "pcsim/simulation/context.hpp"
#include "pcsim/solvers/dynamics.hpp"

namespace pcsim::simulation {

// An input file of the run and the SHA-256 (hex) of its content as the run
// reads it: composed with its base files, 'set' entries and --set overrides
// (scene/composition.hpp), as YAML.
struct InputFile {
  std::string role;  // "scene", "design", "pantograph model <n>"
  std::string path;
  std::string sha256;
};

// The scene (composed), its design, every pantograph's model and the
// criteria set file it names, if any (every rank).
std::vector<InputFile> run_input_files(const std::string& scene_path,
                                       const scene::InputNode& scene);

// Every input file of a scene as the command reads it, with its content: the
// scene (composed), and every file it names under a key 'design', 'model',
// 'rigid_model' or 'criteria' at any depth (designs, pantograph models, the
// rigid model of a flexible one, a criteria set's file), each composed with
// its own base files and 'set' entries.
// Roles: "scene", then the key path ("catenary.design", "pantographs[0].model",
// "pantographs[0].model.rigid_model").
struct RecordedInput {
  std::string role, path, sha256;
  std::string content;  // the composed YAML the command read
};
std::vector<RecordedInput> recorded_inputs(const std::string& scene_path,
                                           const scene::InputNode& scene);

// One SHA-256 (hex) over the command and the contents of its inputs: two
// results with the same fingerprint were made from the same inputs.
std::string inputs_fingerprint(const std::string& command,
                               const std::vector<RecordedInput>& inputs);

// The provenance's record of the inputs (output/provenance.hpp): the scene as
// composed, every input file [{role, path, sha256, content}] and the
// fingerprint over 'command' and them.
void record_inputs(output::ProvenanceInputs& in, const std::string& command,
                   const std::string& scene_path, const scene::InputNode& scene);

// Where the run stands besides the solver's state.
struct RunProgress {
  std::size_t records = 0;    // rows of results.h5 (accepted steps + the start)
  std::size_t snapshots = 0;  // snapshots in results.h5
  long newton_iterations = 0;
  long rejected_steps = 0;  // HHT steps rejected and retried with a smaller Δt
  double wall_time_s = 0;   // of the time integration so far
};

struct RunCheckpoint {
  solvers::DynamicState state;  // vectors on rank 0 only
  RunProgress progress;
  std::string path;  // Jacobian path: "cheap" or "full"
  int ranks = 1;
  std::vector<InputFile> inputs;
  // The modal level's cut-off the run had (its accuracy pilot may have raised
  // it from the scene's default): a restart takes it. 0: an FE level, or a
  // checkpoint from before it was kept.
  double modal_cutoff_hz = 0;
  // The moving window's shifts at the checkpoint (the state is the window's
  // after them); -1: a run without a window.
  int window_shifts = -1;
};

// Writes 'file' on rank 0 (atomically); collective, the outcome agreed.
void write_run_checkpoint(const Context& ctx, const std::string& file,
                          const RunCheckpoint& checkpoint);

// The checkpoint in folder 'dir' (given with --restart), checked against this
// run: the same input files and rank count; else InputError("command line",
// "--restart", why) on every rank (a scene that differs names the --set
// overrides of both runs, those of the checkpointed one from DIR's
// summary.json). Collective: rank 0 reads, the rest is broadcast (vectors
// stay on rank 0).
RunCheckpoint load_run_checkpoint(const Context& ctx, const std::string& dir,
                                  const std::vector<InputFile>& inputs,
                                  const std::vector<std::string>& overrides);

// The summary.json of the run in folder 'dir' (a restart's checkpointed run),
// read where it is called; null if it is missing or not JSON.
nlohmann::json checkpointed_summary(const std::string& dir);

// Refuses (InputError on --restart) a new result folder that is the restart
// folder or its partial folder: a restart reads DIR and writes a new result.
void check_restart_target(const std::string& restart_dir, const std::string& final_dir);

}  // namespace pcsim::simulation
