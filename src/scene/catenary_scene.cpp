#include "pcsim/scene/catenary_scene.hpp"

#include <fstream>

#include "pcsim/scene/design_reader.hpp"

namespace pcsim::catenary {

void check_scene_sections(const InputNode& scene) {
  scene.allow_only({"name", "description", "catenary", "modes", "pantographs", "pantograph",
                    "simulation", "effects", "contact", "analysis", "output", "study"});
}

namespace {

void read_modal_settings(const InputNode& modal, ModalSettings& s) {
  modal.allow_only(
      {"dropper_shapes", "contact_flexibility", "modes", "participation", "droppers", "bars"});
  s.dropper_shapes = modal.get_bool("dropper_shapes", true);
  s.contact_flexibility = modal.get_bool("contact_flexibility", true);
  s.vertical_only = modal.get_choice("modes", {"all", "vertical"}, "all") == "vertical";
  s.participation = modal.get_positive("participation", s.participation);
  if (s.participation >= 1) modal.fail_key("participation", "must be below 1");
  s.dropper_check = modal.get_choice("droppers", {"bounded", "all"}, "bounded") == "all"
                        ? ModalSettings::DropperCheck::all
                        : ModalSettings::DropperCheck::bounded;
  s.bars = modal.get_choice("bars", {"slack", "exact"}, "slack") == "exact"
               ? ModalSettings::Bars::exact
               : ModalSettings::Bars::slack;
}

}  // namespace

void read_catenary_model(const InputNode& section, CatenaryScene& out) {
  out.fidelity_given = section.has("model");
  const std::string model = section.get_choice("model", {"nonlinear", "linear", "modal"}, "linear");
  out.fidelity = model == "nonlinear" ? CatenaryFidelity::nonlinear
                 : model == "modal"   ? CatenaryFidelity::modal
                                      : CatenaryFidelity::linear;
  const bool modal = out.fidelity == CatenaryFidelity::modal;
  for (const char* key : {"max_frequency_hz", "modal"})
    if (section.has(key) && !modal) section.fail_key(key, "only for model: modal");
  if (section.has("max_frequency_hz")) {
    out.modal_cutoff_given = true;
    const InputNode f = section["max_frequency_hz"];
    if (f.is_scalar() && f.as_string() == "all")
      out.modal.max_frequency_hz = 0;  // every mode
    else
      out.modal.max_frequency_hz = section.get_positive("max_frequency_hz");
  }
  if (section.has("modal")) read_modal_settings(section["modal"], out.modal);
}

CatenaryScene load_catenary_scene(const InputNode& scene) {
  check_scene_sections(scene);
  const InputNode section = scene["catenary"];
  section.allow_only({"design", "form_finding", "model", "max_frequency_hz", "modal"});
  CatenaryScene out;
  out.scene_file = scene.file();
  out.design_path = section.resolve_path(section.get_string("design"));
  if (!std::ifstream(out.design_path))
    section.fail_key("design", "cannot open catenary design file '" + out.design_path + "'");
  out.mesh = load_catenary_design(out.design_path);
  out.form_finding = section.get_bool("form_finding", out.mesh.form_finding_default);
  read_catenary_model(section, out);
  return out;
}

}  // namespace pcsim::catenary
