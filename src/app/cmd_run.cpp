// `pcsim run SCENE.yaml`: dynamic pantograph-catenary interaction.
#include <petsctime.h>
#include <petscts.h>
#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "command.hpp"
#include "exit_status.hpp"
#include "pcsim/catenary/mesh_io.hpp"
#include "pcsim/catenary/statics.hpp"
#include "pcsim/contact/interaction.hpp"
#include "pcsim/contact/run_scene.hpp"
#include "pcsim/output/h5_file.hpp"
#include "pcsim/output/output_dir.hpp"
#include "pcsim/output/statistics.hpp"
#include "pcsim/solvers/hht.hpp"

namespace {

using namespace pcsim;

struct RunMonitor {
  contact::InteractionProblem* problem = nullptr;
  const app::CommandContext* ctx = nullptr;
  double duration = 0;
  PetscLogDouble wall_start = 0, last_print = 0;
  std::vector<contact::StepRecord> history;
  long newton_iterations = 0;
  long steps = 0;
  bool keep_dropper_forces = true;
  long snapshot_every = 0;
  std::vector<double> snapshot_times;
  std::vector<std::vector<double>> snapshots;  // node positions (rank 0)
};

PetscErrorCode monitor(TS ts, PetscInt step, PetscReal t, Vec U, void* ptr) {
  PCSIM_CALLBACK_BEGIN
  auto& m = *static_cast<RunMonitor*>(ptr);
  auto rec = m.problem->record(t, U);
  if (!m.keep_dropper_forces) rec.dropper_force.clear();
  if (m.ctx->rank == 0) m.history.push_back(std::move(rec));
  if (m.snapshot_every > 0 && step % m.snapshot_every == 0) {
    auto positions = m.problem->system().gather_positions_to_root(U);  // collective
    if (m.ctx->rank == 0) {
      m.snapshot_times.push_back(t);
      m.snapshots.push_back(std::move(positions));
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

// Zero-phase low-pass of a signal sampled at the accepted time steps. The
// filter needs uniform sampling: when the TS changed the step (rejected
// steps), the signal is first interpolated linearly onto the nominal grid.
std::vector<double> filter_uniformly_sampled(const std::vector<double>& time,
                                             const std::vector<double>& signal, double cutoff_hz) {
  const std::size_t n = time.size();
  if (n < 8) return signal;
  const double dt = (time.back() - time.front()) / (n - 1);
  bool uniform = true;
  for (std::size_t i = 1; i < n && uniform; ++i)
    uniform = std::abs(time[i] - time[i - 1] - dt) < 1e-6 * dt;
  if (uniform) return zero_phase_lowpass(signal, 1.0 / dt, cutoff_hz);
  // Smallest step sets the grid.
  double dt_min = dt;
  for (std::size_t i = 1; i < n; ++i) dt_min = std::min(dt_min, time[i] - time[i - 1]);
  const std::size_t m = static_cast<std::size_t>((time.back() - time.front()) / dt_min) + 1;
  std::vector<double> grid(m), resampled(m);
  std::size_t j = 0;
  for (std::size_t k = 0; k < m; ++k) {
    grid[k] = time.front() + k * dt_min;
    while (j + 2 < n && time[j + 1] < grid[k]) ++j;
    const double w = std::clamp((grid[k] - time[j]) / (time[j + 1] - time[j]), 0.0, 1.0);
    resampled[k] = (1 - w) * signal[j] + w * signal[j + 1];
  }
  const auto filtered_grid = zero_phase_lowpass(resampled, 1.0 / dt_min, cutoff_hz);
  std::vector<double> out(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t k =
        std::min(m - 1, static_cast<std::size_t>(std::lround((time[i] - time.front()) / dt_min)));
    out[i] = filtered_grid[k];
  }
  return out;
}

double peak_memory_mb(MPI_Comm comm) {
  struct rusage usage;
  getrusage(RUSAGE_SELF, &usage);
  double mb = usage.ru_maxrss / 1024.0, max_mb = 0;
  MPI_Allreduce(&mb, &max_mb, 1, MPI_DOUBLE, MPI_MAX, comm);
  return max_mb;
}

int run_dynamic(const app::CommandContext& ctx) {
  const InputNode scene = InputNode::load_file(ctx.scene_path);
  auto run = contact::load_run_scene(scene);
  const auto& design = run.catenary.mesh;
  const double c = contact::wave_speed(design.wires[design.contact_wire]);
  OutputDir out(ctx.comm, ctx.output_request(scene));
  app::print0(ctx, "pcsim run: scene '%s', design %s\n", ctx.scene_name(scene).c_str(),
              run.catenary.design_path.c_str());
  if (run.speed > 0.7 * c)
    app::print0(ctx, "  warning: speed %.0f km/h is above 70%% of the wave speed (%.0f km/h)\n",
                run.speed * 3.6, c * 3.6);

  // 1. Static configuration (form-finding as the scene says).
  const PetscInt extra = run.catenary.form_finding ? catenary::form_finding_unknowns(design) : 0;
  std::vector<double> static_values;
  catenary::CatenaryMesh mesh;
  {
    assembly::CatenarySystem statics_system(ctx.comm, design, extra);
    Vec xs = statics_system.create_vector();
    statics_system.design_state(xs);
    auto statics = catenary::solve_static(statics_system, xs, run.catenary.form_finding, "static_");
    app::print0(ctx, "  static: %d Newton iterations, height error %.2e m, tension error %.2e\n",
                statics.snes_iterations, statics.max_height_error_m, statics.max_tension_error_rel);
    static_values = statics.node_values;
    mesh = statics_system.mesh();
    VecDestroy(&xs);
  }

  // 2. Coupled problem.
  const std::size_t np = run.pantographs.size();
  const double duration = run.duration();
  std::vector<std::string> names;
  for (const auto& p : run.pantographs) names.push_back(p.name);
  contact::InteractionProblem problem(ctx.comm, mesh, static_values, std::move(run.pantographs),
                                      run.effects, run.contact_stiffness);
  char path_option[16] = "";
  PetscBool path_set = PETSC_FALSE;
  PetscOptionsGetString(nullptr, nullptr, "-pcsim_path", path_option, sizeof(path_option),
                        &path_set);
  if (path_set) {
    const std::string path = path_option;
    if (path != "full" && path != "cheap")
      throw InputError("command line", "-pcsim_path", "must be 'full' or 'cheap'");
    problem.set_cheap_path(path == "cheap");
  }
  app::print0(ctx, "  %d catenary DOFs + %d pantograph DOFs on %d rank(s); %s path\n",
              static_cast<int>(problem.system().layout().catenary_dofs()),
              static_cast<int>(problem.system().layout().extra_dofs()), ctx.size,
              problem.cheap_path() ? "cheap (Jacobian reused)" : "full Newton");
  Vec U0 = problem.create_vector(), V0 = problem.create_vector();
  problem.initial_state(U0, V0);
  TS ts = problem.create_ts(run.dt, duration);
  PCSIM_PETSC(TS2SetSolution(ts, U0, V0));
  TSType ts_type;
  PCSIM_PETSC(TSGetType(ts, &ts_type));
  if (std::string(ts_type) == solvers::kTSHHT) {
    // Both starts are equilibria: zero initial acceleration.
    Vec A0 = problem.create_vector();
    PCSIM_PETSC(VecSet(A0, 0.0));
    solvers::hht_set_initial_acceleration(ts, A0);
    PCSIM_PETSC(VecDestroy(&A0));
  }
  RunMonitor mon;
  mon.problem = &problem;
  mon.ctx = &ctx;
  mon.duration = duration;
  mon.keep_dropper_forces = run.dropper_forces;
  mon.snapshot_every = run.snapshot_every;
  PetscTime(&mon.wall_start);
  mon.last_print = mon.wall_start;
  PCSIM_PETSC(TSMonitorSet(ts, monitor, &mon, nullptr));
  PetscReal dt;
  PCSIM_PETSC(TSGetTimeStep(ts, &dt));
  app::print0(ctx, "  %s at %.0f km/h, %.3f s simulated, dt = %.2e s, TS %s\n",
              np > 1 ? "pantographs" : "pantograph", run.speed * 3.6, duration, dt, ts_type);
  PCSIM_PETSC(TSSolve(ts, nullptr));
  TSConvergedReason reason;
  PCSIM_PETSC(TSGetConvergedReason(ts, &reason));
  if (reason < 0)
    throw SolverError(std::string("time integration failed: ") + TSConvergedReasons[reason]);
  PetscLogDouble wall_end;
  PetscTime(&wall_end);
  const double wall = wall_end - mon.wall_start;
  const double memory = peak_memory_mb(ctx.comm);
  PCSIM_PETSC(TSDestroy(&ts));
  PCSIM_PETSC(VecDestroy(&U0));
  PCSIM_PETSC(VecDestroy(&V0));

  // 3. Statistics (EN 50318) and outputs, on rank 0.
  nlohmann::json summary;
  app::on_rank0(ctx, [&] {
    const auto& h = mon.history;
    const std::size_t n = h.size();
    std::vector<double> time(n);
    for (std::size_t i = 0; i < n; ++i) time[i] = h[i].t;
    // Uplift at supports (contact wire, relative to the static configuration).
    const std::size_t ns = mesh.support_nodes.size();
    std::vector<double> uplift(n * ns);
    double max_uplift = 0;
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t s = 0; s < ns; ++s) {
        const double u = h[i].support_z[s] - static_values[6 * mesh.support_nodes[s] + 2];
        uplift[i * ns + s] = u;
        const double xs = mesh.support_x[s];
        if (xs >= run.analysis_from_x - 1e-9 && xs <= run.analysis_to_x + 1e-9)
          max_uplift = std::max(max_uplift, u);
      }
    H5File h5(out.file("results.h5"));
    h5.write("/time", time);
    h5.write("/supports/x", mesh.support_x);
    h5.write("/supports/uplift", uplift, n, ns);
    if (run.dropper_forces && n > 0 && !h[0].dropper_force.empty()) {
      const std::size_t nd = h[0].dropper_force.size();
      std::vector<double> forces(n * nd);
      for (std::size_t i = 0; i < n; ++i)
        std::copy(h[i].dropper_force.begin(), h[i].dropper_force.end(), forces.begin() + i * nd);
      h5.write("/droppers/force", forces, n, nd);
    }
    if (!mon.snapshots.empty()) {
      // Static mesh + displacement snapshots: ParaView animation of the wires.
      const auto static_positions = catenary::positions_from_node_values(static_values);
      catenary::write_mesh_h5_xdmf(mesh, static_positions, out.file("static_mesh.h5"),
                                   out.file("static.xdmf"));
      for (std::size_t k = 0; k < mon.snapshots.size(); ++k) {
        std::vector<double> d(mon.snapshots[k]);
        for (std::size_t i = 0; i < d.size(); ++i) d[i] -= static_positions[i];
        h5.write("/snapshots/displacement_" + std::to_string(k), d, mesh.nodes.size(), 3);
      }
      h5.write("/snapshots/time", mon.snapshot_times);
      catenary::write_snapshots_xdmf(mesh, "static_mesh.h5", "results.h5", mon.snapshot_times,
                                     out.file("snapshots.xdmf"));
    }
    h5.attribute("/", "analysis_from_x", run.analysis_from_x);
    h5.attribute("/", "analysis_to_x", run.analysis_to_x);
    h5.attribute("/", "speed_m_s", run.speed);
    summary["scene"] = ctx.scene_name(scene);
    summary["speed_kmh"] = run.speed * 3.6;
    summary["analysis"] = {
        {"from_x", run.analysis_from_x}, {"to_x", run.analysis_to_x}, {"cutoff_hz", run.cutoff_hz}};
    summary["pantographs"] = nlohmann::json::array();
    app::print0(ctx, "\n  EN 50318 statistics (contact force low-pass %.0f Hz, spans %d-%d)\n",
                run.cutoff_hz, run.analysis_from_span, run.analysis_to_span);
    for (std::size_t p = 0; p < np; ++p) {
      std::vector<double> force(n), x(n), zw(n);
      const std::size_t nq = h.empty() ? 0 : h[0].q[p].size();
      std::vector<double> q(n * nq);
      for (std::size_t i = 0; i < n; ++i) {
        force[i] = h[i].contact_force[p];
        x[i] = h[i].contact_x[p];
        zw[i] = h[i].wire_z[p];
        std::copy(h[i].q[p].begin(), h[i].q[p].end(), q.begin() + i * nq);
      }
      const std::string g = "/pantographs/" + names[p];
      h5.write(g + "/position", x);
      h5.write(g + "/contact_force", force);
      h5.write(g + "/wire_height", zw);
      h5.write(g + "/q", q, n, nq);
      const auto filtered = filter_uniformly_sampled(time, force, run.cutoff_hz);
      h5.write(g + "/contact_force_filtered", filtered);
      const bool crossed =
          !x.empty() && x.front() <= run.analysis_from_x && x.back() >= run.analysis_to_x;
      if (!crossed) {
        // A run cut short (-ts_max_steps, -ts_max_time) has no complete section.
        app::print0(ctx, "  %-12s did not cross the analysis section: no statistics\n",
                    names[p].c_str());
        summary["pantographs"].push_back({{"name", names[p]}, {"complete", false}});
        continue;
      }
      const auto st = force_statistics(x, filtered, force, run.analysis_from_x, run.analysis_to_x);
      nlohmann::json j = {{"name", names[p]},
                          {"mean_N", st.mean},
                          {"std_N", st.std_dev},
                          {"stat_max_N", st.statistical_max},
                          {"stat_min_N", st.statistical_min},
                          {"max_N", st.actual_max},
                          {"min_N", st.actual_min},
                          {"loss_of_contact_percent", st.loss_of_contact_percent},
                          {"samples", st.samples}};
      summary["pantographs"].push_back(j);
      app::print0(ctx,
                  "  %-12s mean %7.2f N  std %6.2f N  stat max %7.2f  stat min %7.2f  "
                  "max %7.2f  min %7.2f  loss of contact %.2f%%\n",
                  names[p].c_str(), st.mean, st.std_dev, st.statistical_max, st.statistical_min,
                  st.actual_max, st.actual_min, st.loss_of_contact_percent);
    }
    summary["max_uplift_at_support_m"] = max_uplift;
    summary["steps"] = mon.steps;
    summary["newton_iterations"] = mon.newton_iterations;
    summary["newton_iterations_per_step"] =
        mon.steps > 0 ? static_cast<double>(mon.newton_iterations) / mon.steps : 0.0;
    summary["wall_time_s"] = wall;
    summary["time_per_step_ms"] = mon.steps > 0 ? 1e3 * wall / mon.steps : 0.0;
    const double simulated = h.empty() ? 0.0 : h.back().t - h.front().t;
    summary["simulated_time_s"] = simulated;
    summary["real_time_factor"] = simulated / wall;
    summary["peak_memory_mb"] = memory;
    summary["ranks"] = ctx.size;
    summary["dofs"] = problem.system().layout().global_size();
    summary["path"] = problem.cheap_path() ? "cheap" : "full";
    std::ofstream(out.file("summary.json")) << summary.dump(2) << "\n";
    app::print0(ctx, "  max uplift at a support in the section: %.1f mm\n", 1e3 * max_uplift);
    app::print0(ctx,
                "  %ld steps, %.2f Newton iterations/step, %.2f ms/step, real-time factor %.2f, "
                "peak memory %.0f MB/rank\n",
                mon.steps, summary["newton_iterations_per_step"].get<double>(),
                summary["time_per_step_ms"].get<double>(), simulated / wall, memory);
  });
  out.commit();
  app::print0(ctx, "  results in %s/\n", out.final_dir().c_str());
  return 0;
}

}  // namespace

PCSIM_COMMAND("run", "dynamic pantograph-catenary interaction (HHT, penalty contact)", run_dynamic);
