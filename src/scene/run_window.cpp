// The 'window' section of a run scene (run_scene.hpp, RunWindow).
#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>

#include "pcsim/catenary/geometry.hpp"
#include "pcsim/core/format.hpp"
#include "pcsim/scene/design_reader.hpp"
#include "pcsim/scene/run_scene.hpp"

namespace pcsim::scene {

namespace {

// An error of the window's fit: on the key of the 'window' section (or on
// the section); where catenary.modal.method: window asks for a window (w is
// the catenary), on that key, with the margins it takes.
[[noreturn]] void fail_window(const InputNode& w, const std::string& key, const std::string& reason,
                              bool margins = true) {
  const RunWindow defaults;
  const std::string said =
      margins ? " (its default margins: " + std::to_string(defaults.spans_behind) +
                    " spans behind the train, " + std::to_string(defaults.spans_ahead) +
                    " ahead; a 'window' section sets them)"
              : "";
  if (w.path() != "window" && w.has("modal") && w["modal"].is_map() && w["modal"].has("method"))
    w["modal"].fail_key("method", "window: " + reason + said);
  if (key.empty()) w.fail(reason);
  w.fail_key(key, reason);
}

// The line must repeat every two spans: one straight section of identical
// spans (catenary::spans_differ; a stitch wire is at every support but the
// line's ends, as it is at the window's inner supports).
void check_periodic_line(const InputNode& w, const catenary::ParametricDesign& d) {
  const std::string why = catenary::spans_differ(d);
  if (!why.empty())
    fail_window(w, "", "needs a line of identical spans; the design has " + why, false);
}

bool starts_before(const contact::PantographRun& a, const contact::PantographRun& b) {
  return a.start_x < b.start_x;
}

// The window (margins and train) must be shorter than the line: it moves along it.
void check_shorter_than_line(const InputNode& w, const RunWindow& window) {
  if (window.spans() < window.line_spans) return;
  const std::string train = window.train_spans == 0
                                ? ""
                                : " + " + std::to_string(window.train_spans) +
                                      " spans of the train (trailing to leading pantograph)";
  fail_window(w, "",
              "a window of " + std::to_string(window.spans()) + " spans (spans_behind" + train +
                  " + 2 + spans_ahead) is not shorter than the line (" +
                  std::to_string(window.line_spans) + " spans)");
}

// Several pantographs: the window spans the train (train_spans), its mesh
// rebuilt from the line's design with that many more spans.
void fit_train(const InputNode& w, RunScene& run, const scene::MeshSizeCheck& size_check) {
  auto& window = *run.window;
  window.train_spans = window_reach(run, window).train_spans;
  if (window.train_spans == 0) return;
  check_shorter_than_line(w, window);
  catenary::ParametricDesign d = window.design;
  d.span_count = window.spans();
  if (size_check) size_check(catenary::mesh_size(d));
  catenary::CatenaryMesh mesh = catenary::build_parametric(d);
  mesh.source_file = run.catenary.mesh.source_file;
  mesh.conditions = run.catenary.mesh.conditions;
  window.mesh = mesh;
  mesh.support_x = std::move(run.catenary.mesh.support_x);  // the line's
  run.catenary.mesh = std::move(mesh);
}

void check_outputs(const InputNode& scene) {
  if (!scene.has("output")) return;
  const InputNode o = scene["output"];
  if (o.get_int("snapshot_every", 0) > 0)
    o.fail_key("snapshot_every", "not available with a moving window (its state is the window's)");
  if (o.get_bool("energy", false))
    o.fail_key("energy", "not available with a moving window (energy leaves through its ends)");
  if (o.get_bool("dropper_forces", false))
    o.fail_key("dropper_forces", "not available with a moving window (its droppers move)");
}

}  // namespace

RunWindow read_window_keys(const InputNode& scene) {
  const InputNode w = scene["window"];
  w.allow_only({"spans_behind", "spans_ahead"});
  RunWindow window;
  window.spans_behind = static_cast<int>(w.get_int("spans_behind", 2));
  window.spans_ahead = static_cast<int>(w.get_int("spans_ahead", 3));
  if (window.spans_behind < 1) w.fail_key("spans_behind", "must be at least 1 span");
  if (window.spans_ahead < 1) w.fail_key("spans_ahead", "must be at least 1 span");
  return window;
}

namespace {

// The line's facts a window over design d keeps.
void keep_line(RunWindow& window, const catenary::ParametricDesign& d) {
  window.line_spans = static_cast<int>(d.span_count);
  window.span_length = d.span_length;
  window.design = d;
}

// The window over the line of design d: the line's facts kept, the mesh of
// spans() spans built (only that is checked against the memory).
catenary::CatenaryMesh build_window(RunWindow& window, catenary::ParametricDesign d,
                                    const scene::MeshSizeCheck& size_check) {
  keep_line(window, d);
  d.span_count = window.spans();
  if (size_check) size_check(catenary::mesh_size(d));
  return catenary::build_parametric(d);
}

}  // namespace

// The line's design read as it is; the window's mesh built from it.
scene::DesignBuilder window_design_builder(const InputNode& w, RunWindow& window) {
  return [w, &window](const InputNode& design, const scene::MeshSizeCheck& size_check) {
    if (design.get_string("type", "") != "parametric")
      fail_window(w, "", "needs a parametric design", false);
    catenary::ParametricDesign d = scene::read_parametric_design(design);
    check_periodic_line(w, d);
    RunWindow line = window;
    line.line_spans = static_cast<int>(d.span_count);
    check_shorter_than_line(w, line);
    return build_window(window, d, size_check);
  };
}

namespace {

// The design when it is a parametric line of identical spans; else none, and
// 'why' says why not.
std::optional<catenary::ParametricDesign> identical_spans_line(const InputNode& design,
                                                               std::string& why) {
  why = "not a parametric design";
  if (design.get_string("type", "") != "parametric") return std::nullopt;
  catenary::ParametricDesign d = scene::read_parametric_design(design);
  const std::string differ = catenary::spans_differ(d);
  why = "not a line of identical spans (the design has " + differ + ")";
  if (!differ.empty()) return std::nullopt;
  why.clear();
  return d;
}

}  // namespace

// A window over a parametric line of identical spans long enough for it
// (line_spans filled); any other line whole (line_spans 0, 'declined' says why).
scene::DesignBuilder auto_window_builder(RunWindow& window) {
  return [&window](const InputNode& design, const scene::MeshSizeCheck& size_check) {
    window.line_spans = 0;
    const auto d = identical_spans_line(design, window.declined);
    if (!d) return scene::build_catenary_design(design, size_check);
    window.declined = "the line (" + std::to_string(d->span_count) + " spans) is shorter than " +
                      std::to_string(kAutoWindowFactor) + " x a window (" +
                      std::to_string(window.spans()) + " spans)";
    if (d->span_count < kAutoWindowFactor * window.spans())
      return scene::build_catenary_design(design, size_check);
    window.declined.clear();
    return build_window(window, *d, size_check);
  };
}

scene::DesignBuilder whole_line_probe(std::optional<RunWindow>& line) {
  return [&line](const InputNode& design, const scene::MeshSizeCheck& size_check) {
    line.reset();
    std::string why;
    if (const auto d = identical_spans_line(design, why)) {
      line = RunWindow{};
      keep_line(*line, *d);
    }
    return scene::build_catenary_design(design, size_check);
  };
}

WindowReach window_reach(const RunScene& run, const RunWindow& window) {
  WindowReach r;
  const auto [lo, hi] =
      std::minmax_element(run.pantographs.begin(), run.pantographs.end(), starts_before);
  r.train_spans =
      static_cast<int>(std::ceil((hi->start_x - lo->start_x) / window.span_length - 1e-9));
  RunWindow fitted = window;
  fitted.train_spans = r.train_spans;
  r.spans = fitted.spans();
  const double L = window.span_length, x0 = run.catenary.mesh.support_x.front();
  r.lead_start = hi->start_x;
  r.start_limit = x0 + fitted.shift_spans() * L;
  // The window moves by two spans while its front stays on the line.
  r.shifts = (window.line_spans - fitted.spans()) / 2;
  r.lead_end = run.end_x + hi->start_x - run.pantographs.front().start_x;
  r.end_limit = x0 + 2.0 * L * r.shifts + fitted.shift_spans() * L;
  return r;
}

// The leading pantograph (the furthest along) starts within the window's
// first shift_spans() spans and ends, when the first of the scene's reaches
// end_x, before the window's front has reached the line's end.
void check_window(const InputNode& scene, const InputNode& w, RunScene& run,
                  const scene::MeshSizeCheck& size_check) {
  auto& window = *run.window;
  fit_train(w, run, size_check);
  check_outputs(scene);
  const WindowReach reach = window_reach(run, window);
  const std::string who = run.pantographs.size() > 1 ? "the leading pantograph" : "the pantograph";
  if (reach.lead_start >= reach.start_limit)
    fail_window(w, "spans_behind",
                who + " starts at " + format_number(reach.lead_start) +
                    " m, beyond the window's first " + std::to_string(window.shift_spans()) +
                    " spans");
  if (reach.lead_end > reach.end_limit)
    fail_window(
        w, "spans_ahead",
        "the window's front reaches the line's end before " + who + " reaches " +
            format_number(reach.lead_end) + " m, where it is when the run ends (simulation.end_x " +
            format_number(run.end_x) + " m; at most " + format_number(reach.end_limit) + " m)");
  // The line as far as the run goes: the supports the window covers before
  // the leading pantograph's end (the records and statistics need no others).
  const double L = window.span_length, x0 = run.catenary.mesh.support_x.front();
  long used = 0;
  while (used < reach.shifts &&
         x0 + (window.shift_spans() + 2.0 * used) * L <= reach.lead_end + 1e-9)
    ++used;
  run.catenary.mesh.support_x.resize(static_cast<std::size_t>(window.spans() + 2 * used + 1));
  run.dropper_forces = false;
}

}  // namespace pcsim::scene
