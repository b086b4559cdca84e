#include "pcsim/scene/run_scene.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "pcsim/core/format.hpp"
#include "pcsim/scene/criteria_reader.hpp"
#include "pcsim/scene/pantograph_reader.hpp"
#include "pcsim/scene/time_signal.hpp"

namespace pcsim::scene {

namespace {

// analysis.loss_min_duration_ms: at most a second (the arcing figures count
// interruptions of a few ms).
constexpr Limit kLossDuration{1000, "ms"};

void read_simulation(const InputNode& scene, RunScene& run, std::optional<double> dt) {
  const auto& mesh = run.catenary.mesh;
  const InputNode sim = scene["simulation"];
  sim.allow_only({"speed_kmh", "end_x", "dt", "hht_alpha"});
  run.speed = sim.get_positive("speed_kmh", limits::speed_kmh) / 3.6;
  const double c = catenary::wave_speed(mesh.wires[mesh.contact_wire]);
  if (run.speed >= c)
    sim.fail_key(
        "speed_kmh",
        "speed " + format_number(run.speed * 3.6) +
            " km/h is not below the contact wire's wave speed sqrt(T (1 + T/EA) / rho) = " +
            format_number(c * 3.6) + " km/h");
  run.dt = sim.get_positive("dt", limits::time_step, 1e-3);
  if (dt) run.dt = *dt;
  run.hht_alpha = sim.get_nonnegative("hht_alpha", 0.1);
  if (run.hht_alpha > 1.0 / 3.0)
    sim.fail_key("hht_alpha",
                 "must lie in [0, 1/3] (HHT-alpha stability), got " + format_number(run.hht_alpha));
  const double x_first = mesh.support_x.front(), x_last = mesh.support_x.back();
  run.end_x = sim.get_double("end_x", x_last - 5.0);
  if (run.end_x <= x_first || run.end_x > x_last)
    sim.fail_key("end_x", "must lie on the line (" + format_number(x_first) + ", " +
                              format_number(x_last) + "] m");
}

// The mean cross-wind's lateral force on a pantograph, F_y = rho CdA V_y |V_y| / 2
// (the wind's component across the track: the cross-flow principle, as the
// wires' drag), and the head's quasi-static lateral deflection F_y / k_y.
void read_cross_wind(const InputNode& p, const catenary::WindLoad& wind,
                     contact::PantographRun& pr) {
  if (!p.has("cross_wind")) return;
  const InputNode c = p["cross_wind"];
  c.allow_only({"drag_area", "lateral_stiffness"});
  const double drag_area = c.get_positive("drag_area", limits::drag_area);
  const double stiffness = c.get_positive("lateral_stiffness", limits::stiffness);
  const double across = wind.velocity().y();
  pr.cross_wind = true;
  pr.cross_wind_force = 0.5 * wind.air_density * drag_area * across * std::abs(across);
  pr.head_lateral_offset = pr.cross_wind_force / stiffness;
}

// Entry i of the scene's pantographs: how it travels and starts, and its model.
void read_pantograph(const InputNode& p, std::size_t i, RunScene& run) {
  p.allow_only({"name", "model", "start_x", "static_force", "start", "ramp_distance",
                "working_height", "effects", "base_motion", "cross_wind"});
  const double x_first = run.catenary.mesh.support_x.front();
  contact::PantographRun pr;
  pr.name = p.get_string("name", "pantograph" + std::to_string(i + 1));
  const InputNode effects = p.has("effects") ? p["effects"] : InputNode(YAML::Node(), p.file(), "");
  // The aerodynamic force's air speed: the train's plus a head wind (the
  // mean wind's component against the x axis; docs/conditions.md).
  const double air_speed = run.speed - run.catenary.mesh.conditions.wind.velocity().x();
  auto model = load_pantograph_model(p.load_referenced("model"),
                                     p.has("effects") ? &effects : nullptr, air_speed);
  apply_base_motion(p, *model);
  read_cross_wind(p, run.catenary.mesh.conditions.wind, pr);
  pr.start_x = p.get_double("start_x", x_first + 5.0);
  if (pr.start_x < x_first || pr.start_x >= run.end_x)
    p.fail_key("start_x", "must lie on the line before simulation.end_x (" +
                              format_number(run.end_x) + " m), got " + format_number(pr.start_x));
  pr.static_force = p.get_positive("static_force", limits::force, 120.0);
  pr.speed = run.speed;
  if (p.has("start") && p["start"].is_map()) {
    // start: {gap: g}: at rest g below the wire, full uplift, no contact force.
    const InputNode start = p["start"];
    start.allow_only({"gap"});
    pr.start_gap = start.get_positive("gap");
    if (pr.start_gap > 0.5)
      start.fail_key("gap", "must be at most 0.5 m (a pantograph that starts " +
                                format_number(pr.start_gap) + " m below the wire)");
  } else {
    const std::string start = p.get_choice("start", {"static", "ramp"}, i == 0 ? "static" : "ramp");
    pr.static_start = start == "static";
  }
  pr.ramp_distance = p.get_positive("ramp_distance", limits::distance, 20.0);
  // The model states its default: a height above its base, or 0 (absolute heights).
  pr.working_height =
      p.get_positive("working_height", limits::pantograph_length, model->default_working_height());
  if (pr.working_height > 0)  // else the head meets the wire wherever it is (lumped models)
    check_working_height(p, *model, pr.static_force, pr.working_height, p.has("working_height"));
  run.pantographs.push_back(std::move(pr));
  run.models.push_back(std::move(model));
}

void read_analysis(const InputNode& scene, RunScene& run) {
  const auto& mesh = run.catenary.mesh;
  const int n_spans = static_cast<int>(mesh.support_x.size()) - 1;
  run.analysis_from_span = std::min(5, n_spans);
  run.analysis_to_span = std::min(6, n_spans);
  if (scene.has("analysis")) {
    const InputNode a = scene["analysis"];
    a.allow_only({"from_span", "to_span", "cutoff_hz", "loss_min_duration_ms"});
    run.analysis_from_span = static_cast<int>(a.get_int("from_span", run.analysis_from_span));
    run.analysis_to_span = static_cast<int>(a.get_int("to_span", run.analysis_to_span));
    if (run.analysis_from_span < 1 || run.analysis_to_span > n_spans ||
        run.analysis_from_span > run.analysis_to_span)
      a.fail("spans must satisfy 1 <= from_span <= to_span <= " + std::to_string(n_spans));
    run.cutoff_hz = a.get_positive("cutoff_hz", limits::frequency, 20.0);
    run.loss_min_duration_s = 1e-3 * a.get_nonnegative("loss_min_duration_ms", kLossDuration, 0.0);
  }
  run.analysis_from_x = mesh.support_x[run.analysis_from_span - 1];
  run.analysis_to_x = mesh.support_x[run.analysis_to_span];
  // Every pantograph must cross the whole analysis section during the run.
  const InputNode list = scene["pantographs"];
  for (std::size_t i = 0; i < run.pantographs.size(); ++i) {
    const auto& p = run.pantographs[i];
    const double x_end = p.start_x + (run.end_x - run.pantographs.front().start_x);
    if (p.start_x > run.analysis_from_x || x_end < run.analysis_to_x)
      list.at(i).fail_key("start_x", "pantograph '" + p.name + "' runs from " +
                                         format_number(p.start_x) + " to " + format_number(x_end) +
                                         " m and does not cross the whole analysis section (" +
                                         format_number(run.analysis_from_x) + ", " +
                                         format_number(run.analysis_to_x) + ") m");
  }
}

void read_effects_and_output(const InputNode& scene, RunScene& run) {
  if (scene.has("effects")) {
    const InputNode e = scene["effects"];
    e.allow_only({"catenary_nonlinear", "dropper_slack", "rayleigh_damping"});
    if (e.has("catenary_nonlinear")) {  // the old key of catenary.model
      // With catenary.model too (a scene composed on one that has this key),
      // the two must agree: false goes with linear and modal.
      const bool nonlinear = e.get_bool("catenary_nonlinear", false);
      const bool model_nonlinear = run.catenary.fidelity == catenary::CatenaryFidelity::nonlinear;
      if (run.catenary.fidelity_given && nonlinear != model_nonlinear)
        e.fail_key("catenary_nonlinear",
                   std::string("contradicts catenary.model: ") +
                       catenary::fidelity_name(run.catenary.fidelity) +
                       " (the catenary's fidelity; give it once, as catenary.model)");
      if (!run.catenary.fidelity_given)
        run.catenary.fidelity =
            nonlinear ? catenary::CatenaryFidelity::nonlinear : catenary::CatenaryFidelity::linear;
    }
    run.effects.dropper_slack = e.get_bool("dropper_slack", true);
    run.effects.rayleigh_damping = e.get_bool("rayleigh_damping", true);
  }
  if (scene.has("contact")) {
    const InputNode c = scene["contact"];
    c.allow_only({"stiffness"});
    run.contact_stiffness = c.get_positive("stiffness", limits::stiffness, 50000.0);
  }
  if (scene.has("output")) {
    const InputNode o = scene["output"];
    o.allow_only({"dropper_forces", "snapshot_every", "energy", "checkpoint_every"});
    run.dropper_forces = o.get_bool("dropper_forces", true);
    run.snapshot_every = o.get_int("snapshot_every", 0);
    run.energy = o.get_bool("energy", false);
    if (run.snapshot_every < 0)
      o.fail_key("snapshot_every", "must be 0 (none) or a number of steps");
    run.checkpoint_every = o.get_int("checkpoint_every", 0);
    if (run.checkpoint_every < 0)
      o.fail_key("checkpoint_every", "must be 0 (none) or a number of steps");
  }
}

// The moving window a scene asks for: its 'window' section, or the modal
// level's method (window, or auto on a long line of identical spans).
struct WindowChoice {
  ModalMethodRequest method;
  bool automatic = false;               // auto chose a window; it may still be dropped
  std::string declined;                 // auto: why the line got none
  std::optional<RunWindow> whole_line;  // an FE level's line a window could serve
};

// The catenary section, and the window's mesh with the line's supports.
WindowChoice load_catenary_and_window(const InputNode& scene, const RunSceneOptions& options,
                                      RunScene& run) {
  WindowChoice choice;
  choice.method = modal_method_request(scene);
  std::optional<RunWindow> window;
  if (scene.has("window")) {
    if (choice.method.method == "whole")
      scene["catenary"]["modal"].fail_key(
          "method", "whole cannot be combined with a moving window (section 'window')");
    window = read_window_keys(scene);
  } else if (choice.method.method == "window" || choice.method.automatic()) {
    window = RunWindow{};
  }
  const bool turbulent = scene.has("conditions") && scene["conditions"].has("wind") &&
                         scene["conditions"]["wind"].has("turbulence");
  if (turbulent && window && !scene.has("window") && choice.method.automatic()) {
    choice.declined =
        "under turbulent wind (a window does not feel the wind outside it; give 'window:')";
    window.reset();
  }
  choice.automatic = window && !scene.has("window") && choice.method.automatic();
  const InputNode where = scene.has("window") ? scene["window"] : scene["catenary"];
  scene::DesignBuilder builder;
  if (window)
    builder =
        choice.automatic ? auto_window_builder(*window) : window_design_builder(where, *window);
  else if (choice.method.method.empty())  // an FE level: the whole line (a warning may say so)
    builder = whole_line_probe(choice.whole_line);
  run.catenary = scene::load_catenary_scene(scene, options.size_check, builder);
  if (window && window->line_spans == 0) {  // auto: the line is no window's
    choice.declined = window->declined;
    window.reset();
  }
  if (window) {  // the window's mesh; the line's supports for everything else
    window->mesh = run.catenary.mesh;
    auto& support_x = run.catenary.mesh.support_x;
    const double x0 = support_x.front();
    support_x.resize(static_cast<std::size_t>(window->line_spans) + 1);
    for (std::size_t k = 0; k < support_x.size(); ++k) support_x[k] = x0 + k * window->span_length;
    run.window = std::move(window);
  }
  return choice;
}

// Once the scene is read: the window fitted and checked (auto: kept or
// dropped), the modal method and the note that says it.
void settle_window(const InputNode& scene, const RunSceneOptions& options,
                   const WindowChoice& choice, RunScene& run) {
  const auto& method = choice.method;
  if (run.window && choice.automatic) {
    std::string why;
    const bool kept = keep_auto_window(scene, run, options.size_check, why);
    run.modal_method_note = kept ? "window (auto: " + why + ")" : "whole (auto: " + why + ")";
  } else if (run.window) {
    const InputNode where = scene.has("window") ? scene["window"] : scene["catenary"];
    check_window(scene, where, run, options.size_check);
    if (!method.method.empty())  // the modal level's (an FE level has no method to say)
      run.modal_method_note = scene.has("window") ? "window (the scene's 'window')" : "window";
  } else if (!method.method.empty()) {
    run.modal_method_note = method.automatic() ? "whole (auto: " + choice.declined + ")" : "whole";
  }
  if (!method.method.empty())
    run.catenary.modal.method = run.window ? catenary::ModalSettings::Method::window
                                           : catenary::ModalSettings::Method::whole;
  if (choice.whole_line && !run.window) warn_whole_fe_line(scene, run, *choice.whole_line);
}

}  // namespace

RunScene load_run_scene(const InputNode& scene, const RunSceneOptions& options) {
  RunScene run;
  const WindowChoice window = load_catenary_and_window(scene, options, run);
  const auto& mesh = run.catenary.mesh;
  if (mesh.contact_wire < 0 || mesh.support_x.size() < 2)
    scene["catenary"].fail_key(
        "design", "a dynamic run needs a parametric design (contact wire and supports)");
  read_simulation(scene, run, options.command_line_dt);
  const InputNode list = scene["pantographs"];
  if (!list.is_sequence() || list.size() == 0) list.fail("must be a non-empty list of pantographs");
  for (std::size_t i = 0; i < list.size(); ++i) read_pantograph(list.at(i), i, run);
  check_pantograph_names(scene, run);
  check_pantograph_positions(scene, run);
  read_effects_and_output(scene, run);
  read_analysis(scene, run);
  // Default modal cut-off: the modes the contact force shows below the filter
  // cut-off, cutoff_hz / (1 - v/c) (docs/fidelity.md).
  if (!run.catenary.modal_cutoff_given) {
    const double c = catenary::wave_speed(mesh.wires[mesh.contact_wire]);
    run.catenary.modal.max_frequency_hz =
        catenary::kModalCutoffMargin * catenary::doppler_frequency(run.cutoff_hz, run.speed, c);
  }
  check_time_step(scene, run, options.command_line_dt ? "-ts_dt" : "simulation.dt");
  check_filter_edges(scene, run);
  settle_window(scene, options, window, run);
  read_assessment(scene, run);
  return run;
}

}  // namespace pcsim::scene
