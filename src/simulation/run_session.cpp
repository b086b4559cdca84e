#include "pcsim/simulation/run_session.hpp"

#include <petsctime.h>
#include <sched.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>

#include "pcsim/assembly/modal_catenary.hpp"
#include "pcsim/core/error.hpp"
#include "pcsim/core/profiling.hpp"
#include "pcsim/simulation/run.hpp"
#include "pcsim/solvers/hht.hpp"
#include "pcsim/solvers/low_rank.hpp"
#include "pilot_process.hpp"

namespace pcsim::simulation {

namespace {

// The stepping thread's context switches, not those of the record thread or
// the window shift's helper (RUSAGE_THREAD: Linux).
#ifdef RUSAGE_THREAD
constexpr int kStepThreadUsage = RUSAGE_THREAD;
#else
constexpr int kStepThreadUsage = RUSAGE_SELF;
#endif

// The inputs that usually make a time step fail or the state blow up.
const char* const kLikelyInputs =
    "check simulation.dt (smaller), the design's damping.rayleigh_alpha and "
    "damping.rayleigh_beta, contact.stiffness and the pantograph model's masses, "
    "stiffnesses and damping";

PetscErrorCode read_debug_options(MPI_Comm comm, PetscInt* step, PetscInt* rank) {
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, nullptr, "pcsim run (tests)", "pcsim");
  PetscCall(PetscOptionsInt("-pcsim_debug_signal_step",
                            "Tests: raise SIGTERM after this step (as an interruption would)", "",
                            *step, step, nullptr));
  PetscCall(PetscOptionsInt("-pcsim_debug_signal_rank", "Tests: on this rank only (-1: every rank)",
                            "", *rank, rank, nullptr));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}

}  // namespace

RecordBatches record_batches_choice() {
  return read_auto_option("pcsim run: a modal run's records", "-pcsim_record_batches",
                          "a reduced catenary's records (support heights, dropper forces) "
                          "computed for 32 states at once (auto: where that pays; true; false; "
                          "docs/fidelity.md)");
}

RecordThread record_thread_choice() {
  return read_auto_option("pcsim run: a modal run's record thread", "-pcsim_record_thread",
                          "a batch of records computed on a thread of its own while the steps "
                          "go on (auto: where every rank has a core to spare; true; false; "
                          "docs/fidelity.md)");
}

namespace {

// Whether every rank has a core to spare for a record thread
// (core_to_spare_here) and MPI allows threads that make no MPI calls
// (MPI_THREAD_FUNNELED: PETSc's default when it starts MPI). Agreed by all
// ranks (the batches' sums are collective, in one order).
bool cores_to_spare(MPI_Comm comm) {
  int level = MPI_THREAD_SINGLE;
  MPI_Query_thread(&level);
  // A pilot's second process (pilot_process.hpp) takes the spare core.
  int spare =
      level >= MPI_THREAD_FUNNELED && core_to_spare_here(comm) && !pilot_process_running() ? 1 : 0;
  MPI_Allreduce(MPI_IN_PLACE, &spare, 1, MPI_INT, MPI_MIN, comm);
  return spare != 0;
}

}  // namespace

RunSession::RunSession(const Context& ctx, assembly::CoupledSystem& system,
                       solvers::DynamicSolver& solver, output::RunStream* stream, Options options,
                       const RunCheckpoint* restart, const GracefulStop* stop)
    : ctx_(ctx),
      system_(system),
      solver_(solver),
      stream_(stream),
      options_(std::move(options)),
      stop_(stop),
      path_(solver.cheap_path() ? "cheap" : "full"),
      // (not the pilot's runs beside its second process: both would take CPU N)
      step_cpu_(pilot_process_running() ? -1 : step_cpu_choice(ctx.size)),
      batch_records_(
          system.batches_records() && !options_.window &&
          (options_.record_batches == RecordBatches::on ||
           (options_.record_batches == RecordBatches::automatic && system.records_batch_pays()))) {
  modal_ = dynamic_cast<const assembly::ModalCatenary*>(&system.catenary());
  const bool spare_core = cores_to_spare(ctx.comm);  // collective
  const bool spare = options_.record_thread == RecordThread::automatic && spare_core;
  record_thread_ = batch_records_ && (options_.record_thread == RecordThread::on || spare);
  if (options_.window) options_.window->use_spare_core(spare_core);
  if (restart) {
    first_step_ = restart->state.step;
    skip_first_record_ = true;
    newton_iterations_ = restart->progress.newton_iterations;
    earlier_rejected_ = restart->progress.rejected_steps;
    earlier_wall_ = restart->progress.wall_time_s;
    last_checkpoint_ = first_step_;
    steps_ = first_step_;
    time_ = start_time_ = restart->state.t;
  }
  PetscInt step = -1, rank = -1;
  PCSIM_PETSC(read_debug_options(ctx.comm, &step, &rank));
  debug_signal_step_ = step;
  debug_signal_rank_ = static_cast<int>(rank);
}

