// `pcsim run SCENE.yaml [--restart DIR]`: dynamic pantograph-catenary interaction.
//   scene -> static configuration -> coupled system -> initial state (or a
//   checkpoint) -> TS, results streamed to results.h5 -> statistics
#include <petscts.h>

#include <algorithm>
#include <filesystem>

#include "accuracy_estimate.hpp"
#include "catenary_setup.hpp"
#include "command.hpp"
#include "exit_status.hpp"
#include "inputs.hpp"
#include "pcsim/assembly/coupled_system.hpp"
#include "pcsim/assembly/fe_catenary.hpp"
#include "pcsim/catenary/window.hpp"
#include "pcsim/core/profiling.hpp"
#include "pcsim/output/checkpoint.hpp"
#include "pcsim/output/en50318.hpp"
#include "pcsim/output/energy_results.hpp"
#include "pcsim/output/line_results.hpp"
#include "pcsim/output/output_dir.hpp"
#include "pcsim/output/run_results.hpp"
#include "pcsim/output/run_stream.hpp"
#include "pcsim/scene/run_scene.hpp"
#include "pcsim/solvers/direct.hpp"
#include "pcsim/solvers/dynamics.hpp"
#include "pcsim/solvers/hht.hpp"
#include "pcsim/solvers/schur_dd.hpp"
#include "pcsim/solvers/static_start.hpp"
#include "pcsim/solvers/statics.hpp"
#include "processes.hpp"
#include "run_checkpoint.hpp"
#include "run_session.hpp"
#include "run_settings.hpp"

