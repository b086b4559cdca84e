// The 'catenary' section of a scene:
//   catenary:
//     design: ../meshes/en50318-reference.yaml   # path relative to the scene
//     form_finding: true                         # default: the design's default
//     model: linear            # fidelity of a dynamic run: nonlinear | linear | modal
//     max_frequency_hz: 70     # modal cut-off [Hz] or 'all'; default: set by the run scene
//     modal: {dropper_shapes: true, contact_flexibility: true, modes: all | vertical,
//             participation: 0.03, droppers: bounded | all, bars: slack | exact}
//   elasticity: {force: 100, from_x: 240, to_x: 300, step: 1}   # pcsim static
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "pcsim/catenary/mesh.hpp"
#include "pcsim/catenary/reduced_basis.hpp"
#include "pcsim/scene/design_reader.hpp"
#include "pcsim/scene/yaml_input.hpp"

namespace pcsim::scene {

// 'elasticity' (pcsim static): uplift under 'force' at from_x, from_x + step,
// ..., to_x (stations on the line).
struct ElasticityRequest {
  double force = 100;  // [N]
  double from_x = 0, to_x = 0, step = 1;
  std::vector<double> stations() const;
};

struct CatenaryScene {
  std::string design_path;
  bool form_finding = false;
  catenary::CatenaryMesh mesh;
  catenary::CatenaryFidelity fidelity = catenary::CatenaryFidelity::linear;
  bool fidelity_given = false;      // the scene has catenary.model
  catenary::ModalSettings modal;              // model: modal
  bool modal_cutoff_given = false;  // catenary.max_frequency_hz (else the run scene sets it)
  std::string scene_file;           // for messages about these keys
  std::optional<ElasticityRequest> elasticity;
};

// 'size_check' sees the design's mesh size before the mesh is built.
// 'build', when given, builds the mesh from the design's node instead of
// build_catenary_design (a moving window builds part of the line; run_scene.hpp).
using DesignBuilder = std::function<catenary::CatenaryMesh(const InputNode& design, const MeshSizeCheck&)>;
CatenaryScene load_catenary_scene(const InputNode& scene, const MeshSizeCheck& size_check = {},
                                  const DesignBuilder& build = {});
// The fidelity keys of a catenary section (model, max_frequency_hz, modal).
void read_catenary_model(const InputNode& section, CatenaryScene& out);

// The 'modes' section (pcsim modes): {count: N >= 1 (20), max_frequency_hz: F > 0 (none: 0)}.
struct ModesSection {
  int count = 20;
  double max_frequency_hz = 0;
};
ModesSection load_modes_section(const InputNode& scene);

// Checks the top-level keys of a scene file (every pcsim command reads the
// same scene format and rejects unknown sections).
void check_scene_sections(const InputNode& scene);

}  // namespace pcsim::scene
