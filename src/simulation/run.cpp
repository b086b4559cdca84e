// The run pipeline (run.hpp): one dynamic run of a scene.
#include "pcsim/simulation/run.hpp"

#include <petsctime.h>
#include <petscts.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>

#include "pcsim/assembly/coupled_system.hpp"
#include "pcsim/catenary/window.hpp"
#include "pcsim/core/profiling.hpp"
#include "pcsim/output/assessment.hpp"
#include "pcsim/output/checkpoint.hpp"
#include "pcsim/output/en50318.hpp"
#include "pcsim/output/line_results.hpp"
#include "pcsim/output/run_stream.hpp"
#include "pcsim/simulation/catenary_setup.hpp"
#include "pcsim/simulation/interrupt.hpp"
#include "pcsim/simulation/moving_window.hpp"
#include "pcsim/simulation/pilot_extremes.hpp"
#include "pcsim/simulation/run_session.hpp"
#include "pcsim/simulation/run_settings.hpp"
#include "pcsim/simulation/run_setup.hpp"
#include "pcsim/simulation/setup_memory.hpp"
#include "pcsim/simulation/static_start.hpp"
#include "pcsim/simulation/statics.hpp"
#include "pcsim/solvers/direct.hpp"
#include "pcsim/solvers/dynamics.hpp"
#include "pcsim/solvers/schur_dd.hpp"
#include "pcsim/solvers/statics.hpp"

