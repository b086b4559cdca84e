// The modal level's choice of method (run_scene.hpp, ModalMethodRequest):
// the whole line's basis or a moving window's.
#include <algorithm>
#include <cmath>

#include "pcsim/catenary/geometry.hpp"
#include "pcsim/catenary/reduced_basis.hpp"
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

namespace {

// Why a window does not fit the scene's train, run and outputs ("" if it does).
std::string window_misfit(const InputNode& scene, const RunScene& run, const RunWindow& window,
                          int factor = kAutoWindowFactor) {
  const WindowReach reach = window_reach(run, window);
  if (factor * reach.spans > window.line_spans)
    return "the line (" + std::to_string(window.line_spans) + " spans) is less than " +
           std::to_string(factor) + " x the window over the train (" + std::to_string(reach.spans) +
           " spans)";
  if (reach.lead_start >= reach.start_limit) return "a pantograph starts beyond the window";
  if (reach.lead_end > reach.end_limit) return "the run ends too near the line's end";
  if (scene.has("output")) {
    const InputNode o = scene["output"];
    if (o.get_int("snapshot_every", 0) > 0 || o.get_bool("energy", false) ||
        o.get_bool("dropper_forces", false))
      return "an output needs the whole line (snapshots, energy or dropper forces)";
  }
  return "";
}

}  // namespace

bool keep_auto_window(const InputNode& scene, RunScene& run, const scene::MeshSizeCheck& size_check,
                      std::string& why) {
  why = window_misfit(scene, run, *run.window);
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

void warn_whole_fe_line(const InputNode& scene, RunScene& run, RunWindow line) {
  if (!window_misfit(scene, run, line, kWholeLineWarningFactor).empty()) return;
  const WindowReach reach = window_reach(run, line);
  run.warnings.push_back(
      {scene.file(), "window",
       "the " + std::string(catenary::fidelity_name(run.catenary.fidelity)) +
           " catenary integrates the whole line, " + std::to_string(line.line_spans) +
           " identical spans (" + std::to_string(run.catenary.mesh.nodes.size()) +
           " nodes); a moving window would integrate " + std::to_string(reach.spans) +
           " of them: add 'window: {}' to the scene (docs/scene-format.md, 'window')"});
}

}  // namespace pcsim::scene
