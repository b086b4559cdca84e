// The modal level's choice of method (run_scene.hpp, ModalMethodRequest):
// the whole line's basis or a moving window's.
#include <algorithm>
#include <cmath>

#include "pcsim/catenary/geometry.hpp"
#include "pcsim/scene/design_reader.hpp"
#include "pcsim/scene/run_scene.hpp"

namespace pcsim::scene {

ModalMethodRequest modal_method_request(const InputNode& scene) {
  ModalMethodRequest r;
  if (!scene.has("catenary")) return r;
  const InputNode c = scene["catenary"];
  if (!c.has("model") || c["model"].as_string() != "modal") return r;
  r.method = "auto";
  if (c.has("modal") && c["modal"].is_map() && c["modal"].has("method"))
    r.method = c["modal"].get_choice("method", {"auto", "whole", "window"}, "auto");
  return r;
}

// A window over a parametric line of identical spans long enough for it
// (line_spans filled); any other line whole (line_spans 0: no window).
catenary::DesignBuilder auto_window_builder(RunWindow& window) {
  return [&window](const InputNode& design, const catenary::MeshSizeCheck& size_check) {
    window.line_spans = 0;
    window.declined = "not a parametric design";
    if (design.get_string("type", "") != "parametric")
      return catenary::build_catenary_design(design, size_check);
    catenary::ParametricDesign d = catenary::read_parametric_design(design);
    const bool identical = d.sections.empty() && !d.stitch_wire && d.support_overrides.empty() &&
                           d.irregularities.empty();
    window.declined =
        "not a line of identical spans (sections, stitch wire, support overrides "
        "or irregularities)";
    if (!identical) return catenary::build_catenary_design(design, size_check);
    window.declined = "the line (" + std::to_string(d.span_count) + " spans) is shorter than " +
                      std::to_string(kAutoWindowFactor) + " x a window (" +
                      std::to_string(window.spans()) + " spans)";
    if (d.span_count < kAutoWindowFactor * window.spans())
      return catenary::build_catenary_design(design, size_check);
    window.declined.clear();
    window.line_spans = static_cast<int>(d.span_count);
    window.span_length = d.span_length;
    window.design = d;
    d.span_count = window.spans();
    if (size_check) size_check(catenary::mesh_size(d));
    return catenary::build_parametric(d);
  };
}

namespace {

// Why a window does not fit the scene's train, run and outputs ("" if it does).
std::string window_misfit(const InputNode& scene, const RunScene& run) {
  RunWindow w = *run.window;
  const auto by_start = [](const auto& a, const auto& b) { return a.start_x < b.start_x; };
  const auto [lo, hi] =
      std::minmax_element(run.pantographs.begin(), run.pantographs.end(), by_start);
  w.train_spans = static_cast<int>(std::ceil((hi->start_x - lo->start_x) / w.span_length - 1e-9));
  if (kAutoWindowFactor * w.spans() > w.line_spans)
    return "the line (" + std::to_string(w.line_spans) + " spans) is less than " +
           std::to_string(kAutoWindowFactor) + " x the window over the train (" +
           std::to_string(w.spans()) + " spans)";
  const double L = w.span_length, x0 = run.catenary.mesh.support_x.front();
  if (hi->start_x >= x0 + w.shift_spans() * L) return "a pantograph starts beyond the window";
  const long shifts = (w.line_spans - w.spans()) / 2;
  const double lead_end = run.end_x + hi->start_x - run.pantographs.front().start_x;
  if (lead_end > x0 + 2.0 * L * shifts + w.shift_spans() * L)
    return "the run ends too near the line's end";
  if (scene.has("output")) {
    const InputNode o = scene["output"];
    if (o.get_int("snapshot_every", 0) > 0 || o.get_int("checkpoint_every", 0) > 0 ||
        o.get_bool("energy", false) || o.get_bool("dropper_forces", false))
      return "an output needs the whole line (snapshots, checkpoints, energy or dropper forces)";
  }
  return "";
}

}  // namespace

bool keep_auto_window(const InputNode& scene, RunScene& run,
                      const catenary::MeshSizeCheck& size_check, std::string& why) {
  why = window_misfit(scene, run);
  if (why.empty()) {
    check_window(scene, scene["catenary"], run, size_check);
    why = "a line of " + std::to_string(run.window->line_spans) + " identical spans, a window of " +
          std::to_string(run.window->spans());
    return true;
  }
  catenary::ParametricDesign d = run.window->design;
  if (size_check) size_check(catenary::mesh_size(d));
  catenary::CatenaryMesh mesh = catenary::build_parametric(d);
  mesh.source_file = run.catenary.mesh.source_file;
  run.catenary.mesh = std::move(mesh);
  run.window.reset();
  return false;
}

}  // namespace pcsim::scene
