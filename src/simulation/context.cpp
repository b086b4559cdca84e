#include "pcsim/simulation/context.hpp"

#include <sys/resource.h>

#include <cstdarg>
#include <cstdio>

namespace pcsim::simulation {

Context Context::of(MPI_Comm comm) {
  Context ctx;
  ctx.comm = comm;
  MPI_Comm_rank(comm, &ctx.rank);
  MPI_Comm_size(comm, &ctx.size);
  return ctx;
}

int exit_status_of(std::exception_ptr error) {
  try {
    std::rethrow_exception(error);
  } catch (const FailedOnOtherRank& e) {
    return e.status();
  } catch (const InputError&) {
    return kExitInput;
  } catch (const SolverError&) {
    return kExitSolver;
  } catch (const OutputError&) {
    return kExitOutput;
  } catch (...) {
    return kExitInternal;
  }
}

void on_rank0(const Context& ctx, const std::function<void()>& work) {
  std::exception_ptr error;
  int status = 0;
  if (ctx.rank == 0) {
    try {
      work();
    } catch (...) {
      error = std::current_exception();
      status = exit_status_of(error);
    }
  }
  MPI_Bcast(&status, 1, MPI_INT, 0, ctx.comm);
  if (status == 0) return;
  if (ctx.rank == 0) std::rethrow_exception(error);
  throw FailedOnOtherRank(status);
}

void print0(const Context& ctx, const char* format, ...) {
  if (ctx.rank != 0 || ctx.quiet) return;
  va_list args;
  va_start(args, format);
  std::vfprintf(stdout, format, args);
  va_end(args);
  std::fflush(stdout);
}

void print_warnings(const Context& ctx, const std::vector<InputWarning>& warnings) {
  std::vector<std::string> texts;
  for (const auto& w : warnings) texts.push_back(w.message());
  print_warnings(ctx, texts);
}

void print_warnings(const Context& ctx, const std::vector<std::string>& warnings) {
  if (ctx.rank != 0) return;
  for (const auto& w : warnings) std::fprintf(stderr, "pcsim: warning: %s\n", w.c_str());
  std::fflush(stderr);
}

namespace {
// This process's peak resident memory, reduced over the ranks by op.
double reduced_peak_memory_mb(MPI_Comm comm, MPI_Op op) {
  struct rusage usage;
  getrusage(RUSAGE_SELF, &usage);
  double mb = usage.ru_maxrss / 1024.0, reduced = 0;
  MPI_Allreduce(&mb, &reduced, 1, MPI_DOUBLE, op, comm);
  return reduced;
}
}  // namespace

double peak_memory_mb(MPI_Comm comm) {
  return reduced_peak_memory_mb(comm, MPI_MAX);
}

double total_peak_memory_mb(MPI_Comm comm) {
  return reduced_peak_memory_mb(comm, MPI_SUM);
}

}  // namespace pcsim::simulation
