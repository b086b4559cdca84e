// `pcsim run SCENE.yaml [--restart DIR]`: dynamic pantograph-catenary interaction
// through the run pipeline (simulation/run.hpp); this file reads the command
// line and prints.
#include <petscsys.h>

#include <memory>

#include "command.hpp"
#include "exit_status.hpp"
#include "inputs.hpp"
#include "pcsim/core/error.hpp"
#include "pcsim/core/format.hpp"
#include "pcsim/core/vec_root.hpp"
#include "pcsim/output/assessment.hpp"
#include "pcsim/output/en50318.hpp"
#include "pcsim/output/output_dir.hpp"
#include "pcsim/output/run_results.hpp"
#include "pcsim/scene/run_scene.hpp"
#include "pcsim/simulation/accuracy_pilot.hpp"
#include "pcsim/simulation/interrupt.hpp"
#include "pcsim/simulation/pilot_extremes.hpp"
#include "pcsim/simulation/run.hpp"
#include "processes.hpp"
#include "rerun.hpp"

namespace {

using namespace pcsim;

// The EN 50318 table of one pantograph: figure, unit, value, and the range
// and verdict where the run is judged against EN 50318's ranges at this speed.
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

// Which criteria set judges the run, why, and what it is for.
void print_criteria_set(const app::CommandContext& ctx, const Assessment& a, double speed_kmh) {
  app::print0(ctx, "  criteria set %s: %s [%s; %s]\n", a.set.name.c_str(), a.set.title.c_str(),
              a.choice.c_str(), a.set.file.c_str());
  if (a.set.name != "en50318-2002") {
    app::print0(ctx, "  %s, %s line at %.0f km/h", a.set.scope.c_str(), a.electrification.c_str(),
                a.line_speed_kmh);
    app::print0(ctx,
                "; \"unverified\": a value not checked against its source (docs/assessment.md)\n");
    return;
  }
  const auto& reference = output::en50318_reference();
  if (reference.ranges_at(speed_kmh))
    app::print0(ctx, "  acceptance ranges of %s at %.0f km/h (%s)\n", reference.edition.c_str(),
                speed_kmh, a.set.criteria.empty() ? "" : a.set.criteria.front().clause.c_str());
  else
    app::print0(ctx, "  %s gives acceptance ranges at %s only: values without verdict\n",
                reference.edition.c_str(), reference.speeds_with_ranges().c_str());
}

// Under a wind: the contact point's lateral position against the permissible
// one, from the head's centre where the cross-wind blows the head aside too.
void print_lateral(const app::CommandContext& ctx, const output::RunSettings& s,
                   const output::PantographStatistics& p, std::size_t i) {
  if (!(s.permissible_lateral_m > 0)) return;
  const bool head_moves = i < s.cross_wind.size() && s.cross_wind[i].on;
  app::print0(ctx, "    contact point up to %.1f mm from the track centre (x = %.1f m)%s",
              1e3 * p.max_lateral_m, p.max_lateral_x,
              s.lateral_static ? " (the wire's static position: modal level)" : "");
  if (head_moves)
    app::print0(ctx,
                "; the cross-wind's %.1f N on the\n    pantograph moves its head %.1f mm: up to "
                "%.1f mm from the head's centre (x = %.1f m)",
                s.cross_wind[i].force_n, 1e3 * s.cross_wind[i].offset_m, 1e3 * p.max_on_head_m,
                p.max_on_head_x);
  app::print0(ctx, "; permissible %.1f mm: %s\n", 1e3 * s.permissible_lateral_m,
              p.judged_lateral_m <= s.permissible_lateral_m ? "inside the working width"
                                                            : "OUTSIDE the working width");
}

// The figures of every pantograph, judged against the run's criteria set.
void print_statistics(const app::CommandContext& ctx, const output::RunSettings& s,
                      const output::RunStatistics& stats) {
  const double speed_kmh = s.speed * 3.6;
  const bool en50318 = s.assessment.set.name == "en50318-2002";
  app::print0(ctx, "\n  figures (contact force low-pass %.0f Hz, spans %d-%d, %.0f km/h)\n",
              s.cutoff_hz, s.analysis_from_span, s.analysis_to_span, speed_kmh);
  print_criteria_set(ctx, s.assessment, speed_kmh);
  const nlohmann::json run = {{"max_uplift_at_support_m", stats.max_uplift_m}};
  for (std::size_t i = 0; i < stats.pantographs.size(); ++i) {
    const auto& p = stats.pantographs[i];
    if (!p.complete) {
      app::print0(ctx, "  %-12s did not cross the analysis section: no statistics\n",
                  p.name.c_str());
      continue;
    }
    const auto statistics = output::force_statistics_json(p.force);
    app::print0(ctx, "  pantograph '%s'\n", p.name.c_str());
    if (en50318)
      print_en50318_table(ctx, output::assess_en50318(run, statistics, speed_kmh));
    else
      app::print0(ctx, "%s",
                  output::assessment_table(
                      s.assessment, output::judge(s.assessment,
                                                  output::criteria_values(
                                                      statistics, stats.max_uplift_m, s.assessment),
                                                  speed_kmh))
                      .c_str());
    print_lateral(ctx, s, p, i);
    if (p.force.actual_min < 0)
      app::print0(ctx,
                  "    the filtered minimum is negative: the contact force is zero while the "
                  "head is off the wire and\n    the %.0f Hz low-pass smooths that edge below "
                  "zero; unfiltered minimum %.2f N (docs/assessment.md)\n",
                  s.cutoff_hz, p.force.unfiltered_min);
  }
}

// The statistics of each tension section and overlap of a line (null for a
// single section).
void print_line_zones(const app::CommandContext& ctx, const nlohmann::json& zones) {
  if (zones.is_null()) return;
  for (const auto& p : zones)
    for (const auto& z : p["zones"]) {
      if (!z["complete"].get<bool>()) continue;
      const std::string verdict = z.value("criteria_verdict", std::string());
      app::print0(
          ctx, "  %-12s %-12s mean %7.2f N  std %6.2f N  max %7.2f  min %7.2f  loss %.2f%%%s%s\n",
          p["name"].get<std::string>().c_str(), z["name"].get<std::string>().c_str(),
          z["mean_N"].get<double>(), z["std_N"].get<double>(), z["max_N"].get<double>(),
          z["min_N"].get<double>(), z["loss_of_contact_percent"].get<double>(),
          verdict.empty() ? "" : "  criteria: ", verdict == "fail" ? "FAIL" : verdict.c_str());
    }
}

// The energy balance (output.energy).
void print_energy(const app::CommandContext& ctx, const output::EnergyBalance& balance) {
  app::print0(ctx,
              "  energy: W_ext %.4g J, W_diss %.4g J, E - E0 %.4g J; balance residual max %.3g J "
              "(%.2g of the turnover %.4g J)\n",
              balance.work_external.empty() ? 0.0 : balance.work_external.back(),
              balance.work_dissipated.empty() ? 0.0 : balance.work_dissipated.back(),
              balance.change.empty() ? 0.0 : balance.change.back(), balance.max_residual,
              balance.turnover > 0 ? balance.max_residual / balance.turnover : 0.0,
              balance.turnover);
}

// An interrupted run keeps its partial folder: data up to this step, a
// checkpoint, a summary saying it is incomplete.
int report_interrupted(const app::CommandContext& ctx, const output::OutputDir& out,
                       const simulation::RunOutcome& outcome) {
  const char* signal = simulation::signal_name(outcome.signal);
  app::print0(ctx,
              "\n  interrupted (%s) at t = %.4f s, step %ld: results up to this step%s in %s/\n",
              signal, outcome.time, outcome.steps, outcome.checkpointed ? " and a checkpoint" : "",
              out.partial_dir().c_str());
  if (outcome.checkpointed)
    app::print0(ctx, "  continue with: pcsim run %s --restart %s -o NEW_FOLDER\n",
                ctx.scene_path.c_str(), out.partial_dir().c_str());
  return 128 + outcome.signal;
}

// report.html (postproc/report.py) in the result folder; a warning if it
// cannot be made (no Python with matplotlib). Returns why it could not be
// written (a full disk: the run's exit 5), "" otherwise.
std::string write_report(const app::CommandContext& ctx, const output::OutputDir& out) {
  int status = 0;
  const std::string why = app::run_postproc("report.py", {"run", out.partial_dir()}, &status);
  if (why.empty())
    app::print0(ctx, "  report: report.html\n");
  else if (status != app::kPostprocWriteFailed)
    std::fprintf(stderr, "pcsim: warning: no report.html: %s\n", why.c_str());
  if (status != app::kPostprocWriteFailed) return "";
  return why.substr(why.rfind(": ") + 2);  // the OS error: "No space left on device"
}

// A run that ended by itself: the tables, the report, the result in place.
int report_complete(const app::CommandContext& ctx, output::OutputDir& out,
                    const simulation::RunOutcome& outcome, bool energy) {
  const auto& facts = outcome.facts;
  if (ctx.rank == 0) {
    print_statistics(ctx, outcome.settings, outcome.stats);
    print_line_zones(ctx, facts.value("line_zones", nlohmann::json()));
    app::print0(ctx, "%s", simulation::extremes_outside_pilot_text(facts).c_str());
    if (energy) print_energy(ctx, outcome.energy);
  }
  app::print0(ctx,
              "  %ld steps, %.2f Newton iterations/step, %.2f ms/step, real-time factor %.2f, "
              "peak memory %.0f MB/rank\n",
              outcome.steps, facts["newton_iterations_per_step"].get<double>(),
              facts["time_per_step_ms"].get<double>(), facts["real_time_factor"].get<double>(),
              facts["peak_memory_mb"].get<double>());
  app::print0(ctx, "%s", outcome.step_time_summary.c_str());
  if (facts["rejected_steps"].get<long>() > 0)
    app::print0(ctx, "  %ld steps rejected by Newton and retried with a smaller time step\n",
                facts["rejected_steps"].get<long>());
  std::string report_failure;
  if (!ctx.has_option("--no-report"))
    app::on_rank0(ctx, [&] { report_failure = write_report(ctx, out); });
  report_failure = broadcast_text(ctx.comm, report_failure);
  if (!report_failure.empty()) {  // exit 5 on every rank, the results kept
    out.keep_partial();
    app::print0(ctx, "  what was written before is kept in %s/\n", out.partial_dir().c_str());
    throw OutputError(out.file("report.html"), report_failure);
  }
  out.commit();
  app::print0(ctx, "  results in %s/\n", out.final_dir().c_str());
  return 0;
}

// -ts_max_steps and -ts_max_time count from the run's start: a restart with
// a stop at or before its checkpoint would step nothing.
void check_restart_stop(const solvers::TimeIntegrationOptions& numerics, const std::string& dir,
                        const simulation::RunCheckpoint& checkpoint) {
  const auto& state = checkpoint.state;
  const std::string where = "the checkpoint in '" + dir + "' is at step " +
                            std::to_string(state.step) + ", t = " + format_number(state.t) + " s";
  const std::string what =
      ": nothing is left to step (-ts_max_steps and -ts_max_time count from the run's start; "
      "give a later stop, or none to run to the scene's end)";
  if (numerics.max_steps && *numerics.max_steps <= state.step)
    throw InputError("command line", "-ts_max_steps",
                     std::to_string(*numerics.max_steps) + " steps: " + where + what);
  if (numerics.max_time && *numerics.max_time <= state.t)
    throw InputError("command line", "-ts_max_time",
                     format_number(*numerics.max_time) + " s: " + where + what);
}

// The checkpoint of --restart DIR, or null.
std::unique_ptr<simulation::RunCheckpoint> load_restart(
    const app::CommandContext& ctx, const app::RunInputs& inputs_read,
    const output::OutputRequest& request, const std::vector<simulation::InputFile>& inputs) {
  const scene::RunScene& run = inputs_read.run;
  const std::string dir = app::restart_dir(ctx);
  if (dir.empty()) return nullptr;
  simulation::check_restart_target(dir, request.dir);
  auto checkpoint = std::make_unique<simulation::RunCheckpoint>(
      simulation::load_run_checkpoint(ctx, dir, inputs, ctx.overrides));
  if ((checkpoint->window_shifts >= 0) != static_cast<bool>(run.window))
    throw InputError("command line", "--restart",
                     "the checkpoint in '" + dir + "' is of a run " +
                         (run.window ? "without" : "with") + " a moving window; this run has " +
                         (run.window ? "one" : "none") +
                         " (scene key 'window', or the modal level's window on a long line: "
                         "catenary.modal.method)");
  if (run.window && checkpoint->window_shifts > run.window->max_shifts())
    throw InputError("command line", "--restart",
                     "the checkpoint in '" + dir + "' is of a moving window shifted " +
                         std::to_string(checkpoint->window_shifts) + " times; this run's shifts " +
                         std::to_string(run.window->max_shifts()) + " times at most");
  check_restart_stop(inputs_read.numerics, dir, *checkpoint);
  return checkpoint;
}

// A result that could not be written (exit 5, on every rank together): the
// partial folder stays with what was written, not marked complete.
void keep_partial_if_not_written(const app::CommandContext& ctx, output::OutputDir& out,
                                 std::exception_ptr error) {
  if (simulation::exit_status_of(error) != app::kExitOutput) return;
  out.keep_partial();
  app::print0(ctx, "  what was written before is kept in %s/\n", out.partial_dir().c_str());
}

// The estimate from the scene itself (and a modal run's cut-off), before the
// run (not for -help or a restart: its cut-off is the checkpoint's); null if
// a pilot run failed (a warning: the run goes on without it).
nlohmann::json accuracy_pilot(const app::CommandContext& ctx, const scene::InputNode& scene,
                              scene::RunScene& run) {
  const simulation::SceneSource source{ctx.scene_path, ctx.overrides, scene, ctx.provenance(scene)};
  try {
    const auto pilot = simulation::run_accuracy_pilot(ctx, source, run);
    simulation::print_pilot(ctx, pilot);
    return pilot.json();
  } catch (const SolverError& e) {
    app::print0(ctx, "\n");
    app::print_warnings(ctx,
                        std::vector<std::string>{std::string("no accuracy pilot: ") + e.what() +
                                                 "; the run goes on without its estimate"});
  } catch (const simulation::FailedOnOtherRank& e) {  // the other ranks of rank 0's SolverError
    if (e.status() != simulation::kExitSolver) throw;
  }
  return nullptr;
}

// The accuracy pilot's estimate of the run a restart continues (its
// summary.json in DIR; null if there is none): a restart runs no pilot.
nlohmann::json checkpointed_pilot(const app::CommandContext& ctx, const std::string& dir) {
  std::string text;
  if (ctx.rank == 0) {
    const auto summary = simulation::checkpointed_summary(dir);
    if (summary.is_object() && summary.contains("accuracy_estimate") &&
        summary["accuracy_estimate"].contains("pilot"))
      text = summary["accuracy_estimate"]["pilot"].dump();
  }
  text = broadcast_text(ctx.comm, text);
  return text.empty() ? nlohmann::json() : nlohmann::json::parse(text);
}

// The run's accuracy pilot: its own, or a restart's checkpointed run's; null
// for none (then the calibrated estimate, which the console says).
nlohmann::json run_accuracy(const app::CommandContext& ctx, const scene::InputNode& scene,
                            scene::RunScene& run, const simulation::RunRequest& request) {
  const auto pilot = simulation::accuracy_pilot_choice();
  if (request.restart) {
    auto checkpointed = checkpointed_pilot(ctx, request.restart_dir);
    if (!checkpointed.is_null())
      app::print0(ctx,
                  "  accuracy: the estimate of the checkpointed run's pilot (%s/summary.json)\n",
                  request.restart_dir.c_str());
    return checkpointed;
  }
  if (!request.stop_before_stepping && simulation::wants_accuracy_pilot(pilot, run))
    return accuracy_pilot(ctx, scene, run);
  if (pilot == simulation::PilotChoice::automatic && !request.stop_before_stepping)
    app::print0(ctx,
                "  accuracy: the calibrated estimate below; -pcsim_accuracy_pilot true "
                "estimates this run's errors from pilot runs of its scene (docs/fidelity.md)\n");
  return {};
}

int run_dynamic(const app::CommandContext& ctx) {
  app::RunInputs run_inputs = app::read_run_inputs(ctx);  // every input checked: exit 2 before work
  const scene::InputNode& scene = run_inputs.scene;
  if (ctx.has_option("--rerun")) app::check_rerun(ctx, scene);
  auto& run = run_inputs.run;
  simulation::RunRequest request;
  request.name = ctx.scene_name(scene);
  request.scene_path = ctx.scene_path;
  request.inputs = simulation::run_input_files(ctx.scene_path, scene);
  const output::OutputRequest output = ctx.output_request(scene);
  const auto restart = load_restart(ctx, run_inputs, output, request.inputs);
  request.restart = restart.get();
  request.restart_dir = app::restart_dir(ctx);
  // The cut-off the checkpointed run had: its pilot's, which a restart does not run again.
  if (restart && restart->modal_cutoff_hz > 0)
    run.catenary.modal.max_frequency_hz = restart->modal_cutoff_hz;
  PetscBool help = PETSC_FALSE;
  PCSIM_PETSC(PetscOptionsHasHelp(nullptr, &help));
  request.stop_before_stepping = help == PETSC_TRUE;
  output::OutputDir out(ctx.comm, output);
  app::print0(ctx, "pcsim run: scene '%s', design %s\n", request.name.c_str(),
              run.catenary.design_path.c_str());
  app::print_warnings(ctx, run.warnings);
  simulation::RunOutcome outcome;
  try {
    request.accuracy_pilot = run_accuracy(ctx, scene, run, request);
    outcome = simulation::run(ctx, run, request, out);
  } catch (...) {
    keep_partial_if_not_written(ctx, out, std::current_exception());
    throw;
  }
  if (request.stop_before_stepping) return 0;  // -help: options listed, nothing written
  if (!outcome.complete) return report_interrupted(ctx, out, outcome);
  return report_complete(ctx, out, outcome, run.energy);
}

}  // namespace

