// `pcsim run SCENE.yaml`: dynamic pantograph-catenary interaction.
//   scene -> static configuration -> coupled system -> initial state -> TS -> results
#include <petsctime.h>
#include <petscts.h>

#include "accuracy_estimate.hpp"
#include "catenary_setup.hpp"
#include "command.hpp"
#include "exit_status.hpp"
#include "pcsim/assembly/coupled_system.hpp"
#include "pcsim/assembly/fe_catenary.hpp"
#include "pcsim/output/en50318.hpp"
#include "pcsim/output/energy_results.hpp"
#include "pcsim/output/line_results.hpp"
#include "pcsim/output/output_dir.hpp"
#include "pcsim/output/run_results.hpp"
#include "pcsim/scene/run_scene.hpp"
#include "pcsim/solvers/dynamics.hpp"
#include "pcsim/solvers/hht.hpp"
#include "pcsim/solvers/static_start.hpp"
#include "pcsim/solvers/statics.hpp"
#include "processes.hpp"

namespace {

using namespace pcsim;

struct RunMonitor {
  assembly::CoupledSystem* system = nullptr;
  const app::CommandContext* ctx = nullptr;
  double duration = 0;
  PetscLogDouble wall_start = 0, last_print = 0;
  output::RunHistory history;
  long newton_iterations = 0;
  long steps = 0;
  bool keep_dropper_forces = true;
  bool energy = false;  // output.energy: E and the powers every step
  output::EnergyHistory energy_history;
  long snapshot_every = 0;
};

// E(t) and the powers of the terms at the TS's state (collective).
void record_energy(TS ts, double t, RunMonitor& m) {
  Vec U, V;
  PCSIM_PETSC(TS2GetSolution(ts, &U, &V));
  const double energy = m.system->energy(t, U, V);
  const auto power = m.system->power(t, U, V);
  auto& h = m.energy_history;
  h.time.push_back(t);
  h.energy.push_back(energy);
  h.power_external.push_back(power.external);
  h.power_dissipative.push_back(power.dissipative);
}

PetscErrorCode monitor(TS ts, PetscInt step, PetscReal t, Vec U, void* ptr) {
  PCSIM_CALLBACK_BEGIN
  auto& m = *static_cast<RunMonitor*>(ptr);
  auto rec = m.system->record(t, U);
  if (!m.keep_dropper_forces) rec.dropper_force.clear();
  if (m.ctx->rank == 0) m.history.steps.push_back(std::move(rec));
  if (m.energy) record_energy(ts, t, m);
  if (m.snapshot_every > 0 && step % m.snapshot_every == 0) {
    auto positions = m.system->catenary().node_positions_to_root(U);  // collective
    if (m.ctx->rank == 0) {
      m.history.snapshot_times.push_back(t);
      m.history.snapshots.push_back(std::move(positions));
    }
  }
  if (step > 0) {
    SNES snes;
    PetscInt its;
    PCSIM_PETSC(TSGetSNES(ts, &snes));
    PCSIM_PETSC(SNESGetIterationNumber(snes, &its));
    m.newton_iterations += its;
    m.steps = step;
  }
  PetscLogDouble now;
  PetscTime(&now);
  if (now - m.last_print > 5.0 || (step > 0 && t >= m.duration - 1e-12)) {
    m.last_print = now;
    const double done = t / m.duration;
    const double eta = done > 0 ? (now - m.wall_start) * (1 - done) / done : 0;
    app::print0(*m.ctx, "  t = %7.3f s of %.3f s (%5.1f%%), step %ld, ETA %.0f s\n", t, m.duration,
                100 * done, static_cast<long>(step), eta);
  }
  PCSIM_CALLBACK_END
}

// Integrates from the initial state; fills the monitor.
void integrate(const app::CommandContext& ctx, assembly::CoupledSystem& system,
               solvers::DynamicSolver& solver, Vec U0, Vec V0, RunMonitor& mon) {
  TS ts = solver.ts();
  PCSIM_PETSC(TS2SetSolution(ts, U0, V0));
  TSType ts_type;
  PCSIM_PETSC(TSGetType(ts, &ts_type));
  if (std::string(ts_type) == solvers::kTSHHT) {
    // Static and ramp starts are equilibria (A0 = 0); a gap start is not.
    Vec A0 = system.create_vector();
    solvers::initial_acceleration(system, U0, V0, A0);
    solvers::hht_set_initial_acceleration(ts, A0);
    PCSIM_PETSC(VecDestroy(&A0));
  }
  PetscTime(&mon.wall_start);
  mon.last_print = mon.wall_start;
  PCSIM_PETSC(TSMonitorSet(ts, monitor, &mon, nullptr));
  PetscReal dt;
  PCSIM_PETSC(TSGetTimeStep(ts, &dt));
  app::print0(ctx, "  %s at %.0f km/h, %.3f s simulated, dt = %.2e s, TS %s\n",
              system.pantographs().size() > 1 ? "pantographs" : "pantograph",
              system.pantographs().front().run.speed * 3.6, mon.duration, dt, ts_type);
  PCSIM_PETSC(TSSolve(ts, nullptr));
  TSConvergedReason reason;
  PCSIM_PETSC(TSGetConvergedReason(ts, &reason));
  if (reason < 0)
    throw SolverError(std::string("time integration failed: ") + TSConvergedReasons[reason]);
}

// Steps the HHT scheme rejected and retried with a smaller Δt (0 for other TS types).
long rejected_steps(TS ts) {
  TSType type;
  PCSIM_PETSC(TSGetType(ts, &type));
  return std::string(type) == solvers::kTSHHT ? solvers::hht_get_info(ts).rejected_steps : 0;
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
nlohmann::json line_results(const app::CommandContext& ctx, const OutputDir& out,
                            const catenary::CatenaryMesh& mesh, const output::RunSettings& s,
                            const output::RunHistory& history) {
  if (mesh.zones.size() < 2) return nullptr;
  std::vector<output::ContactHistory> histories(s.pantograph_names.size());
  for (std::size_t p = 0; p < histories.size(); ++p) {
    histories[p].name = s.pantograph_names[p];
    for (const auto& rec : history.steps) {
      histories[p].time.push_back(rec.t);
      histories[p].x.push_back(rec.contact_x[p]);
      histories[p].force.push_back(rec.contact_force[p]);
      histories[p].wire_force.push_back(rec.wire_force[p]);
    }
  }
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

// energy.h5 and the balance on the console (output.energy).
nlohmann::json energy_results(const app::CommandContext& ctx, const OutputDir& out,
                              const output::EnergyHistory& history) {
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

output::RunSettings run_settings(const app::CommandContext& ctx, const InputNode& scene,
                                 const scene::RunScene& run) {
  output::RunSettings s;
  s.scene_name = ctx.scene_name(scene);
  s.speed = run.speed;
  s.analysis_from_x = run.analysis_from_x;
  s.analysis_to_x = run.analysis_to_x;
  s.analysis_from_span = run.analysis_from_span;
  s.analysis_to_span = run.analysis_to_span;
  s.cutoff_hz = run.cutoff_hz;
  s.dropper_forces = run.dropper_forces;
  for (const auto& p : run.pantographs) s.pantograph_names.push_back(p.name);
  return s;
}

// Performance and solver facts for summary.json and the console.
nlohmann::json run_facts(const app::CommandContext& ctx, const RunMonitor& mon,
                         const assembly::CoupledSystem& system, bool cheap, double wall) {
  const auto& h = mon.history.steps;
  const double simulated = h.empty() ? 0.0 : h.back().t - h.front().t;
  nlohmann::json j;
  j["steps"] = mon.steps;
  j["newton_iterations"] = mon.newton_iterations;
  j["newton_iterations_per_step"] =
      mon.steps > 0 ? static_cast<double>(mon.newton_iterations) / mon.steps : 0.0;
  j["wall_time_s"] = wall;
  j["time_per_step_ms"] = mon.steps > 0 ? 1e3 * wall / mon.steps : 0.0;
  j["simulated_time_s"] = simulated;
  j["real_time_factor"] = simulated / wall;
  j["peak_memory_mb"] = app::peak_memory_mb(ctx.comm);
  j["ranks"] = ctx.size;
  j["dofs"] = system.global_size();
  j["path"] = cheap ? "cheap" : "full";
  return j;
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

int run_dynamic(const app::CommandContext& ctx) {
  const InputNode scene = ctx.load_scene();
  auto run = scene::load_run_scene(scene);
  const auto& design = run.catenary.mesh;
  const double c = catenary::wave_speed(design.wires[design.contact_wire]);
  OutputDir out(ctx.comm, ctx.output_request(scene));
  app::print0(ctx, "pcsim run: scene '%s', design %s\n", ctx.scene_name(scene).c_str(),
              run.catenary.design_path.c_str());
  if (run.speed > 0.7 * c)
    app::print0(ctx, "  warning: speed %.0f km/h is above 70%% of the wave speed (%.0f km/h)\n",
                run.speed * 3.6, c * 3.6);
  const auto statics =
      solvers::static_configuration(ctx.comm, design, run.catenary.form_finding, "static_");
  app::print0(ctx, "  static: %d Newton iterations, height error %.2e m, tension error %.2e\n",
              statics.result.snes_iterations, statics.result.max_height_error_m,
              statics.result.max_tension_error_rel);
  const auto settings = run_settings(ctx, scene, run);
  app::CatenarySetup setup;
  auto system = app::make_coupled_system(ctx, run, statics, setup);
  app::print_catenary_setup(ctx, run, setup);
  Vec U0 = system->create_vector(), V0 = system->create_vector();
  solvers::initial_state(*system, U0, V0);
  solvers::DynamicSolver solver(*system, run.dt, run.duration(), run.hht_alpha);
  const auto estimate = app::estimate_accuracy(ctx, run, *system, solver, U0);
  app::print0(ctx, "  %d catenary DOFs + %d pantograph DOFs on %d rank(s); %s path\n",
              static_cast<int>(system->catenary().catenary_dofs()),
              static_cast<int>(system->global_size() - system->catenary().catenary_dofs()),
              ctx.size, solver.cheap_path() ? "cheap (Jacobian reused)" : "full Newton");
  RunMonitor mon;
  mon.system = system.get();
  mon.ctx = &ctx;
  mon.duration = run.duration();
  mon.keep_dropper_forces = run.dropper_forces;
  system->set_record_dropper_forces(run.dropper_forces);
  mon.snapshot_every = run.snapshot_every;
  mon.energy = run.energy;
  integrate(ctx, *system, solver, U0, V0, mon);
  PetscLogDouble wall_end;
  PetscTime(&wall_end);
  auto facts = run_facts(ctx, mon, *system, solver.cheap_path(), wall_end - mon.wall_start);
  app::add_fidelity_facts(run, setup, *system, estimate, facts);
  facts["rejected_steps"] = rejected_steps(solver.ts());
  PCSIM_PETSC(VecDestroy(&U0));
  PCSIM_PETSC(VecDestroy(&V0));
  app::on_rank0(ctx, [&] {
    const auto stats = output::write_run_results(out, statics.mesh, statics.result.node_values,
                                                 settings, mon.history);
    auto summary_facts = facts;
    summary_facts["en50318"] = print_statistics(ctx, settings, stats);
    summary_facts["provenance"] = out.provenance();
    const auto zones = line_results(ctx, out, statics.mesh, settings, mon.history);
    if (!zones.is_null()) summary_facts["line_zones"] = zones;
    if (mon.energy) summary_facts["energy"] = energy_results(ctx, out, mon.energy_history);
    output::write_run_summary(out, settings, stats, summary_facts);
    app::print0(ctx,
                "  %ld steps, %.2f Newton iterations/step, %.2f ms/step, real-time factor %.2f, "
                "peak memory %.0f MB/rank\n",
                mon.steps, facts["newton_iterations_per_step"].get<double>(),
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
    "  output       dropper_forces, snapshot_every\n"
    "  base, set    composition: a base scene, keys set by path\n"
    "results: results.h5, summary.json (EN 50318 figures, provenance), report.html\n",
    {"--no-report", "", "no report.html (postproc/report.py)"});
PCSIM_COMMAND("run", "dynamic pantograph-catenary interaction (HHT, penalty contact)", run_dynamic);