namespace {

using namespace pcsim;

// Starts the TS from the initial state (solvers::initial_state) and destroys it.
void set_initial_state(solvers::DynamicSolver& solver, Vec U0, Vec V0) {
  solver.set_initial_state(U0, V0);
  PCSIM_PETSC(VecDestroy(&U0));
  PCSIM_PETSC(VecDestroy(&V0));
}

void warn_if_start_differs(const app::CommandContext& ctx, assembly::CoupledSystem& system,
                           const solvers::DynamicState& checkpointed) {
  const auto& slots = system.pantographs();
  for (std::size_t p = 0; p < slots.size() && p < checkpointed.head_offsets.size(); ++p)
    if (slots[p].head_offset != checkpointed.head_offsets[p])
      app::print0(ctx,
                  "  warning: pantograph '%s' starts %.3g m from where the checkpointed run "
                  "started it; the restart will not equal an uninterrupted run\n",
                  slots[p].run.name.c_str(), slots[p].head_offset - checkpointed.head_offsets[p]);
}

// The EN 50318 table of one pantograph: figure, unit, value, and the range
// and verdict where the standard gives ranges at this speed.
void print_en50318_table(const app::CommandContext& ctx,
                         const std::vector<output::AssessedFigure>& figures) {
  const bool ranges = !figures.empty() && figures.front().has_range;
  app::print0(ctx, "    %-32s %-4s %9s%s\n", "figure", "unit", "value",
              ranges ? "         range    verdict" : "");
  int inside = 0;
  for (const auto& a : figures) {
    char range[64] = "", bounds[40];
    std::snprintf(bounds, sizeof bounds, "%g .. %g", a.range.low, a.range.high);
    if (a.has_range)
      std::snprintf(range, sizeof range, "  %12s    %s", bounds, a.inside ? "pass" : "FAIL");
    app::print0(ctx, "    %-32s %-4s %9.2f%s\n", a.figure.label.c_str(), a.figure.unit.c_str(),
                a.value, range);
    inside += a.inside;
  }
  if (ranges) app::print0(ctx, "    %d of %zu figures inside the ranges\n", inside, figures.size());
}

// The EN 50318 figures of every pantograph; their json for summary.json.
nlohmann::json print_statistics(const app::CommandContext& ctx, const output::RunSettings& s,
                                const output::RunStatistics& stats) {
  const auto& reference = output::en50318_reference();
  const double speed_kmh = s.speed * 3.6;
  app::print0(ctx,
              "\n  EN 50318 figures (contact force low-pass %.0f Hz, spans %d-%d, %.0f km/h)\n",
              s.cutoff_hz, s.analysis_from_span, s.analysis_to_span, speed_kmh);
  if (reference.ranges_at(speed_kmh))
    app::print0(ctx, "  acceptance ranges of %s at %.0f km/h\n", reference.edition.c_str(),
                speed_kmh);
  else
    app::print0(ctx, "  %s gives acceptance ranges at %s only: values without verdict\n",
                reference.edition.c_str(), reference.speeds_with_ranges().c_str());
  const nlohmann::json run = {{"max_uplift_at_support_m", stats.max_uplift_m}};
  nlohmann::json assessed = nlohmann::json::object();
  for (const auto& p : stats.pantographs) {
    if (!p.complete) {
      app::print0(ctx, "  %-12s did not cross the analysis section: no statistics\n",
                  p.name.c_str());
      continue;
    }
    const auto figures =
        output::assess_en50318(run, output::force_statistics_json(p.force), speed_kmh);
    app::print0(ctx, "  pantograph '%s'\n", p.name.c_str());
    print_en50318_table(ctx, figures);
    assessed[p.name] = output::en50318_json(figures, speed_kmh);
  }
  return assessed;
}

// A line of several tension sections: statistics over each section and
// overlap, forces on each contact wire (output/line_results.hpp); printed,
// and returned for summary.json (null for a single section).
// The histories come from results.h5 (run_layout keeps the wire forces).
nlohmann::json line_results(const app::CommandContext& ctx, const OutputDir& out,
                            const catenary::CatenaryMesh& mesh, const output::RunSettings& s) {
  if (mesh.zones.size() < 2) return nullptr;
  const auto histories = output::read_contact_histories(out, s);
  const auto json = output::write_line_results(out, mesh, histories, s.cutoff_hz);
  for (const auto& p : json)
    for (const auto& z : p["zones"]) {
      if (!z["complete"].get<bool>()) continue;
      app::print0(ctx,
                  "  %-12s %-12s mean %7.2f N  std %6.2f N  max %7.2f  min %7.2f  loss %.2f%%\n",
                  p["name"].get<std::string>().c_str(), z["name"].get<std::string>().c_str(),
                  z["mean_N"].get<double>(), z["std_N"].get<double>(), z["max_N"].get<double>(),
                  z["min_N"].get<double>(), z["loss_of_contact_percent"].get<double>());
    }
  return json;
}

// energy.h5 and the balance on the console (output.energy), from the
// energy streamed into results.h5.
nlohmann::json energy_results(const app::CommandContext& ctx, const OutputDir& out) {
  const auto history = output::read_energy_history(out);
  const auto balance = output::energy_balance(history);
  app::print0(ctx,
              "  energy: W_ext %.4g J, W_diss %.4g J, E - E0 %.4g J; balance residual max %.3g J "
              "(%.2g of the turnover %.4g J)\n",
              balance.work_external.empty() ? 0.0 : balance.work_external.back(),
              balance.work_dissipated.empty() ? 0.0 : balance.work_dissipated.back(),
              balance.change.empty() ? 0.0 : balance.change.back(), balance.max_residual,
              balance.turnover > 0 ? balance.max_residual / balance.turnover : 0.0,
              balance.turnover);
  return output::write_energy_results(out.file("energy.h5"), history, balance);
}

output::RunLayout run_layout(const scene::RunScene& run, assembly::CoupledSystem& system,
                             const solvers::StaticConfiguration& statics) {
  const auto& mesh = statics.mesh;
  const auto& values = statics.result.node_values;
  output::RunLayout layout;
  for (const auto& slot : system.pantographs()) {
    layout.q_sizes.push_back(slot.dof_count());
    layout.q_labels.push_back(slot.model->dof_names());
  }
  layout.support_x = mesh.support_x;
  for (int node : mesh.support_nodes) layout.support_static_z.push_back(values[6 * node + 2]);
  if (run.dropper_forces)
    layout.droppers = static_cast<std::size_t>(
        std::count_if(mesh.bars.begin(), mesh.bars.end(),
                      [](const auto& b) { return b.kind == catenary::BarKind::dropper; }));
  if (mesh.zones.size() >= 2) layout.contact_wires = mesh.contact_wire_list().size();
  layout.energy = run.energy;
  layout.snapshots = run.snapshot_every > 0;
  if (layout.snapshots) layout.static_positions = catenary::positions_from_node_values(values);
  return layout;
}

// results.h5 on rank 0: new, or a copy of the restart folder's records up to
// its checkpoint; the static mesh for the snapshots.
std::unique_ptr<output::RunStream> open_stream(const app::CommandContext& ctx, const OutputDir& out,
                                               const output::RunSettings& settings,
                                               output::RunLayout layout,
                                               const solvers::StaticConfiguration& statics,
                                               const app::RunCheckpoint* restart) {
  std::unique_ptr<output::RunStream> stream;
  app::on_rank0(ctx, [&] {
    const bool snapshots = layout.snapshots;
    const std::string path = out.file("results.h5");
    if (restart) {
      std::filesystem::copy_file(app::restart_dir(ctx) + "/results.h5", path);
      stream = std::make_unique<output::RunStream>(path, settings, std::move(layout),
                                                   restart->progress.records,
                                                   restart->progress.snapshots, out.provenance());
    } else {
      stream =
          std::make_unique<output::RunStream>(path, settings, std::move(layout), out.provenance());
    }
    if (snapshots) output::write_static_mesh(out, statics.mesh, statics.result.node_values);
  });
  return stream;
}

// An interrupted run keeps its partial folder: data up to this step, a
// checkpoint, a summary saying it is incomplete.
int keep_interrupted(const app::CommandContext& ctx, OutputDir& out, app::RunSession& session,
                     std::unique_ptr<output::RunStream>& stream, const output::RunSettings& s,
                     const catenary::CatenaryMesh& mesh, int signal) {
  const bool checkpointed = session.checkpoint_last_step();
  nlohmann::json facts = session.facts();
  facts["interrupted_by"] = app::signal_name(signal);
  facts["provenance"] = out.provenance();
  app::on_rank0(ctx, [&] {
    stream->close();
    output::write_run_summary(out, s, nullptr, facts);
    output::write_snapshots_view(out, mesh);
  });
  out.keep_partial();
  app::print0(ctx,
              "\n  interrupted (%s) at t = %.4f s, step %ld: results up to this step%s in %s/\n",
              app::signal_name(signal), session.time(), session.steps(),
              checkpointed ? " and a checkpoint" : "", out.partial_dir().c_str());
  if (checkpointed)
    app::print0(ctx, "  continue with: pcsim run %s --restart %s -o NEW_FOLDER\n",
                ctx.scene_path.c_str(), out.partial_dir().c_str());
  return 128 + signal;
}

// report.html (postproc/report.py) in the result folder; a warning if it
// cannot be made (no Python with matplotlib).
void write_report(const app::CommandContext& ctx, const OutputDir& out) {
  const std::string why = app::run_postproc("report.py", {"run", out.partial_dir()});
  if (why.empty())
    app::print0(ctx, "  report: report.html\n");
  else
    std::fprintf(stderr, "pcsim: warning: no report.html: %s\n", why.c_str());
}

// The statistics, line and energy results of a complete run, and its summary.
void write_complete_results(const app::CommandContext& ctx, const OutputDir& out,
                            const output::RunSettings& settings, const catenary::CatenaryMesh& mesh,
                            bool energy, nlohmann::json facts) {
  const auto stats = output::finish_run_results(out, mesh, settings);
  facts["en50318"] = print_statistics(ctx, settings, stats);
  facts["provenance"] = out.provenance();
  const auto zones = line_results(ctx, out, mesh, settings);
  if (!zones.is_null()) facts["line_zones"] = zones;
  if (energy) facts["energy"] = energy_results(ctx, out);
  output::write_run_summary(out, settings, &stats, facts);
}

// A run that ended by itself: statistics, summary, the result in place.
int finish_complete(const app::CommandContext& ctx, OutputDir& out, app::RunSession& session,
                    std::unique_ptr<output::RunStream>& stream, const output::RunSettings& settings,
                    const catenary::CatenaryMesh& mesh, bool energy,
                    const app::RunCheckpoint* restart, const nlohmann::json& fidelity) {
  nlohmann::json facts = session.facts();
  facts.update(fidelity);
  if (restart) {
    facts["restarted_from"] = app::restart_dir(ctx);
    facts["restart_step"] = restart->state.step;
  }
  app::on_rank0(ctx, [&] {
    stream->close();
    write_complete_results(ctx, out, settings, mesh, energy, facts);
    app::print0(ctx,
                "  %ld steps, %.2f Newton iterations/step, %.2f ms/step, real-time factor %.2f, "
                "peak memory %.0f MB/rank\n",
                session.steps(), facts["newton_iterations_per_step"].get<double>(),
                facts["time_per_step_ms"].get<double>(), facts["real_time_factor"].get<double>(),
                facts["peak_memory_mb"].get<double>());
    if (facts["rejected_steps"].get<long>() > 0)
      app::print0(ctx, "  %ld steps rejected by Newton and retried with a smaller time step\n",
                  facts["rejected_steps"].get<long>());
  });
  if (!ctx.has_option("--no-report")) app::on_rank0(ctx, [&] { write_report(ctx, out); });
  out.commit();
  app::print0(ctx, "  results in %s/\n", out.final_dir().c_str());
  return 0;
}

// The window's mesh (static configuration) with its ends released
// (catenary/window.hpp), on the console.
void prepare_window(const app::CommandContext& ctx, const scene::RunWindow& window,
                    solvers::StaticConfiguration& statics) {
  const auto ends = catenary::release_window_ends(statics.mesh, statics.result.node_values);
  app::print0(ctx,
              "  moving window: %d of the line's %d spans (%d behind, 2 with the pantograph, %d "
              "ahead), %zu wire ends with matched dashpots\n",
              window.spans(), window.line_spans, window.spans_behind, window.spans_ahead,
              ends.size());
}

// The checkpoint of --restart DIR, or null.
std::unique_ptr<app::RunCheckpoint> load_restart(const app::CommandContext& ctx,
                                                 const scene::RunScene& run,
                                                 const OutputRequest& request,
                                                 const std::vector<app::InputFile>& inputs) {
  if (app::restart_dir(ctx).empty()) return nullptr;
  if (run.window)
    throw InputError("command line", "--restart",
                     "a run with a moving window (scene key 'window') cannot be restarted");
  app::check_restart_target(ctx, request.dir);
  return std::make_unique<app::RunCheckpoint>(app::load_run_checkpoint(ctx, inputs));
}

// The static configuration of the line, or of the window with its ends released.
solvers::StaticConfiguration run_statics(const app::CommandContext& ctx,
                                         const scene::RunScene& run) {
  auto statics =
      solvers::static_configuration(ctx.comm, run.window ? run.window->mesh : run.catenary.mesh,
                                    run.catenary.form_finding, "static_");
  if (run.window) prepare_window(ctx, *run.window, statics);
  app::print0(ctx, "  static: %d Newton iterations, height error %.2e m, tension error %.2e\n",
              statics.result.snes_iterations, statics.result.max_height_error_m,
              statics.result.max_tension_error_rel);
  app::print_warnings(ctx, statics.result.warnings);
  return statics;
}

app::RunSession::Options session_options(const scene::RunScene& run, const OutputDir& out,
                                         const std::vector<app::InputFile>& inputs) {
  app::RunSession::Options options;
  options.duration = run.duration();
  options.snapshot_every = run.snapshot_every;
  options.checkpoint_every = run.checkpoint_every;
  options.keep_dropper_forces = run.dropper_forces;
  options.energy = run.energy;
  options.checkpoint_file = out.file(output::kCheckpointName);
  options.inputs = inputs;
  return options;
}

int run_dynamic(const app::CommandContext& ctx) {
  app::RunInputs run_inputs = app::read_run_inputs(ctx);  // every input checked: exit 2 before work
  const InputNode& scene = run_inputs.scene;
  auto& run = run_inputs.run;
  const auto& design = run.catenary.mesh;
  const double c = catenary::wave_speed(design.wires[design.contact_wire]);
  const auto inputs = app::run_input_files(ctx.scene_path, scene);
  const OutputRequest request = ctx.output_request(scene);
  const auto restart = load_restart(ctx, run, request, inputs);
  OutputDir out(ctx.comm, request);
  app::print0(ctx, "pcsim run: scene '%s', design %s\n", ctx.scene_name(scene).c_str(),
              run.catenary.design_path.c_str());
  app::print_warnings(ctx, run.warnings);
  if (run.speed > 0.7 * c)
    app::print0(ctx, "  warning: speed %.0f km/h is above 70%% of the wave speed (%.0f km/h)\n",
                run.speed * 3.6, c * 3.6);
  LogStage stage("Form-finding");  // -log_view: the phases of a run
  const auto statics = run_statics(ctx, run);
  stage.next("Static start");
  const auto settings = app::run_settings(run, ctx.scene_name(scene));
  app::CatenarySetup setup;
  auto system = app::make_coupled_system(ctx, run, statics, setup);
  app::print_catenary_setup(ctx, run, setup);
  system->set_record_dropper_forces(run.dropper_forces);
  std::unique_ptr<app::MovingWindow> window;
  if (run.window)
    window = std::make_unique<app::MovingWindow>(*run.window, *system, design.support_x);
  Vec U0 = system->create_vector(), V0 = system->create_vector();
  solvers::initial_state(*system, U0, V0);
  solvers::DynamicSolver solver(*system, run.dt, run.duration(), run.hht_alpha);
  const auto estimate = app::estimate_accuracy(ctx, run, *system, solver, U0);
  app::print0(ctx, "  %d catenary DOFs + %d pantograph DOFs on %d rank(s); %s path\n",
              static_cast<int>(system->catenary().catenary_dofs()),
              static_cast<int>(system->global_size() - system->catenary().catenary_dofs()),
              ctx.size, solver.cheap_path() ? "cheap (Jacobian reused)" : "full Newton");
  TSType ts_type;
  PCSIM_PETSC(TSGetType(solver.ts(), &ts_type));
  // A restart starts as a new run (the models keep parameters of their static
  // equilibrium), then takes the checkpoint's state.
  set_initial_state(solver, U0, V0);
  if (restart) {
    warn_if_start_differs(ctx, *system, restart->state);
    solver.restore_state(restart->state);
    app::print0(ctx, "  restarted from %s at t = %.4f s, step %ld\n", app::restart_dir(ctx).c_str(),
                restart->state.t, restart->state.step);
  }
  const app::GracefulStop stop;  // from here SIGINT/SIGTERM stop at the next step, data kept
  auto layout = run_layout(run, *system, statics);
  if (window) window->set_line_supports(layout);
  auto stream = open_stream(ctx, out, settings, std::move(layout), statics, restart.get());
  auto options = session_options(run, out, inputs);
  options.window = window.get();
  app::RunSession session(ctx, *system, solver, stream.get(), options, restart.get(), stop);
  PetscReal dt;
  PCSIM_PETSC(TSGetTimeStep(solver.ts(), &dt));
  app::print0(ctx, "  %s at %.0f km/h, %.3f s simulated, dt = %.2e s, TS %s\n",
              system->pantographs().size() > 1 ? "pantographs" : "pantograph",
              system->pantographs().front().run.speed * 3.6, run.duration(), dt, ts_type);
  stage.next("Time loop");
  const int signal = session.integrate();
  stage.next("Output");
  // The modal counters per step of this process (a restart's earlier steps
  // are not in them); "steps" itself comes from the session.
  nlohmann::json fidelity = {{"steps", session.steps() - (restart ? restart->state.step : 0)}};
  app::add_fidelity_facts(run, setup, *system, estimate, fidelity);
  fidelity["step_factor_nonzeros"] = solvers::step_factor_nonzeros(solver.step_ksp());
  fidelity["step_interface_unknowns"] =
      solvers::domain_decomposition_info(solver.step_ksp()).interface_size;
  fidelity.erase("steps");
  if (window) fidelity["window_shifts"] = window->shifts();
  // The statistics' supports and zones are the line's.
  const auto& line = run.window ? design : statics.mesh;
  if (signal != 0) return keep_interrupted(ctx, out, session, stream, settings, line, signal);
  if (session.stopped_early()) session.checkpoint_last_step();  // -ts_max_steps: can go on
  return finish_complete(ctx, out, session, stream, settings, line, run.energy, restart.get(),
                         fidelity);
}

}  // namespace

