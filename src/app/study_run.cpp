#include "study_run.hpp"

#include <malloc.h>
#include <petsctime.h>

#include <cstdio>
#include <fstream>

#include "accuracy_estimate.hpp"
#include "catenary_setup.hpp"
#include "exit_status.hpp"
#include "pcsim/output/output_dir.hpp"
#include "pcsim/output/run_results.hpp"
#include "pcsim/output/run_stream.hpp"
#include "pcsim/scene/composition.hpp"
#include "pcsim/scene/run_scene.hpp"
#include "pcsim/solvers/dynamics.hpp"
#include "pcsim/solvers/hht.hpp"
#include "pcsim/solvers/static_start.hpp"
#include "run_settings.hpp"

namespace pcsim::app {

namespace {

// The peak resident memory of this run: the heap freed by earlier runs given
// back to the system (malloc_trim) and the kernel's high-water mark reset
// before it (/proc/self/clear_refs), read after, largest over ranks [MB].
void reset_peak_memory() {
  malloc_trim(0);
  std::ofstream("/proc/self/clear_refs") << "5";
}
double peak_memory(MPI_Comm comm) {
  std::ifstream status("/proc/self/status");
  std::string line;
  double kb = 0;
  while (std::getline(status, line))
    if (line.rfind("VmHWM:", 0) == 0) kb = std::atof(line.c_str() + 6);
  double mb = kb / 1024, max_mb = 0;
  MPI_Allreduce(&mb, &max_mb, 1, MPI_DOUBLE, MPI_MAX, comm);
  return max_mb > 0 ? max_mb : peak_memory_mb(comm);
}

}  // namespace

double design_element_length(const InputNode& scene) {
  const InputNode design = scene["catenary"].load_referenced("design");
  if (!design.has("type") || design.get_string("type") != "parametric") return 0.0;
  return design.get_double("element_length", 0.5);  // the design reader's default
}

namespace {

// The scene changed as the variant says: the element length through a --set
// of the design's key (composition, like the user's own --set), the rest in
// the scene read.
scene::RunScene variant_scene(const CommandContext& ctx, const StudyVariant& v, double h) {
  std::vector<std::string> overrides = ctx.overrides;
  if (v.h_factor != 1) {
    char value[64];
    std::snprintf(value, sizeof(value), "%.17g", h);
    overrides.push_back(std::string("catenary.design.element_length=") + value);
  }
  std::vector<InputOverride> parsed;
  for (const auto& o : overrides)
    parsed.push_back(parse_override(o, {"", "pcsim study --set " + o}));
  auto run = scene::load_run_scene(load_composed(ctx.scene_path, parsed));
  run.catenary.fidelity = v.model;
  run.effects.catenary_nonlinear = v.model == catenary::CatenaryFidelity::nonlinear;
  run.dt *= v.dt_factor;
  if (v.cutoff_factor > 0) {
    const auto& mesh = run.catenary.mesh;
    run.catenary.modal.max_frequency_hz =
        v.cutoff_factor *
        catenary::doppler_frequency(run.cutoff_hz, run.speed,
                                    catenary::wave_speed(mesh.wires[mesh.contact_wire]));
  }
  run.catenary.modal.vertical_only = v.vertical_only;
  run.snapshot_every = 0;
  run.dropper_forces = false;  // costs a reduced catenary a product per step
  return run;
}

struct Recorder {
  assembly::CoupledSystem* system;
  std::vector<contact::StepRecord> steps;  // rank 0
  int rank = 0;
};

PetscErrorCode record(TS, PetscInt, PetscReal t, Vec U, void* ptr) {
  PCSIM_CALLBACK_BEGIN
  auto& r = *static_cast<Recorder*>(ptr);
  auto rec = r.system->record(t, U);
  if (r.rank == 0) r.steps.push_back(std::move(rec));
  PCSIM_CALLBACK_END
}

// Integrates; returns the wall time of the time loop.
double integrate(solvers::DynamicSolver& solver, Vec U0, Vec V0, Recorder& recorder) {
  TS ts = solver.ts();
  solver.set_initial_state(U0, V0);
  PCSIM_PETSC(TSMonitorSet(ts, record, &recorder, nullptr));
  PetscLogDouble t0, t1;
  PetscTime(&t0);
  PCSIM_PETSC(TSSolve(ts, nullptr));
  PetscTime(&t1);
  TSConvergedReason reason;
  PCSIM_PETSC(TSGetConvergedReason(ts, &reason));
  if (reason < 0)
    throw SolverError(std::string("time integration failed: ") + TSConvergedReasons[reason]);
  return t1 - t0;
}

void fill_results(const output::RunStatistics& stats, const Recorder& recorder, double wall,
                  output::StudyRun& out) {
  const auto& steps = recorder.steps;
  out.steps = steps.empty() ? 0 : static_cast<long>(steps.size()) - 1;
  const double simulated = steps.empty() ? 0.0 : steps.back().t - steps.front().t;
  out.wall_s = wall;
  out.ms_per_step = out.steps > 0 ? 1e3 * wall / out.steps : 0.0;
  out.real_time_factor = wall > 0 ? simulated / wall : 0.0;
  out.uplift_m = stats.max_uplift_m;
  out.ok = true;
  for (const auto& p : stats.pantographs) {
    if (!p.complete) {
      out.ok = false;
      out.failure = "pantograph '" + p.name + "' did not cross the analysis section";
    }
    const auto& f = p.force;
    out.figures.push_back({p.name, f.mean, f.std_dev, f.statistical_max, f.statistical_min,
                           f.actual_max, f.actual_min});
  }
}

}  // namespace

output::StudyRun run_variant(const CommandContext& ctx, const InputNode& scene,
                             const StudyVariant& v, const std::string& run_dir) {
  const double h = design_element_length(scene) * v.h_factor;
  auto run = variant_scene(ctx, v, h);
  output::StudyRun out;
  out.model = catenary::fidelity_name(v.model);
  out.dt = run.dt;
  out.element_length = h;
  out.vertical_only = v.vertical_only;
  reset_peak_memory();
  PetscLogDouble t0, t1;
  PetscTime(&t0);
  try {
    const auto statics = solvers::static_configuration(ctx.comm, run.catenary.mesh,
                                                       run.catenary.form_finding, "static_");
    CatenarySetup setup;
    auto system = make_coupled_system(ctx, run, statics, setup);
    out.cutoff_hz = setup.modal ? setup.cutoff_hz : 0.0;
    out.basis_size = setup.basis_size;
    Vec U0 = system->create_vector(), V0 = system->create_vector();
    solvers::initial_state(*system, U0, V0);
    solvers::DynamicSolver solver(*system, run.dt, run.duration(), run.hht_alpha);
    PCSIM_PETSC(TSSetTimeStep(solver.ts(), run.dt));  // the variant's, over -ts_dt
    const auto estimate = estimate_accuracy(ctx, run, *system, solver, U0, false);
    out.predicted_error_percent = 0;
    for (const auto& c : estimate.criteria)
      out.predicted_error_percent = std::max(out.predicted_error_percent, c.error_percent);
    out.estimate_ok = estimate.ok();
    PetscTime(&t1);
    out.setup_s = t1 - t0;
    Recorder recorder{system.get(), {}, ctx.rank};
    const double wall = integrate(solver, U0, V0, recorder);
    PCSIM_PETSC(VecDestroy(&U0));
    PCSIM_PETSC(VecDestroy(&V0));
    OutputRequest request{run_dir,     "command line",       "-o", "study", ctx.scene_path,
                          out.label(), ctx.provenance(scene)};
    OutputDir dir(ctx.comm, request);
    output::RunStatistics stats;
    auto settings = app::run_settings(run, out.label());
    settings.dropper_forces = false;  // the study keeps the contact force only
    on_rank0(ctx, [&] {
      output::RunLayout layout;
      for (const auto& slot : system->pantographs()) {
        layout.q_sizes.push_back(slot.dof_count());
        layout.q_labels.push_back(slot.model->dof_names());
      }
      layout.support_x = statics.mesh.support_x;
      for (int node : statics.mesh.support_nodes)
        layout.support_static_z.push_back(statics.result.node_values[6 * node + 2]);
      {
        output::RunStream stream(dir.file("results.h5"), settings, layout, dir.provenance());
        for (const auto& rec : recorder.steps) stream.append(rec);
      }
      stats = output::finish_run_results(dir, statics.mesh, settings);
      fill_results(stats, recorder, wall, out);
      output::write_run_summary(dir, settings, &stats, {{"wall_time_s", wall}});
    });
    dir.commit();
  } catch (const SolverError& e) {
    out.ok = false;
    out.failure = e.what();
  }
  out.peak_memory_mb = peak_memory(ctx.comm);
  return out;
}

}  // namespace pcsim::app
