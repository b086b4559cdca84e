// What every procedure of the simulation part runs in: the communicator of
// the run (one case of a study may run on a subset of the ranks), the modal
// cache folder, and whether rank 0 prints progress. The command line of the
// `pcsim` executable (app/command.hpp) extends it; a library user makes one
// with Context::of(comm).
// Also the collective helpers for work done on rank 0 alone, and the peak
// memory of the ranks.
#pragma once

#include <mpi.h>

#include <exception>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "pcsim/core/error.hpp"

namespace pcsim::simulation {

struct Context {
  MPI_Comm comm = MPI_COMM_WORLD;
  int rank = 0;
  int size = 1;
  std::string cache_dir = "out/.pcsim-cache";  // modal bases (output/modal_cache.hpp)
  bool quiet = false;                          // no console lines (warnings still on stderr)
  // The context of 'comm' (rank and size from it).
  static Context of(MPI_Comm comm);
};

// Exit status of each class of error (README "Exit codes").
constexpr int kExitInput = 2;
constexpr int kExitSolver = 3;
constexpr int kExitInternal = 4;
constexpr int kExitOutput = 5;  // a result file could not be written (OutputError)

// The exit status of an error: 2 InputError, 3 SolverError, 5 OutputError,
// 4 anything else.
int exit_status_of(std::exception_ptr error);

// Thrown on the ranks that stop because another rank failed; that rank
// carries the message, this one only the exit status.
class FailedOnOtherRank : public std::runtime_error {
 public:
  explicit FailedOnOtherRank(int status)
      : std::runtime_error("failed on another rank"), status_(status) {}
  int status() const { return status_; }

 private:
  int status_;
};

// Runs 'work' on rank 0 only (output files); if it throws, rank 0 rethrows and
// the other ranks throw FailedOnOtherRank with its status (collective).
void on_rank0(const Context& ctx, const std::function<void()>& work);

// printf on rank 0 unless ctx.quiet.
void print0(const Context& ctx, const char* format, ...);

// "pcsim: warning: ..." on stderr, rank 0.
void print_warnings(const Context& ctx, const std::vector<InputWarning>& warnings);
void print_warnings(const Context& ctx, const std::vector<std::string>& warnings);

// Largest peak resident memory of any rank [MB] (collective).
double peak_memory_mb(MPI_Comm comm);
// The sum over the ranks of their peak resident memory [MB] (collective).
double total_peak_memory_mb(MPI_Comm comm);

}  // namespace pcsim::simulation