PCSIM_COMMAND_HELP(
    run_help, "run",
    "scene sections (docs/scene-format.md, \"Run scenes\"):\n"
    "  name         scene name: results go to out/<name>/ (default: the file name)\n"
    "  description  free text\n"
    "  catenary     design: FILE (docs/design-format.md), form_finding: true|false,\n"
    "               model: nonlinear|linear|modal, max_frequency_hz, modal (docs/fidelity.md)\n"
    "  pantographs  list of {name, model, start_x, static_force, start, ramp_distance,\n"
    "               working_height, effects}\n"
    "  simulation   speed_kmh, end_x [m], dt [s]\n"
    "  effects      catenary_nonlinear, dropper_slack, rayleigh_damping\n"
    "  contact      stiffness [N/m]\n"
    "  analysis     from_span, to_span, cutoff_hz\n"
    "  output       dropper_forces, snapshot_every, energy, checkpoint_every\n"
    "  window       spans_behind, spans_ahead: a moving window (docs/scaling.md)\n"
    "  base, set    composition: a base scene, keys set by path\n"
    "results: results.h5, summary.json (EN 50318 figures, provenance), report.html;\n"
    "an interrupted run (SIGINT, SIGTERM) keeps <dir>.partial with its data and a\n"
    "checkpoint (README \"Interrupted runs and restarts\")\n",
    {"--no-report", "", "no report.html (postproc/report.py)"},
    {"--restart", "DIR", "continue the run whose checkpoint is in DIR, into a new folder"});
PCSIM_COMMAND("run", "dynamic pantograph-catenary interaction (HHT, penalty contact)", run_dynamic);
