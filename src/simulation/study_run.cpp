#include "pcsim/simulation/study_run.hpp"

#include <malloc.h>
#include <petsctime.h>

#include <cstdio>
#include <fstream>

#include "pcsim/output/output_dir.hpp"
#include "pcsim/output/run_results.hpp"
#include "pcsim/scene/composition.hpp"
#include "pcsim/scene/run_scene.hpp"
#include "pcsim/simulation/accuracy_estimate.hpp"
#include "pcsim/simulation/context.hpp"
#include "pcsim/simulation/run.hpp"
#include "pcsim/simulation/run_settings.hpp"
#include "pcsim/simulation/static_start.hpp"
#include "pcsim/solvers/dynamics.hpp"
#include "pcsim/solvers/hht.hpp"

namespace pcsim::simulation {

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

double design_element_length(const scene::InputNode& scene) {
  const scene::InputNode design = scene["catenary"].load_referenced("design");
  if (!design.has("type") || design.get_string("type") != "parametric") return 0.0;
  return design.get_double("element_length", 0.5);  // the design reader's default
}

// The scene changed as the variant says: the element length through a --set
// of the design's key (composition, like the user's own --set), the rest in
// the scene read.
scene::RunScene variant_scene(const SceneSource& source, const StudyVariant& v, double h) {
  std::vector<std::string> overrides = source.overrides;
  if (v.h_factor != 1) {
    char value[64];
    std::snprintf(value, sizeof(value), "%.17g", h);
    overrides.push_back(std::string("catenary.design.element_length=") + value);
  }
  std::vector<scene::InputOverride> parsed;
  for (const auto& o : overrides)
    parsed.push_back(scene::parse_override(o, {"", "pcsim study --set " + o}));
  auto run = scene::load_run_scene(scene::load_composed(source.path, parsed));
  run.catenary.fidelity = v.model;
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

namespace {

void fill_results(const RunOutcome& outcome, output::StudyRun& out) {
  const auto& facts = outcome.facts;
  out.steps = outcome.steps;
  out.wall_s = facts["wall_time_s"].get<double>();
  out.ms_per_step = facts["time_per_step_ms"].get<double>();
  out.real_time_factor = facts["real_time_factor"].get<double>();
  out.uplift_m = outcome.stats.max_uplift_m;
  out.ok = true;
  for (const auto& p : outcome.stats.pantographs) {
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

output::StudyRun run_variant(const Context& ctx, const SceneSource& source, const StudyVariant& v,
                             const std::string& run_dir) {
  const double h = design_element_length(source.scene) * v.h_factor;
  auto run = variant_scene(source, v, h);
  output::StudyRun out;
  out.model = catenary::fidelity_name(v.model);
  out.dt = run.dt;
  out.element_length = h;
  out.vertical_only = v.vertical_only;
  reset_peak_memory();
  try {
    output::OutputRequest request{run_dir,     "command line",   "-o", "study", source.path,
                                  out.label(), source.provenance};
    output::OutputDir dir(ctx.comm, request);
    RunRequest what;
    what.name = out.label();
    what.scene_path = source.path;
    what.stop_on_signal = false;
    what.scene_dt = true;  // the variant's, over -ts_dt
    Context quiet = ctx;
    quiet.quiet = true;
    const auto outcome = simulation::run(quiet, run, what, dir);
    const auto& modal = outcome.facts.value("modal", nlohmann::json::object());
    out.cutoff_hz = modal.value("cutoff_hz", 0.0);
    out.basis_size = modal.value("basis_size", 0);
    out.predicted_error_percent = 0;
    for (const auto& c : outcome.estimate.criteria)
      out.predicted_error_percent = std::max(out.predicted_error_percent, c.error_percent);
    out.estimate_ok = outcome.estimate.ok();
    out.setup_s = outcome.setup_s;
    on_rank0(ctx, [&] { fill_results(outcome, out); });
    dir.commit();
  } catch (const SolverError& e) {
    out.ok = false;
    out.failure = e.what();
  } catch (const FailedOnOtherRank& e) {  // the other ranks of rank 0's SolverError
    if (e.status() != kExitSolver) throw;
    out.ok = false;  // (rank 0 holds the message)
  }
  out.peak_memory_mb = peak_memory(ctx.comm);
  return out;
}

}  // namespace pcsim::simulation
