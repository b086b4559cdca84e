// Scene of a dynamic interaction run (`pcsim run`):
//
//   name: en50318-300
//   catenary: {design: ../meshes/en50318-reference.yaml}
//   pantographs:
//     - name: leading
//       model: ../meshes/pantographs/en50318_two_mass.yaml
//       start_x: 5.0            # contact point x at t = 0 [m] (default: 2nd dropper of span 1)
//       static_force: 120       # static contact force F0 [N] (default 120)
//       start: static|ramp      # default: static for the first, ramp for the others;
//                               # or {gap: 0.02}: at rest 2 cm below the wire
//       ramp_distance: 20       # [m] (default 20)
//       effects: {...}          # pantograph effects (see docs/pantograph.md)
//   simulation:
//     speed_kmh: 300
//     end_x: 590                # the run ends when the first pantograph reaches end_x
//     dt: 0.001                 # default time step [s] (-ts_dt overrides)
//   effects: {dropper_slack: true, rayleigh_damping: true}   # (catenary_nonlinear: the older
//                                                            #  key of catenary.model)
//   contact: {stiffness: 50000}
//   analysis: {from_span: 5, to_span: 6, cutoff_hz: 20}   # 1-based spans
//   output: {dropper_forces: true, snapshot_every: 0, energy: false, checkpoint_every: 0}
//   window: {spans_behind: 2, spans_ahead: 3}   # optional moving window (docs/scaling.md)
//   assessment: {criteria: en50367-ac, electrification: AC, line_speed_kmh: 300,
//                steady_arm_space_mm: 240}      # docs/assessment.md (default: see there)
//     snapshot_every: field snapshots every N steps (0: none)
//     energy: energy balance in energy.h5
//     checkpoint_every: checkpoint.h5 every N steps, for --restart (0: only when
//     the run stops early: SIGINT/SIGTERM, -ts_max_steps)
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "pcsim/contact/pantograph_run.hpp"
#include "pcsim/core/criteria.hpp"
#include "pcsim/pantograph/model.hpp"
#include "pcsim/scene/catenary_scene.hpp"

