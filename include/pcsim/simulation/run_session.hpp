// The time integration of `pcsim run` as it goes: every accepted step into
// results.h5 (rank 0, streamed: output/run_stream.hpp), field snapshots,
// checkpoints every output.checkpoint_every steps, and the stop on SIGINT or
// SIGTERM at a step boundary, agreed by every rank (interrupt.hpp).
#pragma once

#include <exception>
#include <future>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "pcsim/assembly/coupled_system.hpp"
#include "pcsim/output/run_stream.hpp"
#include "pcsim/simulation/auto_option.hpp"
#include "pcsim/simulation/context.hpp"
#include "pcsim/simulation/interrupt.hpp"
#include "pcsim/simulation/moving_window.hpp"
#include "pcsim/simulation/run_checkpoint.hpp"
#include "pcsim/simulation/step_cpu.hpp"
#include "pcsim/simulation/step_timing.hpp"
#include "pcsim/solvers/dynamics.hpp"

namespace pcsim::assembly {
class ModalCatenary;
}

namespace pcsim::simulation {

class RunObserver;  // run.hpp

// -pcsim_record_batches auto|true|false: a reduced catenary's records (support
// heights, dropper forces) in batches of states (auto: where that pays,
// ModalCatenary::records_batch_pays). Checked (InputError) on every call.
using RecordBatches = AutoChoice;
RecordBatches record_batches_choice();
// -pcsim_record_thread auto|true|false: a batch's product on a thread of its
// own while the steps go on (auto: where every rank of the node has a core
// to spare, agreed by all ranks). Checked (InputError) on every call.
using RecordThread = AutoChoice;
RecordThread record_thread_choice();
// Counts the job's processes on this node once, for the record thread's auto
// (collective on 'world': pcsim's main and the Python module call it at
// start-up, before a sweep splits the ranks into groups). Uncounted, a run
// counts its own ranks on the node.
void count_node_processes(MPI_Comm world);
int counted_node_processes();  // as counted (0: not counted)
// Whether this process has a core to spare: its affinity allows more than
// one CPU and its node has more online CPUs than the job's processes there
// (as counted, else comm's ranks on it; collective on comm).
bool core_to_spare_here(MPI_Comm comm);

class RunSession {
 public:
  struct Options {
    double duration = 0;  // [s]
    long snapshot_every = 0, checkpoint_every = 0;
    bool keep_dropper_forces = true;
    RecordBatches record_batches = RecordBatches::automatic;
    RecordThread record_thread = RecordThread::automatic;
    bool energy = false;              // E(t) and the powers every step (output.energy)
    std::string checkpoint_file;      // in the partial output folder
    std::vector<InputFile> inputs;    // fingerprint stored in checkpoints
    double modal_cutoff_hz = 0;       // stored in checkpoints (0: an FE level)
    MovingWindow* window = nullptr;   // scene key 'window': shifts after steps, line records
    RunObserver* observer = nullptr;  // sees every record
  };
  // stream: rank 0's results.h5 (null on the other ranks). restart: the
  // checkpoint the run continues from (null for a new run).
  // stop: installed by the caller before results.h5 exists, so that a signal
  // from then on stops the run at its next step (null: signals are not caught).
  RunSession(const Context& ctx, assembly::CoupledSystem& system, solvers::DynamicSolver& solver,
             output::RunStream* stream, Options options, const RunCheckpoint* restart,
             const GracefulStop* stop);

  // TSSolve with the monitor and the stop check installed. Returns the signal
  // that stopped the run (0: it ended by itself). A result that cannot be
  // written (results.h5, a checkpoint) stops the run on every rank at the
  // next step: OutputError on rank 0, FailedOnOtherRank(5) on the others. A
  // state that is not finite stops it with a SolverError naming the inputs
  // that usually cause it.
  int integrate();
  // After integrate(): writes a checkpoint at the last step unless there is
  // one already (collective). False for a TS type that cannot be checkpointed
  // and with a moving window.
  bool checkpoint_last_step();
  // True if the run stopped before its final time (signal, -ts_max_steps).
  bool stopped_early() const;

  // Performance and solver facts for summary.json and the console (collective).
  nlohmann::json facts() const;
  long steps() const { return steps_; }
  const StepTiming& timing() const { return timing_; }
  output::RunStream* stream() const { return stream_; }
  double time() const { return time_; }