namespace pcsim::simulation {

namespace {

void warn_if_start_differs(const Context& ctx, assembly::CoupledSystem& system,
                           const solvers::DynamicState& checkpointed) {
  const auto& slots = system.pantographs();
  for (std::size_t p = 0; p < slots.size() && p < checkpointed.head_offsets.size(); ++p)
    if (slots[p].head_offset != checkpointed.head_offsets[p])
      print_warnings(ctx, {"pantograph '" + slots[p].run.name + "' starts " +
                           std::to_string(slots[p].head_offset - checkpointed.head_offsets[p]) +
                           " m from where the checkpointed run started it; the restart will "
                           "not equal an uninterrupted run"});
}

output::RunLayout run_layout(const scene::RunScene& run, assembly::CoupledSystem& system,
                             const simulation::StaticConfiguration& statics) {
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
  if (!layout.snapshots) return layout;
  layout.static_positions = catenary::positions_from_node_values(values);
  for (const auto& c : mesh.cables)
    if (mesh.wires[c.wire].kind == catenary::WireKind::contact)
      layout.contact_segments.push_back({c.nodes[0], c.nodes[1]});
  return layout;
}

// results.h5 on rank 0: new, or a copy of the restart folder's records up to
// its checkpoint; the static mesh for the snapshots.
std::unique_ptr<output::RunStream> open_stream(const Context& ctx, const output::OutputDir& out,
                                               const RunRequest& request,
                                               const output::RunSettings& settings,
                                               output::RunLayout layout,
                                               const simulation::StaticConfiguration& statics) {
  std::unique_ptr<output::RunStream> stream;
  on_rank0(ctx, [&] {
    const bool snapshots = layout.snapshots;
    const std::string path = out.file("results.h5");
    if (const auto* restart = request.restart) {
      std::filesystem::copy_file(request.restart_dir + "/results.h5", path);
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

RunSession::Options session_options(const scene::RunScene& run, const output::OutputDir& out,
                                    const RunRequest& request) {
  RunSession::Options options;
  options.duration = run.duration();
  options.snapshot_every = run.snapshot_every;
  options.checkpoint_every = run.checkpoint_every;
  options.keep_dropper_forces = run.dropper_forces;
  options.record_batches = record_batches_choice();
  options.record_thread = record_thread_choice();
  options.energy = run.energy;
  options.checkpoint_file = out.file(output::kCheckpointName);
  options.inputs = request.inputs;
  if (run.catenary.fidelity == catenary::CatenaryFidelity::modal)
    options.modal_cutoff_hz = run.catenary.modal.max_frequency_hz;
  return options;
}

// The modal counters per step of this process (a restart's earlier steps are
// not in them), the step solver's size, the window's shifts.
nlohmann::json fidelity_facts(const scene::RunScene& run, const RunRequest& request,
                              const CatenarySetup& setup, const assembly::CoupledSystem& system,
                              solvers::DynamicSolver& solver, const RunSession& session,
                              const AccuracyEstimate& estimate, const MovingWindow* window) {
  nlohmann::json fidelity = {
      {"steps", session.steps() - (request.restart ? request.restart->state.step : 0)}};
  add_fidelity_facts(run, setup, system, estimate, fidelity);
  if (!request.accuracy_pilot.is_null())
    fidelity["accuracy_estimate"]["pilot"] = request.accuracy_pilot;
  fidelity["step_factor_nonzeros"] = solvers::step_factor_nonzeros(solver.step_ksp());
  const auto dd = solvers::domain_decomposition_info(solver.step_ksp());
  fidelity["step_interface_unknowns"] = dd.interface_size;
  fidelity["step_interface_bandwidth"] = dd.interface_bandwidth;
  fidelity["step_correction_stored"] = dd.correction_stored;
  fidelity["step_correction_entries"] = dd.correction_entries;
  fidelity.erase("steps");
  if (window) fidelity["window_shifts"] = window->shifts();
  if (const auto* low_rank = solver.low_rank()) {  // the blocks' owners' counts, summed
    long counts[2] = {low_rank->sparse_block_factorisations(),
                      low_rank->kept_order_factorisations()};
    MPI_Allreduce(MPI_IN_PLACE, counts, 2, MPI_LONG, MPI_SUM,
                  PetscObjectComm(reinterpret_cast<PetscObject>(solver.ts())));
    if (counts[0] > 0)
      fidelity["sparse_block_factorisations"] = {{"all", counts[0]},
                                                 {"in_j0_pivot_order", counts[1]}};
  }
  return fidelity;
}

// The figures of every pantograph that crossed the analysis section: EN
// 50318's ('en50318': with their ranges and verdicts only when the run is
// judged against en50318-2002) and their verdicts under the run's criteria
// set ('assessment', docs/assessment.md).
void assess_figures(const output::RunSettings& s, const output::RunStatistics& stats,
                    nlohmann::json& facts) {
  const nlohmann::json run = {{"max_uplift_at_support_m", stats.max_uplift_m}};
  const bool en50318 = s.assessment.set.name == "en50318-2002";
  const double speed_kmh = s.speed * 3.6;
  nlohmann::json figures = nlohmann::json::object();
  std::map<std::string, std::vector<output::JudgedCriterion>> judged;
  for (const auto& p : stats.pantographs) {
    if (!p.complete) continue;
    const auto statistics = output::force_statistics_json(p.force);
    figures[p.name] = output::en50318_json(
        output::assess_en50318(run, statistics, speed_kmh, en50318), speed_kmh, en50318);
    judged[p.name] = output::judge(
        s.assessment, output::criteria_values(statistics, stats.max_uplift_m, s.assessment),
        speed_kmh);
  }
  facts["en50318"] = figures;
  facts["assessment"] = output::assessment_json(s.assessment, judged);
}

// Rank 0: the statistics, line and energy results of a complete run and its
// summary, read back from results.h5.
void write_complete_results(const output::OutputDir& out, const catenary::CatenaryMesh& line,
                            bool energy, RunOutcome& outcome) {
  const auto& s = outcome.settings;
  outcome.stats = output::finish_run_results(out, line, s);
  assess_figures(s, outcome.stats, outcome.facts);
  add_extremes_outside_pilot(outcome.stats, outcome.facts);
  outcome.facts["provenance"] = out.provenance();
  if (line.zones.size() >= 2) {
    auto zones =
        output::write_line_results(out, line, output::read_contact_histories(out, s), s.cutoff_hz);
    output::judge_line_zones(s.assessment, s.speed * 3.6, zones);
    outcome.facts["line_zones"] = zones;
  }
  if (energy) {
    const auto history = output::read_energy_history(out);
    outcome.energy = output::energy_balance(history);
    outcome.facts["energy"] = output::write_energy_results(out.file("energy.h5"), history,
                                                           outcome.energy, out.provenance());
  }
  output::write_run_summary(out, s, &outcome.stats, outcome.facts);
}

// Rank 0: an interrupted run's summary and snapshot view; the folder stays partial.
void write_interrupted_results(const output::OutputDir& out, const catenary::CatenaryMesh& line,
                               RunOutcome& outcome) {
  outcome.facts["interrupted_by"] = signal_name(outcome.signal);
  outcome.facts["provenance"] = out.provenance();
  output::write_run_summary(out, outcome.settings, nullptr, outcome.facts);
  output::write_snapshots_view(out, line);
}

// After the time loop: the facts, a checkpoint where the run can go on, the
// results (complete, or the partial folder of an interrupted run).
void finish(const Context& ctx, const scene::RunScene& scene, const RunRequest& request,
            const CatenarySetup& setup, const assembly::CoupledSystem& system,
            solvers::DynamicSolver& solver, RunSession& session, const MovingWindow* window,
            const simulation::StaticConfiguration& statics, output::OutputDir& out,
            RunOutcome& outcome) {
  outcome.steps = session.steps();
  outcome.time = session.time();
  outcome.facts = session.facts();
  outcome.step_time_summary = session.timing().summary_line();
  outcome.facts.update(
      fidelity_facts(scene, request, setup, system, solver, session, outcome.estimate, window));
  outcome.facts["setup_s"] = outcome.setup_s;
  outcome.facts["statics_kept_in_memory"] = outcome.statics_kept;
  if (request.restart) {
    outcome.facts["restarted_from"] = request.restart_dir;
    outcome.facts["restart_step"] = request.restart->state.step;
  }
  if (outcome.signal != 0 || session.stopped_early())  // -ts_max_steps: can go on
    outcome.checkpointed = session.checkpoint_last_step();
  outcome.complete = outcome.signal == 0;
  // The statistics' supports and zones are the line's.
  const auto& line = scene.window ? scene.catenary.mesh : statics.mesh;
  on_rank0(ctx, [&] {
    if (session.stream()) session.stream()->close();
    if (outcome.complete)
      write_complete_results(out, line, scene.energy, outcome);
    else
      write_interrupted_results(out, line, outcome);
  });
  if (!outcome.complete) out.keep_partial();
}

// -snes_test_jacobian on the modal level: PETSc 3.18's test builds its
// finite-difference Jacobian, dense here (the contact couples every mode), in
// a sparse matrix of the hand-coded one's type without preallocation, whose
// every few inserts copy it whole. A Newton iteration's test of the EN 50318
// catenary took 4 s at 623 unknowns, 34 s at 1019 and 95 s at 1248 (15, 25,
// 30 Hz; build/pcsim run runs/en50318-300-modal.yaml --set
// catenary.max_frequency_hz=F -pcsim_accuracy_pilot false -ts_max_steps 1
// -snes_test_jacobian, less the run without the test): about n^4, so some 37
// min at EN 50318's default cut-off and hours above (on the three-span
// catenary at 300 Hz, 1163 unknowns, a scene it was not fitted to: 58 s,
// estimated 72 s). Said before the steps, with a cut-off that tests the same
// code in seconds.
void warn_slow_jacobian_test(const Context& ctx, const assembly::CoupledSystem& system) {
  PetscBool test = PETSC_FALSE;
  PCSIM_PETSC(PetscOptionsHasName(nullptr, nullptr, "-snes_test_jacobian", &test));
  if (!test || system.catenary().fidelity() != catenary::CatenaryFidelity::modal) return;
  constexpr double kMeasuredUnknowns = 1248, kMeasuredSeconds = 95;
  const double n = static_cast<double>(system.global_size());
  const double seconds = kMeasuredSeconds * std::pow(n / kMeasuredUnknowns, 4);
  if (seconds < 60) return;
  char duration[32], text[512];
  if (seconds < 120)
    std::snprintf(duration, sizeof duration, "%.0f s", seconds);
  else if (seconds < 7200)
    std::snprintf(duration, sizeof duration, "%.0f min", seconds / 60);
  else
    std::snprintf(duration, sizeof duration, "%.1f h", seconds / 3600);
  std::snprintf(text, sizeof text,
                "-snes_test_jacobian on the modal level with %.0f unknowns: about %s a Newton "
                "iteration (PETSc stores its finite-difference Jacobian, dense here, in a "
                "sparse matrix it grows entry by entry: %.0f s at %.0f unknowns, as n^4); the "
                "tangents are the same code at any cut-off: --set catenary.max_frequency_hz=15 "
                "tests them in seconds",
                n, duration, kMeasuredSeconds, kMeasuredUnknowns);
  print_warnings(ctx, std::vector<std::string>{text});
}

bool has_block_terms(const assembly::CoupledSystem& system) {
  for (const auto& term : system.terms())
    if (term->tangent_kind() == assembly::TangentKind::block) return true;
  return false;
}

}  // namespace

// A nonlinear pantograph's tangent stays in its own block (refactored per
// iteration on the cheap path): only the catenary decides.
bool cheap_path_possible(const scene::RunScene& scene) {
  return scene.catenary.fidelity != catenary::CatenaryFidelity::nonlinear;
}

RunOutcome run(const Context& ctx, scene::RunScene& scene, const RunRequest& request,
               output::OutputDir& out, RunObserver* observer) {
  const double start = wall_clock_s();
  RunOutcome outcome;
  const auto& design = scene.catenary.mesh;
  LogStage stage("Form-finding");  // -log_view: the phases of a run
  RunSetup prepared = set_up_run(ctx, scene, &stage);
  const auto& statics = prepared.statics;
  const CatenarySetup& setup = prepared.catenary;
  auto& system = prepared.system;
  outcome.statics_kept = prepared.statics_kept;
  outcome.settings = run_settings(scene, request.name);
  system->set_record_dropper_forces(scene.dropper_forces);
  std::unique_ptr<MovingWindow> window;
  if (scene.window)
    window = std::make_unique<MovingWindow>(*scene.window, *system, design.support_x);
  Vec U0 = system->create_vector(), V0 = system->create_vector();
  initial_state(*system, U0, V0);
  const auto solver_owner = make_run_solver(scene, *system);
  solvers::DynamicSolver& solver = *solver_owner;
  if (ctx.quiet) solver.silence_monitors();  // before RunSession::integrate() adds its own
  if (request.scene_dt) PCSIM_PETSC(TSSetTimeStep(solver.ts(), scene.dt));
  // With the pilot's estimate, the calibrated rules only when one is broken.
  const bool pilot = !request.accuracy_pilot.is_null();
  outcome.estimate = estimate_accuracy(ctx, scene, *system, solver, U0, !pilot);
  if (pilot && !outcome.estimate.ok()) print_accuracy(ctx, outcome.estimate);
  print0(ctx, "  %d catenary DOFs + %d pantograph DOFs on %d rank(s); %s path\n",
         static_cast<int>(system->catenary().catenary_dofs()),
         static_cast<int>(system->global_size() - system->catenary().catenary_dofs()), ctx.size,
         solver.cheap_path() ? "cheap (Jacobian reused)" : "full Newton");
  if (solver.cheap_path() && has_block_terms(*system))
    print0(ctx, "  cheap path: nonlinear pantograph blocks refactored at every Newton iteration\n");
  warn_slow_jacobian_test(ctx, *system);
  if (request.stop_before_stepping) {
    print0(ctx,
           "  -help: the options above are those this run reads; stopped before the "
           "time loop, nothing written\n");
    return outcome;
  }
  // A restart starts as a new run (the models keep parameters of their static
  // equilibrium), then takes the checkpoint's state.
  solver.set_initial_state(U0, V0);
  PCSIM_PETSC(VecDestroy(&U0));
  PCSIM_PETSC(VecDestroy(&V0));
  if (request.restart) {
    warn_if_start_differs(ctx, *system, request.restart->state);
    if (window) window->resume(request.restart->window_shifts);  // its pins before J0
    solver.restore_state(request.restart->state);
    print0(ctx, "  restarted from %s at t = %.4f s, step %ld\n", request.restart_dir.c_str(),
           request.restart->state.t, request.restart->state.step);
  }
  // From here SIGINT/SIGTERM stop at the next step, data kept.
  std::unique_ptr<GracefulStop> stop;
  if (request.stop_on_signal) stop = std::make_unique<GracefulStop>();
  auto layout = run_layout(scene, *system, statics);
  if (window) window->set_line_supports(layout);
  auto stream = open_stream(ctx, out, request, outcome.settings, std::move(layout), statics);
  auto options = session_options(scene, out, request);
  options.window = window.get();
  options.observer = observer;
  RunSession session(ctx, *system, solver, stream.get(), options, request.restart, stop.get());
  PetscReal dt;
  TSType ts_type;
  PCSIM_PETSC(TSGetTimeStep(solver.ts(), &dt));
  PCSIM_PETSC(TSGetType(solver.ts(), &ts_type));
  print0(ctx, "  %s at %.0f km/h, %.3f s simulated, dt = %.2e s, TS %s\n",
         system->pantographs().size() > 1 ? "pantographs" : "pantograph",
         system->pantographs().front().run.speed * 3.6, scene.duration(), dt, ts_type);
  if (const auto throttled = session.timing().scheduling().throttle_warning(); !throttled.empty())
    print_warnings(ctx, std::vector<std::string>{throttled});
  outcome.setup_s = wall_clock_s() - start;
  stage.next("Time loop");
  outcome.signal = session.integrate();
  stage.next("Output");
  finish(ctx, scene, request, setup, *system, solver, session, window.get(), statics, out, outcome);
  return outcome;
}

}  // namespace pcsim::simulation
