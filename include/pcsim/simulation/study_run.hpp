// One run of an accuracy study (`pcsim study accuracy`): the scene at another
// fidelity, time step, element length or modal cut-off, run in this process
// on every rank as `pcsim run` would, its results in a folder of its own.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "pcsim/catenary/reduced_basis.hpp"
#include "pcsim/output/accuracy_study.hpp"
#include "pcsim/scene/run_scene.hpp"
#include "pcsim/scene/yaml_input.hpp"
#include "pcsim/simulation/context.hpp"

namespace pcsim::simulation {

struct StudyVariant {
  catenary::CatenaryFidelity model = catenary::CatenaryFidelity::linear;
  double dt_factor = 1, h_factor = 1;
  double cutoff_factor = 0;  // modal: cut-off over cutoff_hz / (1 - v/c); 0: the scene's
  bool vertical_only = false;
};

// A scene as its file and overrides give it.
struct SceneSource {
  std::string path;                    // the scene file
  std::vector<std::string> overrides;  // KEY=VALUE, in order (--set)
  scene::InputNode scene;              // composed from both
  nlohmann::json provenance;           // of the study (output/provenance.hpp)
};

// The scene of the source changed as the variant says (h: the design's
// element length, through a --set of catenary.design.element_length when
// h_factor != 1); no snapshots, no dropper forces.
scene::RunScene variant_scene(const SceneSource& source, const StudyVariant& variant, double h);

// Runs the variant of the scene through the run pipeline (run.hpp), quietly;
// results into run_dir (a new folder). Solver failures are recorded in the
// returned run (ok = false).
output::StudyRun run_variant(const Context& ctx, const SceneSource& source,
                             const StudyVariant& variant, const std::string& run_dir);

// The element length of the scene's catenary design (0 for an explicit
// design, which has none: the study leaves its mesh alone).
double design_element_length(const scene::InputNode& scene);

}  // namespace pcsim::simulation
