#include "pcsim/scene/catenary_scene.hpp"

namespace pcsim::catenary {

void check_scene_sections(const InputNode& scene) {
  scene.allow_only({"name", "description", "catenary", "modes", "pantographs", "pantograph",
                    "simulation", "effects", "contact", "analysis", "output", "study"});
}

CatenaryScene load_catenary_scene(const InputNode& scene, const MeshSizeCheck& size_check) {
  check_scene_sections(scene);
  const InputNode section = scene["catenary"];
  section.allow_only({"design", "form_finding"});
  CatenaryScene out;
  out.design_path = section.get_file_path("design");
  out.mesh = load_catenary_design(out.design_path, size_check);
  out.form_finding = section.get_bool("form_finding", out.mesh.form_finding_default);
  return out;
}

}  // namespace pcsim::catenary
