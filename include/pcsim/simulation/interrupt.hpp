// SIGINT and SIGTERM during the time integration of `pcsim run`: the signal
// only sets a flag; the run stops at the next step boundary on every rank
// together (agreed_signal() is collective: under mpirun the signal reaches
// the ranks at different moments), writes a checkpoint and keeps its partial
// folder. A second signal, a second or more after the first, ends the process
// at once, through the handler that was there before (the output folder's
// cleanup, output_dir.hpp); one sooner is the same request delivered twice.
// GracefulStops nest: an inner one (each case of an MPI sweep) keeps the
// outer one's handlers, and a signal caught before it was made.
#pragma once

#include <mpi.h>

namespace pcsim::simulation {

class GracefulStop {
 public:
  GracefulStop();   // installs the handlers (an inherited SIG_IGN is kept)
  ~GracefulStop();  // restores the earlier ones
  GracefulStop(const GracefulStop&) = delete;
  GracefulStop& operator=(const GracefulStop&) = delete;

  // The signal any rank has received (SIGINT or SIGTERM), 0 if none
  // (collective: one reduction).
  int agreed_signal(MPI_Comm comm) const;
  // This rank's own signal (no communication), for a caller that folds the
  // agreement into a reduction of its own.
  int local_signal() const;
};

// "SIGINT", "SIGTERM", or the number.
const char* signal_name(int signal_number);

}  // namespace pcsim::simulation