double RunSession::wall_time() const {
  return earlier_wall_ + (wall_clock_s() - wall_start_);
}

int RunSession::integrate() {
  TS ts = solver_.ts();
  wall_start_ = last_print_ = step_end_ = wall_clock_s();
  counted_ = counters_now();
  PCSIM_PETSC(TSSetApplicationContext(ts, this));
  PCSIM_PETSC(TSMonitorSet(ts, monitor, this, nullptr));
  PCSIM_PETSC(TSSetPostStep(ts, post_step));
  // A failed step ends TSSolve with an error and a negative reason: the
  // reason, the time and the likely inputs make the message, not PETSc's.
  const PetscErrorCode solved = TSSolve(ts, nullptr);
  raise_output_failure();
  try {
    complete_pending_records();  // collective
  } catch (...) {
    if (!hold_output_failure(std::current_exception())) throw;
  }
  raise_output_failure();
  if (not_finite_) throw SolverError(not_finite_message(not_finite_time_));
  raise_if_step_failed(ts, solved, time_, ", and any -snes_*/-ksp_* options given");
  on_rank0(ctx_, [&] {
    if (stream_) stream_->flush();
  });
  return stop_signal_;
}

void raise_if_step_failed(TS ts, PetscErrorCode solved, double last_time,
                          const std::string& also_check) {
  TSConvergedReason reason;
  PCSIM_PETSC(TSGetConvergedReason(ts, &reason));
  if (reason < 0) {
    PetscInt step = 0;
    PCSIM_PETSC(TSGetStepNumber(ts, &step));
    throw SolverError(std::string("the time step did not converge (") + TSConvergedReasons[reason] +
                      ") at step " + std::to_string(step + 1) + ", after t = " +
                      std::to_string(last_time) + " s; " + kLikelyInputs + also_check);
  }
  if (solved) throw_petsc_error(solved, "TSSolve", __FILE__, __LINE__);
}

std::string not_finite_message(double t) {
  return "the state became NaN or infinite at t = " + std::to_string(t) + " s; " + kLikelyInputs;
}

bool RunSession::hold_output_failure(std::exception_ptr error) {
  if (exit_status_of(error) != kExitOutput) return false;
  if (!output_failure_) output_failure_ = error;
  return true;
}

bool RunSession::agreed_output_failure() const {
  int failed = output_failure_ ? 1 : 0;
  MPI_Allreduce(MPI_IN_PLACE, &failed, 1, MPI_INT, MPI_MAX, ctx_.comm);
  return failed != 0;
}

void RunSession::raise_output_failure() const {
  if (!agreed_output_failure()) return;
  if (output_failure_) std::rethrow_exception(output_failure_);
  throw FailedOnOtherRank(kExitOutput);
}

bool RunSession::state_finite_here(TS ts) const {
  Vec U;
  PCSIM_PETSC(TSGetSolution(ts, &U));
  PetscInt n = 0;
  const PetscScalar* u = nullptr;
  PCSIM_PETSC(VecGetLocalSize(U, &n));
  PCSIM_PETSC(VecGetArrayRead(U, &u));
  const bool finite = std::all_of(u, u + n, [](PetscScalar x) { return std::isfinite(x); });
  PCSIM_PETSC(VecRestoreArrayRead(U, &u));
  return finite;
}

bool RunSession::stopped_early() const {
  return stop_signal_ != 0 || time_ < options_.duration * (1 - 1e-12);
}