int pcsim::app::run_scene_command(const CommandContext& ctx) {
  return run_dynamic(ctx);
}

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
    "  effects      dropper_slack, rayleigh_damping (catenary_nonlinear: the older\n"
    "               key of catenary.model)\n"
    "  contact      stiffness [N/m]\n"
    "  analysis     from_span, to_span, cutoff_hz\n"
    "  output       dropper_forces, snapshot_every, energy, checkpoint_every\n"
    "  window       spans_behind, spans_ahead: a moving window (docs/scaling.md)\n"
    "  base, set    composition: a base scene, keys set by path\n"
    "results: results.h5, summary.json (EN 50318 figures, provenance), report.html;\n"
    "an interrupted run (SIGINT, SIGTERM) keeps <dir>.partial with its data and a\n"
    "checkpoint (README \"Interrupted runs and restarts\")\n",
    {"--no-report", "", "no report.html (postproc/report.py)"},
    {"--restart", "DIR", "continue the run whose checkpoint is in DIR, into a new folder"},
    {"--rerun", "DIR",
     "run the record of the result in DIR again (its scene, overrides and "
     "PETSc options; default -o DIR-rerun)"});
PCSIM_COMMAND("run", "dynamic pantograph-catenary interaction (HHT, penalty contact)", run_dynamic);
