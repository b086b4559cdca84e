#include "pcsim/scene/catenary_scene.hpp"

#include <fstream>

#include "pcsim/scene/design_reader.hpp"

namespace pcsim::catenary {

void check_scene_sections(const InputNode& scene) {
  scene.allow_only({"name", "description", "catenary", "modes", "pantographs", "pantograph",
                    "simulation", "effects", "contact", "analysis", "output", "study"});
}

CatenaryScene load_catenary_scene(const InputNode& scene) {
  check_scene_sections(scene);
  const InputNode section = scene["catenary"];
  section.allow_only({"design", "form_finding"});
  CatenaryScene out;
  out.design_path = section.resolve_path(section.get_string("design"));
  if (!std::ifstream(out.design_path))
    section.fail_key("design", "cannot open catenary design file '" + out.design_path + "'");
  out.mesh = load_catenary_design(out.design_path);
  out.form_finding = section.get_bool("form_finding", out.mesh.form_finding_default);
  return out;
}

}  // namespace pcsim::catenary
