// The set-up a dynamic run of a scene shares with the step-wise interface
// (run_setup.hpp).
#include "pcsim/simulation/run_setup.hpp"

#include "pcsim/catenary/window.hpp"
#include "pcsim/simulation/accuracy_estimate.hpp"
#include "pcsim/simulation/setup_memory.hpp"

namespace pcsim::simulation {

namespace {

// The window's mesh (static configuration) with its ends released
// (catenary/window.hpp), on the console.
void prepare_window(const Context& ctx, const scene::RunWindow& window,
                    simulation::StaticConfiguration& statics) {
  const auto ends = catenary::release_window_ends(statics.mesh, statics.result.node_values);
  print0(ctx,
         "  moving window: %d of the line's %d spans (%d behind, %d with the %s, %d ahead), "
         "%zu wire ends with matched dashpots\n",
         window.spans(), window.line_spans, window.spans_behind, window.train_spans + 2,
         window.train_spans > 0 ? "train" : "pantograph", window.spans_ahead, ends.size());
}

// The static configuration of the line, or of the window with its ends released.
simulation::StaticConfiguration run_statics(const Context& ctx, const scene::RunScene& run,
                                            bool& kept) {
  auto statics = kept_static_configuration(ctx, run.catenary.design_path,
                                           run.window ? run.window->mesh : run.catenary.mesh,
                                           run.catenary.form_finding, kept);
  if (run.window) prepare_window(ctx, *run.window, statics);
  print0(ctx, "  static: %d Newton iterations, height error %.2e m, tension error %.2e%s\n",
         statics.result.snes_iterations, statics.result.max_height_error_m,
         statics.result.max_tension_error_rel, kept ? " (kept in memory from an earlier run)" : "");
  const std::string conditions = simulation::conditions_summary(statics);
  if (!conditions.empty()) print0(ctx, "  %s\n", conditions.c_str());
  print_warnings(ctx, statics.result.warnings);
  return statics;
}

}  // namespace

RunSetup set_up_run(const Context& ctx, scene::RunScene& scene, LogStage* stage) {
  RunSetup s;
  s.statics = run_statics(ctx, scene, s.statics_kept);
  if (stage) stage->next("Static start");
  s.system = make_coupled_system(ctx, scene, s.statics, s.catenary);
  print_catenary_setup(ctx, scene, s.catenary);
  return s;
}

std::unique_ptr<solvers::DynamicSolver> make_run_solver(const scene::RunScene& scene,
                                                        assembly::CoupledSystem& system) {
  return std::make_unique<solvers::DynamicSolver>(system, scene.dt, scene.duration(),
                                                  scene.hht_alpha);
}

}  // namespace pcsim::simulation
