// The 'catenary' section of a scene:
//   catenary:
//     design: ../meshes/en50318-reference.yaml   # path relative to the scene
//     form_finding: true                         # default: the design's default
//     model: linear            # fidelity of a dynamic run: nonlinear | linear | modal
//     max_frequency_hz: 70     # modal cut-off [Hz] or 'all'; default: set by the run scene
//     modal: {dropper_shapes: true, contact_flexibility: true, modes: all | vertical,
//             participation: 0.03, droppers: bounded | all, bars: slack | exact}
#pragma once

#include <string>

#include "pcsim/catenary/mesh.hpp"
#include "pcsim/catenary/reduced_basis.hpp"
#include "pcsim/scene/yaml_input.hpp"

namespace pcsim::catenary {

struct CatenaryScene {
  std::string design_path;
  bool form_finding = false;
  CatenaryMesh mesh;
  CatenaryFidelity fidelity = CatenaryFidelity::linear;
  bool fidelity_given = false;      // the scene has catenary.model
  ModalSettings modal;              // model: modal
  bool modal_cutoff_given = false;  // catenary.max_frequency_hz (else the run scene sets it)
  std::string scene_file;           // for messages about these keys
};

CatenaryScene load_catenary_scene(const InputNode& scene);
// The fidelity keys of a catenary section (model, max_frequency_hz, modal).
void read_catenary_model(const InputNode& section, CatenaryScene& out);

// Checks the top-level keys of a scene file (every pcsim command reads the
// same scene format and rejects unknown sections).
void check_scene_sections(const InputNode& scene);

}  // namespace pcsim::catenary
