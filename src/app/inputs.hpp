// Every command's inputs, read and checked before any work: one function per
// command reads the scene and every file it names, the command-line numerics
// and the memory the mesh will need, so that an input error (file, key,
// reason; exit 2) is found before anything is written or solved. The commands
// and `pcsim check` call the same functions.
#pragma once

#include <string>
#include <vector>

#include "command.hpp"
#include "pcsim/core/error.hpp"
#include "pcsim/pantograph/study.hpp"
#include "pcsim/scene/catenary_scene.hpp"
#include "pcsim/scene/run_scene.hpp"
#include "pcsim/simulation/memory_estimate.hpp"
#include "pcsim/solvers/command_line.hpp"
#include "pcsim/solvers/modes.hpp"

namespace pcsim::app {

// `static` (and the first half of `modes`).
struct StaticInputs {
  scene::InputNode scene;
  std::string name;  // the scene's name (output folder)
  scene::CatenaryScene catenary;
  simulation::MemoryEstimate memory;
};
StaticInputs read_static_inputs(const CommandContext& ctx);

struct ModesInputs {
  StaticInputs statics;
  solvers::ModesRequest request;  // scene 'modes', -eps_nev, -modes_fmax
};
ModesInputs read_modes_inputs(const CommandContext& ctx);

struct RunInputs {
  scene::InputNode scene;
  std::string name;
  scene::RunScene run;
  solvers::TimeIntegrationOptions numerics;  // -ts_dt, -ts_type, -ts_hht_alpha
  bool cheap_path = false;                   // -pcsim_path and the scene's terms
  simulation::MemoryEstimate memory;
};
RunInputs read_run_inputs(const CommandContext& ctx);
// The same for a scene composed by the caller (the cases of `pcsim sweep`).
RunInputs read_run_inputs(const CommandContext& ctx, const scene::InputNode& scene);

// The folder given with `pcsim run --restart DIR`, or "".
std::string restart_dir(const CommandContext& ctx);

struct PantographInputs {
  scene::InputNode scene;
  std::string name;
  pantograph::StudyScene study;
};
PantographInputs read_pantograph_inputs(const CommandContext& ctx);

// A catenary design file alone (`pcsim check DESIGN.yaml`, composed, with --set).
struct DesignInputs {
  catenary::CatenaryMesh mesh;
  simulation::MemoryEstimate memory;
};
DesignInputs read_design_inputs(const CommandContext& ctx);

}  // namespace pcsim::app