// Every accepted step (and the start): a record, perhaps a snapshot, a
// checkpoint when due, the progress line.
PetscErrorCode RunSession::monitor(TS ts, PetscInt step, PetscReal t, Vec U, void* ptr) {
  PCSIM_CALLBACK_BEGIN
  auto& s = *static_cast<RunSession*>(ptr);
  const double start = wall_clock_s();
  s.time_ = t;
  if (s.skip_first_record_) {
    s.skip_first_record_ = false;
  } else {
    PetscInt its = 0;
    if (step > s.first_step_) {
      SNES snes;
      PCSIM_PETSC(TSGetSNES(ts, &snes));
      PCSIM_PETSC(SNESGetIterationNumber(snes, &its));
      s.newton_iterations_ += its;
      s.steps_ = step;
      s.time_step(step, start, its);
    }
    try {
      if (!s.output_stopped_) s.flushed_ = s.record(ts, step, t, U);
      // (A record that failed on rank 0 just now agreed first: every rank or none.)
      if (s.options_.checkpoint_every > 0 && step > s.first_step_ &&
          step % s.options_.checkpoint_every == 0 && !s.output_stopped_ &&
          !s.agreed_output_failure())
        s.write_checkpoint();
    } catch (...) {  // an output failure stops the run in post_step, on every rank
      if (!s.hold_output_failure(std::current_exception())) throw;
    }
  }
  s.print_progress(step, t);
  s.batch_beside_ = s.computing_job_.valid() &&
                    s.computing_job_.wait_for(std::chrono::seconds(0)) != std::future_status::ready;
  s.timing_.add_output(wall_clock_s() - start);
  // What the record did (its own exact anchor, ModalCatenary::dropper_forces;
  // its page faults and context switches) is not the next step's.
  s.counted_ = s.counters_now();
  s.step_end_ = wall_clock_s();
  PCSIM_CALLBACK_END
}

// The counts a step's events are the changes of.
RunSession::StepCounters RunSession::counters_now() const {
  struct rusage usage;
  getrusage(kStepThreadUsage, &usage);
  StepCounters c;
  c.reference_builds = solver_.reference_builds();
  c.involuntary_switches = usage.ru_nivcsw;
  c.page_faults = usage.ru_minflt + usage.ru_majflt;
  if (options_.window) c.window_shifts = options_.window->shifts();
  if (const solvers::LowRankStepSolver* low_rank = solver_.low_rank()) {
    c.rank_one_set_changes = low_rank->active_set_changes();
    c.capacitance_rows = low_rank->capacitance_rows_formed();
  }
  if (modal_) c.exact_dropper_anchors = modal_->exact_anchors();
  return c;
}

// The step that ended at 'start': its wall time since the previous record and
// what happened in it (step_timing.hpp).
void RunSession::time_step(long step, double start, long newton_iterations) {
  const StepCounters now = counters_now();
  StepEvents events;
  events.newton_iterations = newton_iterations;
  events.reference_builds = now.reference_builds - counted_.reference_builds;
  events.involuntary_switches = now.involuntary_switches - counted_.involuntary_switches;
  events.page_faults = now.page_faults - counted_.page_faults;
  events.window_shift = now.window_shifts != counted_.window_shifts;
  events.output_flush_before = flushed_;
  events.records_batch_beside = batch_beside_;
  events.rank_one_set_changes = now.rank_one_set_changes - counted_.rank_one_set_changes;
  events.capacitance_rows = now.capacitance_rows - counted_.capacitance_rows;
  if (const solvers::LowRankStepSolver* low_rank = solver_.low_rank())
    events.rank_one_terms = static_cast<long>(low_rank->active_terms());
  events.exact_dropper_anchors = now.exact_dropper_anchors - counted_.exact_dropper_anchors;
  events.cpu = sched_getcpu();  // -1 where the system cannot tell
  if (step_end_ > 0) timing_.add(step, start - step_end_, events);
}

