// The 'catenary' section of a scene:
//   catenary:
//     design: ../meshes/en50318-reference.yaml   # path relative to the scene
//     form_finding: true                         # default: the design's default
#pragma once

#include <string>

#include "pcsim/catenary/mesh.hpp"
#include "pcsim/scene/design_reader.hpp"
#include "pcsim/scene/yaml_input.hpp"

namespace pcsim::catenary {

struct CatenaryScene {
  std::string design_path;
  bool form_finding = false;
  CatenaryMesh mesh;
};

// 'size_check' sees the design's mesh size before the mesh is built.
CatenaryScene load_catenary_scene(const InputNode& scene, const MeshSizeCheck& size_check = {});

// Checks the top-level keys of a scene file (every pcsim command reads the
// same scene format and rejects unknown sections).
void check_scene_sections(const InputNode& scene);

}  // namespace pcsim::catenary
