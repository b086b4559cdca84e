// The 'catenary' section of a scene:
//   catenary:
//     design: ../meshes/en50318-reference.yaml   # path relative to the scene
//     form_finding: true                         # default: the design's default
//   elasticity: {force: 100, from_x: 240, to_x: 300, step: 1}   # pcsim static
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "pcsim/catenary/mesh.hpp"
#include "pcsim/scene/yaml_input.hpp"

namespace pcsim::catenary {

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
  CatenaryMesh mesh;
  std::optional<ElasticityRequest> elasticity;
};

CatenaryScene load_catenary_scene(const InputNode& scene);

// The 'modes' section (pcsim modes): {count: N >= 1 (20), max_frequency_hz: F > 0 (none: 0)}.
struct ModesSection {
  int count = 20;
  double max_frequency_hz = 0;
};
ModesSection load_modes_section(const InputNode& scene);

// Checks the top-level keys of a scene file (every pcsim command reads the
// same scene format and rejects unknown sections).
void check_scene_sections(const InputNode& scene);

}  // namespace pcsim::catenary