// A reduced catenary's support heights and dropper forces wait for a batch
// of kRecordBatch records (one product for them all: modal_records.cpp); a
// snapshot, a checkpoint and the run's end complete the batch first.
bool RunSession::record(TS ts, PetscInt step, PetscReal t, Vec U) {
  const bool snapshot = options_.snapshot_every > 0 && step % options_.snapshot_every == 0;
  auto rec = system_.record(t, U, batch_records_);  // collective
  if (options_.window) options_.window->to_line(rec);
  output::EnergySample energy;
  if (options_.energy) {  // collective
    Vec Ut, V;
    PCSIM_PETSC(TS2GetSolution(ts, &Ut, &V));
    energy.energy = system_.energy(t, Ut, V);
    const auto power = system_.power(t, Ut, V);
    energy.power_external = power.external;
    energy.power_dissipative = power.dissipative;
  }
  if (batch_records_) {
    // The snapshot reads the contact only, complete already.
    contact::StepRecord snapshot_record;
    if (snapshot) snapshot_record = rec;
    pending_.emplace_back(std::move(rec), energy);
    if (pending_.size() >= kRecordBatch && record_thread_ && !snapshot)
      start_computing_records();  // collective
    else if (pending_.size() >= kRecordBatch || snapshot)
      complete_pending_records();  // collective
    if (snapshot) rec = std::move(snapshot_record);
  } else {
    deliver(rec, energy);
  }
  if (snapshot) {
    auto positions = system_.catenary().node_positions_to_root(U);  // collective
    if (stream_) stream_->append_snapshot(positions, rec);
  }
  if (!stream_ || !stream_->flush_due()) return false;
  stream_->flush();
  return true;
}

void RunSession::deliver(contact::StepRecord& rec, const output::EnergySample& energy) {
  if (!options_.keep_dropper_forces) rec.dropper_force.clear();
  if (options_.observer) options_.observer->on_record(rec);
  if (stream_) stream_->append(rec, energy);
}

// The full batch's product on a thread of its own; the batch before it,
// whose thread has had a batch's steps to run, is delivered first.
void RunSession::start_computing_records() {
  finish_computing_records();  // collective
  computing_ = std::move(pending_);
  pending_.clear();
  const StepCpuWidened widened;  // (the thread begins off a pinned step's CPU)
  computing_job_ = std::async(std::launch::async, [job = system_.take_records()] {
    leave_step_cpu();  // -pcsim_step_cpu: the step's CPU is the step's
    return job();
  });
}

void RunSession::finish_computing_records() {
  if (!computing_job_.valid()) return;  // the same on every rank
  const ScopedEvent timed(log_events().record);
  deliver_batch(computing_, computing_job_.get());  // waits; rethrows what the product threw
}

void RunSession::complete_pending_records() {
  finish_computing_records();                       // collective: the batch before, in order
  if (!batch_records_ || pending_.empty()) return;  // the same on every rank
  const ScopedEvent timed(log_events().record);
  deliver_batch(pending_, system_.take_records()());
}

// The batch's records filled from its quantities (collective), delivered in
// order; the batch is left empty.
void RunSession::deliver_batch(std::vector<PendingRecord>& batch,
                               assembly::CatenaryModel::RecordQuantities quantities) {
  std::vector<contact::StepRecord*> records;
  for (auto& p : batch) records.push_back(&p.first);
  system_.finish_records(records, std::move(quantities));  // collective
  auto done = std::move(batch);
  batch.clear();
  for (auto& p : done) deliver(p.first, p.second);
}

void RunSession::print_progress(PetscInt step, PetscReal t) const {
  const double now = wall_clock_s();
  if (now - last_print_ <= 5.0 && !(step > first_step_ && t >= options_.duration - 1e-12)) return;
  last_print_ = now;
  const double done = t / options_.duration, done_at_start = start_time_ / options_.duration;
  const double eta =
      done > done_at_start ? (now - wall_start_) * (1 - done) / (done - done_at_start) : 0;
  print0(ctx_, "  t = %7.3f s of %.3f s (%5.1f%%), step %ld, ETA %.0f s\n", t, options_.duration,
         100 * done, static_cast<long>(step), eta);
}