 private:
  static PetscErrorCode monitor(TS ts, PetscInt step, PetscReal t, Vec U, void* ptr);
  static PetscErrorCode post_step(TS ts);
  bool record(TS ts, PetscInt step, PetscReal t, Vec U);  // true: results.h5 was flushed
  void deliver(contact::StepRecord& rec, const output::EnergySample& energy);  // observer, stream
  void complete_pending_records();                                             // collective
  void start_computing_records();                                              // collective
  void finish_computing_records();                                             // collective
  using PendingRecord = std::pair<contact::StepRecord, output::EnergySample>;
  void deliver_batch(std::vector<PendingRecord>& batch,
                     assembly::CatenaryModel::RecordQuantities quantities);  // collective
  void time_step(long step, double start, long newton_iterations);
  long rejected_steps() const;  // earlier runs included
  void print_progress(PetscInt step, PetscReal t) const;
  void write_checkpoint();
  bool hold_output_failure(std::exception_ptr error);  // false: not an output failure
  bool agreed_output_failure() const;                  // collective
  void raise_output_failure() const;                   // collective: throws if any rank failed
  bool state_finite_here(TS ts) const;                 // this rank's part of the state
  double wall_time() const;                            // of the integration, earlier runs included

  const Context& ctx_;
  assembly::CoupledSystem& system_;
  solvers::DynamicSolver& solver_;
  output::RunStream* stream_;
  Options options_;
  const GracefulStop* stop_;
  int stop_signal_ = 0;
  long first_step_ = 0;             // step the integration starts from
  bool skip_first_record_ = false;  // a restart's first step is in results.h5 already
  long steps_ = 0, newton_iterations_ = 0, earlier_rejected_ = 0, last_checkpoint_ = -1;
  double time_ = 0, start_time_ = 0, earlier_wall_ = 0, wall_start_ = 0;
  mutable double last_print_ = 0;
  long debug_signal_step_ = -1;  // -pcsim_debug_signal_step: raise SIGTERM there (tests)
  int debug_signal_rank_ = -1;   // on this rank only (-1: every rank)
  std::string path_;             // "cheap" or "full"
  StepCpuPin step_cpu_;          // -pcsim_step_cpu (step_cpu.hpp)
  StepTiming timing_;            // this process's steps (a restart's earlier ones are not in it)
  double step_end_ = -1;         // when the previous step's record ended [s]
  // Counts whose changes over a step are its events (StepEvents).
  struct StepCounters {
    long reference_builds = 0, involuntary_switches = 0, page_faults = 0, window_shifts = 0;
    long rank_one_set_changes = 0, capacitance_rows = 0;  // the cheap path's
    long exact_dropper_anchors = 0;                       // a reduced catenary's
  };
  StepCounters counters_now() const;
  StepCounters counted_;                            // at the previous step's end
  const assembly::ModalCatenary* modal_ = nullptr;  // a reduced catenary
  bool flushed_ = false;                            // the previous record flushed results.h5
  bool batch_beside_ = false;          // a records' batch was computing on its thread after it
  std::exception_ptr output_failure_;  // this rank's OutputError (or its FailedOnOtherRank)
  // Some rank's output failed, as every rank agreed after a step: from then
  // on no rank records. (Only rank 0 writes: a test of output_failure_ would
  // let the other ranks into the record's collectives alone, and hang.)
  bool output_stopped_ = false;
  bool not_finite_ = false;  // the state became NaN or inf
  double not_finite_time_ = 0;
  // Records waiting for their support heights and dropper forces (a reduced
  // catenary computes them for kRecordBatch states at once).
  static constexpr std::size_t kRecordBatch = 32;
  bool batch_records_ = false;
  std::vector<PendingRecord> pending_;
  // The batch before, whose product runs on its own thread (record_thread_):
  // delivered when the next batch is full, or at a snapshot, a checkpoint or
  // the run's end, before the records that follow it.
  bool record_thread_ = false;
  std::vector<PendingRecord> computing_;
  std::future<assembly::CatenaryModel::RecordQuantities> computing_job_;
};

// After TSSolve returned 'solved': a failed step is a SolverError naming the
// step, the last time reached and the inputs that usually cause it (then
// 'also_check'); another PETSc error is thrown as such.
void raise_if_step_failed(TS ts, PetscErrorCode solved, double last_time,
                          const std::string& also_check);

// The SolverError of a state that is not finite at time t: names the inputs
// that usually cause it.
std::string not_finite_message(double t);

}  // namespace pcsim::simulation
