// Exit codes, the same on every rank, and no hang when only some ranks fail.
//   0 success, 2 input error, 3 solver failure, 4 internal error, 5 output
// not written (README "Exit codes").
// Errors found identically on every rank (bad input: every rank reads the
// scene) end the job normally with one message. Work done by rank 0 alone
// goes through on_rank0(), which broadcasts its outcome. Anything else that
// fails on some ranks only is caught by agree_exit_status(): the failing rank
// prints its message and calls MPI_Abort with its code (mpirun returns it).
#pragma once

#include <mpi.h>

#include <exception>
#include <functional>
#include <stdexcept>
#include <string>

#include "command.hpp"

namespace pcsim::app {

using simulation::FailedOnOtherRank;
using simulation::kExitInput;
using simulation::kExitInternal;
using simulation::kExitOutput;
using simulation::kExitSolver;

// Exit status of an exception (simulation::exit_status_of), and the line to
// print for it ("" for FailedOnOtherRank).
int exit_status_of(std::exception_ptr error, const CommandContext& ctx, std::string& message);

// Collective on 'comm' (a communicator used for nothing else): returns the
// status all ranks exit with, the highest one, after printing its message once.
// A rank that failed ('failed_here') waits at most 'timeout_s' for the others:
// if some rank is stuck in a collective of the failed work, it prints its
// message and calls MPI_Abort(MPI_COMM_WORLD, status), which does not return.
int agree_exit_status(MPI_Comm comm, int status, const std::string& message, bool failed_here,
                      double timeout_s = 10.0);

// Every rank of 'comm' together: the highest status, and the lowest rank
// with that status that has a message (-1: none has one).
struct AgreedStatus {
  int status = 0;
  int message_rank = -1;
};
AgreedStatus agree_status(MPI_Comm comm, int status, bool has_message);

// The first half of agree_exit_status: returns once every rank of 'comm' is
// here; a rank that failed and waited 'timeout_s' in vain ends the job so.
void wait_for_ranks_or_abort(MPI_Comm comm, int status, const std::string& message,
                             bool failed_here, double timeout_s = 10.0);

// Debugging aid for the tests of the above: with
//   -pcsim_debug_fail_rank R -pcsim_debug_fail_class input|solver|internal
// rank R alone throws that class of error as the command starts.
void debug_fail_if_asked(const CommandContext& ctx);

}  // namespace pcsim::app