// Tests raise SIGTERM themselves here; then every rank learns whether any
// rank was signalled, and the run stops there if one was.
PetscErrorCode RunSession::post_step(TS ts) {
  PCSIM_CALLBACK_BEGIN
  RunSession* s;
  PCSIM_PETSC(TSGetApplicationContext(ts, &s));
  PetscInt step;
  PCSIM_PETSC(TSGetStepNumber(ts, &step));
  if (step == s->debug_signal_step_ &&
      (s->debug_signal_rank_ < 0 || s->debug_signal_rank_ == s->ctx_.rank))
    std::raise(SIGTERM);
  if (s->options_.window) {
    PetscReal t;
    PCSIM_PETSC(TSGetTime(ts, &t));
    s->options_.window->after_step(t, s->solver_);  // collective
  }
  // One reduction for the three things every rank must agree on: a signal,
  // a state no longer finite (NaN on one rank is seen by all), an output
  // failure.
  int flags[3] = {s->stop_ ? s->stop_->local_signal() : 0, s->state_finite_here(ts) ? 0 : 1,
                  s->output_failure_ ? 1 : 0};
  MPI_Allreduce(MPI_IN_PLACE, flags, 3, MPI_INT, MPI_MAX, s->ctx_.comm);
  s->stop_signal_ = flags[0];
  if (flags[1]) {
    s->not_finite_ = true;
    PCSIM_PETSC(TSGetTime(ts, &s->not_finite_time_));
    PCSIM_PETSC(TSSetConvergedReason(ts, TS_DIVERGED_NONLINEAR_SOLVE));
    return 0;
  }
  const bool output_failed = flags[2] != 0;
  if (output_failed) s->output_stopped_ = true;
  TSConvergedReason reason;
  PCSIM_PETSC(TSGetConvergedReason(ts, &reason));
  if (reason != TS_CONVERGED_ITERATING)
    s->stop_signal_ = 0;  // the last step: the run is complete anyway
  else if (s->stop_signal_ || output_failed)
    PCSIM_PETSC(TSSetConvergedReason(ts, TS_CONVERGED_USER));
  PCSIM_CALLBACK_END
}

void RunSession::write_checkpoint() {
  complete_pending_records();  // collective: the records up to this step
  RunCheckpoint c;
  c.state = solver_.save_state();  // collective
  on_rank0(ctx_, [&] {
    if (!stream_) return;
    stream_->flush();  // the records up to this step are on disk
    c.progress.records = stream_->records();
    c.progress.snapshots = stream_->snapshots();
  });
  c.progress.newton_iterations = newton_iterations_;
  c.progress.rejected_steps = rejected_steps();
  c.progress.wall_time_s = wall_time();
  c.path = path_;
  c.ranks = ctx_.size;
  c.inputs = options_.inputs;
  c.modal_cutoff_hz = options_.modal_cutoff_hz;
  c.window_shifts = options_.window ? options_.window->shifts() : -1;
  write_run_checkpoint(ctx_, options_.checkpoint_file, c);
  last_checkpoint_ = c.state.step;
}

bool RunSession::checkpoint_last_step() {
  TSType type;
  PCSIM_PETSC(TSGetType(solver_.ts(), &type));
  if (std::string(type) != solvers::kTSHHT) return false;
  if (last_checkpoint_ != steps_) write_checkpoint();
  return true;
}

long RunSession::rejected_steps() const {
  return earlier_rejected_ + solvers::hht_get_info(solver_.ts()).rejected_steps;
}

nlohmann::json RunSession::facts() const {
  const double wall = wall_time();
  const double simulated = time_;
  nlohmann::json j;
  j["steps"] = steps_;
  j["newton_iterations"] = newton_iterations_;
  j["newton_iterations_per_step"] =
      steps_ > 0 ? static_cast<double>(newton_iterations_) / steps_ : 0.0;
  j["wall_time_s"] = wall;
  j["time_per_step_ms"] = steps_ > 0 ? 1e3 * wall / steps_ : 0.0;
  j["simulated_time_s"] = simulated;
  j["real_time_factor"] = simulated / wall;
  j["peak_memory_mb"] = peak_memory_mb(ctx_.comm);
  j["peak_memory_total_mb"] = total_peak_memory_mb(ctx_.comm);
  j["ranks"] = ctx_.size;
  j["dofs"] = system_.global_size();
  j["path"] = path_;
  j["records_in_batches"] = batch_records_;
  j["records_thread"] = record_thread_;
  TSType type;
  PCSIM_PETSC(TSGetType(solver_.ts(), &type));
  j["rejected_steps"] = std::string(type) == solvers::kTSHHT ? rejected_steps() : 0;
  if (std::string(type) == solvers::kTSHHT) {  // this process's steps (not a restart's earlier)
    const auto info = solvers::hht_get_info(solver_.ts());
    j["alpha_terms_reused"] = info.alpha_terms_reused;
    j["alpha_terms_evaluated"] = info.alpha_terms_evaluated;
    j["residuals_updated"] = info.residuals_updated;
    if (info.residual_update_checked) j["residual_update_gap_n"] = info.residual_update_gap;
  }
  j["step_time"] = timing_.json();
  j["step_time"]["pinned"] = step_cpu_.json();
  return j;
}

}  // namespace pcsim::simulation
