// The accuracy pilot's linear FE runs in a second process, beside its other
// runs (accuracy_pilot.cpp): on one rank with a core to spare, the pilot's
// run at dt/2 and h/2 (and, before a modal pilot's, its run at the run's dt
// and h) need not wait for the modal runs, nor they for it. The second
// process is a fork of this one: it runs its pilot runs in turn, writes each
// one's figures to a pipe as one line (the doubles exactly, in hexadecimal)
// and ends; a run that fails sends its error instead. It makes no MPI call
// that leaves the process (one rank: PETSc's collectives on a communicator of
// one) and dies with its parent (PR_SET_PDEATHSIG). Private to
// src/simulation.
#pragma once

#include <sys/types.h>

#include <functional>
#include <string>
#include <vector>

#include "pcsim/output/statistics.hpp"
#include "pcsim/simulation/context.hpp"

namespace pcsim::simulation {

// The figures of one pilot run, per pantograph (rank 0).
struct PilotFigures {
  std::vector<std::string> names;
  std::vector<output::ForceStatistics> force;
  double uplift_m = 0;
};

// Rank 0's figures on every rank of comm (collective): a pilot's decisions
// (raise the cut-off or not) must be the same on every rank.
PilotFigures broadcast_figures(MPI_Comm comm, const PilotFigures& figures);

// Whether this pilot's FE runs go to a second process (collective on ctx.comm).
bool use_pilot_process(const Context& ctx);
// True while a pilot's second process runs: it takes the core a run would
// otherwise spare for its record thread or a window shift's helper.
bool pilot_process_running();

class PilotProcess {
 public:
  using Run = std::function<PilotFigures()>;
  struct Result {
    PilotFigures figures;
    double seconds = 0;  // the run's wall time in the second process
  };
  // Forks the second process, which runs 'runs' in turn.
  explicit PilotProcess(std::vector<Run> runs);
  PilotProcess(const PilotProcess&) = delete;
  PilotProcess& operator=(const PilotProcess&) = delete;
  // A second process still running is killed (this one failed), and reaped.
  ~PilotProcess();
  // The next run's figures, when it has ended (blocks until then). A run
  // that failed throws its SolverError again (another error: a
  // std::runtime_error with its text); a process that ended without a
  // result, a SolverError.
  Result next();
  // Waits for the process to end after its last result; its peak resident
  // memory [MB].
  double finish();

 private:
  void reap(bool kill_first);
  pid_t pid_ = -1;
  int fd_ = -1;
  std::string buffer_;
  int last_status_ = 0;  // wait4's, once reaped
  double peak_mb_ = 0;
};

}  // namespace pcsim::simulation
