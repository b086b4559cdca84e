#include "pcsim/scene/catenary_scene.hpp"

#include <fstream>

#include "pcsim/scene/design_reader.hpp"

namespace pcsim::catenary {

void check_scene_sections(const InputNode& scene) {
  scene.allow_only({"name", "description", "catenary", "modes", "pantographs", "simulation",
                    "effects", "contact", "analysis", "output"});
}

CatenaryScene load_catenary_scene(const InputNode& scene) {
  check_scene_sections(scene);
  const InputNode section = scene["catenary"];
  section.allow_only({"design", "form_finding"});
  CatenaryScene out;
  out.design_path = section.path_value("design");
  if (!std::ifstream(out.design_path))
    section.fail_key("design", "cannot open catenary design file '" + out.design_path + "'");
  const InputNode design = section.load_referenced("design");
  try {
    out.mesh = build_catenary_design(design);
  } catch (const InputError& e) {
    design.rethrow_with_origin(e);
  }
  out.mesh.source_file = out.design_path;
  out.form_finding = section.get_bool("form_finding", out.mesh.form_finding_default);
  return out;
}

ModesSection load_modes_section(const InputNode& scene) {
  ModesSection r;
  if (!scene.has("modes")) return r;
  const InputNode m = scene["modes"];
  m.allow_only({"count", "max_frequency_hz"});
  r.count = static_cast<int>(m.get_int("count", 20));
  if (r.count < 1) m.fail_key("count", "must be at least 1");
  r.max_frequency_hz = m.get_positive("max_frequency_hz", 0.0);
  return r;
}

}  // namespace pcsim::catenary