namespace pcsim::scene {

// A moving window over a line of identical spans (catenary/window.hpp): the
// run integrates spans_behind + train_spans + 2 + spans_ahead spans, the
// leading pantograph within the two spans after the train's (the window moves
// back by two spans, the period of the stagger, when it leaves them). One
// pantograph: train_spans 0. Several: the window spans the whole train, the
// trailing pantograph at least spans_behind spans from the rear.
struct RunWindow {
  int spans_behind = 2, spans_ahead = 3;
  int train_spans = 0;  // ceil(distance trailing -> leading pantograph / span_length)
  int spans() const { return spans_behind + train_spans + 2 + spans_ahead; }
  // Spans from the window's rear to where the leading pantograph shifts it.
  int shift_spans() const { return spans_behind + train_spans + 2; }
  // Shifts of two spans before the window's front reaches the line's end.
  int max_shifts() const { return (line_spans - spans()) / 2; }
  int line_spans = 0;                 // the line's (the scene's design's)
  double span_length = 0;             // [m]
  catenary::ParametricDesign design;  // the line's design, read
  catenary::CatenaryMesh mesh;        // the window's design: the line's with spans() spans
  std::string declined;               // method auto: why the line gets no window
};
// With a window, RunScene::catenary.mesh is the window's mesh with the line's
// supports (support_x: every span of the line while the scene is checked,
// then those the window covers before the run ends): the line itself is
// never built, and the checks, records and statistics see its stations.

struct RunScene {
  scene::CatenaryScene catenary;
  std::vector<contact::PantographRun> pantographs;
  std::vector<std::unique_ptr<pantograph::PantographModel>> models;  // one per pantograph
  double speed = 0;                                                  // [m/s]
  double end_x = 0;
  double dt = 1e-3;
  contact::InteractionEffects effects;
  double contact_stiffness = 50000;
  double analysis_from_x = 0, analysis_to_x = 0;
  int analysis_from_span = 0, analysis_to_span = 0;  // 1-based
  double cutoff_hz = 20;
  double loss_min_duration_s = 0;  // analysis.loss_min_duration_ms / 1000
  bool dropper_forces = true;
  double hht_alpha = 0.1;   // HHT numerical dissipation (simulation.hht_alpha; -ts_hht_alpha wins)
  bool energy = false;      // energy balance every step (energy.h5)
  long snapshot_every = 0;  // steps between field snapshots (XDMF animation); 0: none
  std::vector<InputWarning> warnings;  // allowed, but probably not meant (printed by the app)
  long checkpoint_every = 0;           // steps between checkpoints (restart); 0: none
  std::optional<RunWindow> window;     // 'window': only part of the line is integrated
  std::string modal_method_note;       // modal level: the method chosen and why
  Assessment assessment;  // 'assessment': the criteria set and its inputs (criteria_reader.hpp)
  // Duration of the run: from t = 0 until the first pantograph reaches end_x.
  double duration() const { return (end_x - pantographs.front().start_x) / speed; }
};

// What the reader needs from outside the scene to check it completely.
struct RunSceneOptions {
  scene::MeshSizeCheck size_check;        // sees the design's mesh size before it is built
  std::optional<double> command_line_dt;  // -ts_dt, already checked; replaces simulation.dt
};

// Reads and checks the whole scene: everything wrong is an InputError naming
// the file and key, found before any work (duplicate pantograph names, every
// pantograph's start and end on the contact wire, its static equilibrium at
// its working height, the filter's cut-off against the time step's Nyquist
// frequency, ...); pantographs closer than 10 m and more than 1e7 time steps
// are warnings.
RunScene load_run_scene(const InputNode& scene, const RunSceneOptions& options = {});

// Why 'name' cannot name a pantograph ("" if it can): it must be one HDF5
// link name (/pantographs/<name>): not empty, '.' or '..', no '/', no
// control characters.
std::string pantograph_name_problem(const std::string& name);

// The checks of load_run_scene that need every pantograph (names: valid and
// each once; positions along the line, spacing) and the time step
// (run_scene_checks.cpp).
void check_pantograph_names(const InputNode& scene, const RunScene& run);
void check_pantograph_positions(const InputNode& scene, RunScene& run);
void check_time_step(const InputNode& scene, RunScene& run, const std::string& dt_key);
// Warns when a pantograph starts or ends within the contact-force filter's
// transient length (3 / cutoff_hz of travel) of the analysis section
// (run_scene_edges.cpp).
void check_filter_edges(const InputNode& scene, RunScene& run);
// The 'window' section (run_window.cpp): its keys; the builder of the
// window's mesh from the line's design (a parametric line of identical spans,
// longer than the window; fills line_spans, span_length and design); and,
// once the scene is read, the window fitted to the train (several
// pantographs: its mesh rebuilt with train_spans, still shorter than the
// line) and that the pantographs and outputs allow a moving window.
// 'w': the 'window' section, whose keys errors name, or the catenary where
// catenary.modal.method: window asks for a window (errors name that key).
RunWindow read_window_keys(const InputNode& scene);
// Where a window over the scene's pantographs reaches: the train's spans,
// the window's spans with them, the leading pantograph's start and end
// stations and the limits the window puts on them (start below
// start_limit, end at most end_limit), its shifts.
struct WindowReach {
  int train_spans = 0, spans = 0;
  long shifts = 0;
  double lead_start = 0, start_limit = 0, lead_end = 0, end_limit = 0;
};
WindowReach window_reach(const RunScene& run, const RunWindow& window);
scene::DesignBuilder window_design_builder(const InputNode& w, RunWindow& window);
void check_window(const InputNode& scene, const InputNode& w, RunScene& run,
                  const scene::MeshSizeCheck& size_check);
// The modal level's choice of method (run_modal_method.cpp): a window where
// the scene has one or catenary.modal.method is window; with auto (the
// default) where the line is a parametric line of identical spans at least
// kAutoWindowFactor times as long as the window over the train, the
// pantographs start and end where a window allows and no output needs the
// whole line; else the whole line.
constexpr int kAutoWindowFactor = 2;
struct ModalMethodRequest {
  std::string method;  // "" (not modal), "auto", "whole", "window"
  bool automatic() const { return method == "auto"; }
};
ModalMethodRequest modal_method_request(const InputNode& scene);
scene::DesignBuilder auto_window_builder(RunWindow& window);
// After the scene is read: keeps the window if it fits (true) or rebuilds
// the whole line's mesh and drops it; 'why' says which and why.
bool keep_auto_window(const InputNode& scene, RunScene& run, const scene::MeshSizeCheck& size_check,
                      std::string& why);

// The FE levels integrate the whole line unless the scene has a 'window'
// section. On a parametric line of identical spans at least
// kWholeLineWarningFactor times as long as the window over the train, where
// a window would fit the run, that is probably not meant: a warning on the
// key 'window' says so (run_modal_method.cpp). Below that factor the whole
// line costs at most about that many windows and is the usual reference
// (the 40-span line against its 7-span window, docs/scaling.md).
constexpr int kWholeLineWarningFactor = 10;
// The line's facts (line_spans, span_length, design) where the design is such
// a line, without building a window: the line is built whole.
scene::DesignBuilder whole_line_probe(std::optional<RunWindow>& line);
void warn_whole_fe_line(const InputNode& scene, RunScene& run, RunWindow line);

}  // namespace pcsim::scene
