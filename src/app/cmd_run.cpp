// `pcsim run SCENE.yaml`: dynamic pantograph-catenary interaction.
//   scene -> static configuration -> coupled system -> initial state -> TS -> results
#include <petsctime.h>
#include <petscts.h>

#include "accuracy_estimate.hpp"
#include "catenary_setup.hpp"
#include "command.hpp"
#include "exit_status.hpp"
#include "pcsim/assembly/coupled_system.hpp"
#include "pcsim/output/output_dir.hpp"
#include "pcsim/output/run_results.hpp"
#include "pcsim/scene/run_scene.hpp"
#include "pcsim/solvers/dynamics.hpp"
#include "pcsim/solvers/hht.hpp"
#include "pcsim/solvers/static_start.hpp"
#include "pcsim/solvers/statics.hpp"

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
  long snapshot_every = 0;
};

PetscErrorCode monitor(TS ts, PetscInt step, PetscReal t, Vec U, void* ptr) {
  PCSIM_CALLBACK_BEGIN
  auto& m = *static_cast<RunMonitor*>(ptr);
  auto rec = m.system->record(t, U);
  if (!m.keep_dropper_forces) rec.dropper_force.clear();
  if (m.ctx->rank == 0) m.history.steps.push_back(std::move(rec));
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
    // Both starts are equilibria: zero initial acceleration.
    Vec A0 = system.create_vector();
    PCSIM_PETSC(VecSet(A0, 0.0));
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

void print_statistics(const app::CommandContext& ctx, const output::RunSettings& s,
                      const output::RunStatistics& stats) {
  app::print0(ctx, "\n  EN 50318 statistics (contact force low-pass %.0f Hz, spans %d-%d)\n",
              s.cutoff_hz, s.analysis_from_span, s.analysis_to_span);
  for (const auto& p : stats.pantographs) {
    if (!p.complete) {
      app::print0(ctx, "  %-12s did not cross the analysis section: no statistics\n",
                  p.name.c_str());
      continue;
    }
    const auto& st = p.force;
    app::print0(ctx,
                "  %-12s mean %7.2f N  std %6.2f N  stat max %7.2f  stat min %7.2f  "
                "max %7.2f  min %7.2f  loss of contact %.2f%%\n",
                p.name.c_str(), st.mean, st.std_dev, st.statistical_max, st.statistical_min,
                st.actual_max, st.actual_min, st.loss_of_contact_percent);
  }
  app::print0(ctx, "  max uplift at a support in the section: %.1f mm\n", 1e3 * stats.max_uplift_m);
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

int run_dynamic(const app::CommandContext& ctx) {
  const InputNode scene = InputNode::load_file(ctx.scene_path);
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
  solvers::DynamicSolver solver(*system, run.dt, run.duration());
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
  integrate(ctx, *system, solver, U0, V0, mon);
  PetscLogDouble wall_end;
  PetscTime(&wall_end);
  auto facts = run_facts(ctx, mon, *system, solver.cheap_path(), wall_end - mon.wall_start);
  app::add_fidelity_facts(run, setup, *system, estimate, facts);
  PCSIM_PETSC(VecDestroy(&U0));
  PCSIM_PETSC(VecDestroy(&V0));
  app::on_rank0(ctx, [&] {
    const auto stats = output::write_run_results(out, statics.mesh, statics.result.node_values,
                                                 settings, mon.history);
    output::write_run_summary(out, settings, stats, facts);
    print_statistics(ctx, settings, stats);
    app::print0(ctx,
                "  %ld steps, %.2f Newton iterations/step, %.2f ms/step, real-time factor %.2f, "
                "peak memory %.0f MB/rank\n",
                mon.steps, facts["newton_iterations_per_step"].get<double>(),
                facts["time_per_step_ms"].get<double>(), facts["real_time_factor"].get<double>(),
                facts["peak_memory_mb"].get<double>());
  });
  out.commit();
  app::print0(ctx, "  results in %s/\n", out.final_dir().c_str());
  return 0;
}

}  // namespace

PCSIM_COMMAND("run", "dynamic pantograph-catenary interaction (HHT, penalty contact)", run_dynamic);
