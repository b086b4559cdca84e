#include "exit_status.hpp"

#include <petscsys.h>
#include <unistd.h>

#include <cstdio>

#include "pcsim/core/error.hpp"

namespace pcsim::app {

int exit_status_of(std::exception_ptr error, const CommandContext& ctx, std::string& message) {
  const std::string where = ctx.size > 1 ? " (rank " + std::to_string(ctx.rank) + ")" : "";
  try {
    std::rethrow_exception(error);
  } catch (const FailedOnOtherRank& e) {
    message.clear();
    return e.status();
  } catch (const InputError& e) {
    message = std::string("pcsim: error: ") + e.what();
    return kExitInput;
  } catch (const OutputError& e) {
    message = std::string("pcsim: error: ") + e.what();
    return kExitOutput;
  } catch (const SolverError& e) {
    message = "pcsim: solver failure" + where + ": " + e.what();
    return kExitSolver;
  } catch (const std::exception& e) {
    message = "pcsim: internal error" + where + ": " + e.what();
    return kExitInternal;
  } catch (...) {
    message = "pcsim: internal error" + where + ": unknown exception";
    return kExitInternal;
  }
}

void wait_for_ranks_or_abort(MPI_Comm comm, int status, const std::string& message,
                             bool failed_here, double timeout_s) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  MPI_Request arrived;
  MPI_Ibarrier(comm, &arrived);
  const double deadline = MPI_Wtime() + timeout_s;
  for (int done = 0;;) {
    MPI_Test(&arrived, &done, MPI_STATUS_IGNORE);
    if (done) break;
    if (failed_here && MPI_Wtime() > deadline) {
      // Another rank is stuck in a collective that this one left.
      if (!message.empty()) std::fprintf(stderr, "%s\n", message.c_str());
      std::fprintf(stderr, "  (rank %d: other ranks did not stop within %.0f s; ending the job)\n",
                   rank, timeout_s);
      std::fflush(stderr);
      MPI_Abort(MPI_COMM_WORLD, status);
    }
    usleep(1000);
  }
}

AgreedStatus agree_status(MPI_Comm comm, int status, bool has_message) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  // The highest status wins, with its lowest rank that has a message
  // (MPI_MAXLOC takes the lowest rank among equals).
  struct {
    int key, rank;
  } mine{2 * status + (has_message ? 1 : 0), rank}, agreed{0, 0};
  MPI_Allreduce(&mine, &agreed, 1, MPI_2INT, MPI_MAXLOC, comm);
  return {agreed.key / 2, agreed.key % 2 ? agreed.rank : -1};
}

int agree_exit_status(MPI_Comm comm, int status, const std::string& message, bool failed_here,
                      double timeout_s) {
  wait_for_ranks_or_abort(comm, status, message, failed_here, timeout_s);
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const AgreedStatus agreed = agree_status(comm, status, !message.empty());
  if (agreed.message_rank == rank) std::fprintf(stderr, "%s\n", message.c_str());
  std::fflush(stderr);
  return agreed.status;
}

// Declared (not only read) so that -help lists them.
static PetscErrorCode read_debug_options(MPI_Comm comm, PetscInt& rank, char* kind,
                                         std::size_t size) {
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, nullptr, "pcsim exit-code tests", "pcsim");
  PetscCall(PetscOptionsInt("-pcsim_debug_fail_rank", "rank that fails as the command starts", "",
                            rank, &rank, nullptr));
  PetscCall(PetscOptionsString("-pcsim_debug_fail_class", "its error: input, solver or internal",
                               "", kind, kind, size, nullptr));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}

void debug_fail_if_asked(const CommandContext& ctx) {
  PetscInt fail_rank = -1;
  char fail_class[16] = "";
  PCSIM_PETSC(read_debug_options(ctx.comm, fail_rank, fail_class, sizeof fail_class));
  if (fail_rank != ctx.rank) return;
  const std::string kind = fail_class;
  const std::string text = "debug failure on rank " + std::to_string(ctx.rank);
  if (kind == "input") throw InputError("command line", "-pcsim_debug_fail_class", text);
  if (kind == "solver") throw SolverError(text);
  throw std::runtime_error(text);
}

}  // namespace pcsim::app
