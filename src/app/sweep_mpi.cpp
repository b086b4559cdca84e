#include "sweep_mpi.hpp"

#include <fcntl.h>
#include <petscsys.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <memory>

#include "exit_status.hpp"
#include "pcsim/core/error.hpp"
#include "pcsim/core/vec_root.hpp"
#include "pcsim/output/sweep_journal.hpp"
#include "pcsim/simulation/interrupt.hpp"
#include "pcsim/solvers/command_line.hpp"
#include "processes.hpp"

namespace pcsim::app {

namespace {

using Clock = std::chrono::steady_clock;

// Declared in an options block so that -help lists it and PETSc counts it read.
PetscErrorCode read_ranks_per_case(MPI_Comm comm, char* text, std::size_t size, PetscBool* set) {
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, nullptr, "pcsim sweep under mpirun (docs/cluster.md)", "pcsim");
  PetscCall(PetscOptionsString(kRanksPerCaseOption,
                               "MPI ranks of each case (a divisor of the ranks)", "pcsim sweep",
                               text, text, size, set));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}

// Debugging aid for tests/studies/test_sweep_mpi.sh: the group rank that
// fails alone as each case starts (-1: none). Declared so that -help lists it.
PetscErrorCode read_case_fail_rank(MPI_Comm comm, PetscInt* rank) {
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, nullptr, "pcsim sweep tests", "pcsim");
  PetscCall(PetscOptionsInt("-pcsim_debug_case_fail_rank",
                            "group rank that fails alone as each case starts", "", *rank, rank,
                            nullptr));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}

// This process's stdout and stderr into a file for its lifetime (a case's
// log); left as they are if the file cannot be made (the case's run, on every
// rank of its group, says why its folder cannot be written).
class ConsoleToFile {
 public:
  explicit ConsoleToFile(const std::string& path) {
    std::fflush(stdout);
    std::fflush(stderr);
    const int fd = open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0) return;
    out_ = dup(STDOUT_FILENO);
    err_ = dup(STDERR_FILENO);
    dup2(fd, STDOUT_FILENO);
    dup2(fd, STDERR_FILENO);
    close(fd);
  }
  ~ConsoleToFile() {
    if (out_ < 0) return;
    std::fflush(stdout);
    std::fflush(stderr);
    dup2(out_, STDOUT_FILENO);
    dup2(err_, STDERR_FILENO);
    close(out_);
    close(err_);
  }
  ConsoleToFile(const ConsoleToFile&) = delete;
  ConsoleToFile& operator=(const ConsoleToFile&) = delete;

 private:
  int out_ = -1, err_ = -1;
};

// How a case ended, agreed by its group.
struct CaseEnd {
  int status = 0;
  std::string error;  // the failure's message, on the group's first rank
  double wall_s = 0, cpu_s = 0;
};

class GroupRunner {
 public:
  GroupRunner(const CommandContext& ctx, SweepPlan& plan, const output::OutputDir& out,
              int ranks_per_case);
  ~GroupRunner();
  GroupRunner(const GroupRunner&) = delete;
  GroupRunner& operator=(const GroupRunner&) = delete;
  int run();

 private:
  long fetch_add(int slot);  // the counter's value before adding one
  long claim(const simulation::GracefulStop& stop, int& stopped_by);
  CommandContext case_context(std::size_t k, const std::string& folder) const;
  CaseEnd run_case(std::size_t k);
  void journal(std::size_t k, const CaseEnd& end);

  const CommandContext& ctx_;
  SweepPlan& plan_;
  const output::OutputDir& out_;
  MPI_Comm group_ = MPI_COMM_NULL;
  MPI_Comm agreement_ = MPI_COMM_NULL;  // group_'s ranks, for a case's end only
  int group_index_ = 0, group_rank_ = 0;
  PetscInt debug_fail_rank_ = -1;
  MPI_Win window_ = MPI_WIN_NULL;  // on world rank 0: {next case to claim, cases finished}
  long* counters_ = nullptr;
  std::vector<std::size_t> todo_;
  std::size_t resumed_ = 0;
  Clock::time_point start_ = Clock::now();
};

GroupRunner::GroupRunner(const CommandContext& ctx, SweepPlan& plan, const output::OutputDir& out,
                         int ranks_per_case)
    : ctx_(ctx), plan_(plan), out_(out) {
  group_index_ = ctx.rank / ranks_per_case;
  MPI_Comm_split(ctx.comm, group_index_, ctx.rank, &group_);
  MPI_Comm_rank(group_, &group_rank_);
  MPI_Comm_dup(group_, &agreement_);
  PCSIM_PETSC(read_case_fail_rank(ctx.comm, &debug_fail_rank_));
  const MPI_Aint bytes = ctx.rank == 0 ? 2 * sizeof(long) : 0;
  MPI_Win_allocate(bytes, sizeof(long), MPI_INFO_NULL, ctx.comm, &counters_, &window_);
  if (ctx.rank == 0) {
    MPI_Win_lock(MPI_LOCK_EXCLUSIVE, 0, 0, window_);
    counters_[0] = counters_[1] = 0;
    MPI_Win_unlock(0, window_);
  }
  for (std::size_t k = 0; k < plan.cases.size(); ++k)
    if (plan.cases[k].status < 0) todo_.push_back(k);
  resumed_ = plan.cases.size() - todo_.size();
  MPI_Barrier(ctx.comm);  // the counters are set before anyone claims
}

GroupRunner::~GroupRunner() {
  // An error on one rank (a journal that cannot be written): no collective
  // here, main's agree_exit_status ends the job (exit_status.hpp).
  if (std::uncaught_exceptions() > 0) return;
  MPI_Win_free(&window_);
  MPI_Comm_free(&agreement_);
  MPI_Comm_free(&group_);
}

long GroupRunner::fetch_add(int slot) {
  const long one = 1;
  long before = 0;
  MPI_Win_lock(MPI_LOCK_SHARED, 0, 0, window_);
  MPI_Fetch_and_op(&one, &before, MPI_LONG, 0, slot, MPI_SUM, window_);
  MPI_Win_unlock(0, window_);
  return before;
}

// The group's next case (-1: none left, or a signal came), decided by its first rank.
long GroupRunner::claim(const simulation::GracefulStop& stop, int& stopped_by) {
  long k = -1;
  if (group_rank_ == 0) {
    stopped_by = stop.agreed_signal(MPI_COMM_SELF);
    const long next = stopped_by ? -1 : fetch_add(0);
    if (next >= 0 && static_cast<std::size_t>(next) < todo_.size()) k = todo_[next];
  }
  MPI_Bcast(&k, 1, MPI_LONG, 0, group_);
  return k;
}

// `pcsim run SCENE -o cases/<case> --no-report --set ...` with the sweep's PETSc options.
CommandContext GroupRunner::case_context(std::size_t k, const std::string& folder) const {
  CommandContext c = ctx_;
  c.comm = group_;
  c.rank = group_rank_;
  MPI_Comm_size(group_, &c.size);
  c.command = "run";
  c.output_dir = folder;
  c.overwrite = false;
  c.cleanup_on_signal = false;  // a signal stops the case at its next step (GroupRunner::run)
  c.options = {{"--no-report", ""}};
  c.overrides = plan_.fixed;
  c.overrides.insert(c.overrides.end(), plan_.assignments[k].begin(), plan_.assignments[k].end());
  c.arguments = case_command(ctx_, plan_, k, folder);  // (no --ranks under mpirun)
  return c;
}

CaseEnd GroupRunner::run_case(std::size_t k) {
  const std::string folder = out_.file("cases") + "/" + plan_.cases[k].name;
  if (group_rank_ == 0) discard_case_leftovers(folder);
  const CommandContext c = case_context(k, folder);
  const auto start = Clock::now();
  const double cpu_start = own_cpu_seconds();
  CaseEnd end;
  std::string message;
  {
    std::unique_ptr<ConsoleToFile> log;
    if (group_rank_ == 0) log = std::make_unique<ConsoleToFile>(folder + ".log");
    try {
      if (group_rank_ == debug_fail_rank_)
        throw SolverError("debug failure of a case on group rank " + std::to_string(group_rank_));
      end.status = run_scene_command(c);
    } catch (...) {
      end.status = exit_status_of(std::current_exception(), c, message);
    }
    // A rank that failed alone may leave the others in a collective of the
    // case: after 10 s it ends the job (a resumable sweep) with its message.
    wait_for_ranks_or_abort(agreement_, end.status, message, end.status != 0);
    const AgreedStatus agreed = agree_status(group_, end.status, !message.empty());
    end.status = agreed.status;
    if (agreed.message_rank >= 0) end.error = broadcast_text(group_, message, agreed.message_rank);
    if (group_rank_ == 0 && !end.error.empty()) std::fprintf(stderr, "%s\n", end.error.c_str());
  }
  end.wall_s = std::chrono::duration<double>(Clock::now() - start).count();
  const double cpu = own_cpu_seconds() - cpu_start;
  MPI_Reduce(&cpu, &end.cpu_s, 1, MPI_DOUBLE, MPI_SUM, 0, group_);
  return end;
}

// The group's first rank: the finished case into the group's journal, then a progress line.
void GroupRunner::journal(std::size_t k, const CaseEnd& end) {
  auto& c = plan_.cases[k];
  c.status = end.status;
  c.error = end.error;
  c.wall_s = end.wall_s;
  c.cpu_s = end.cpu_s;
  c.summary = read_case_summary(out_.file("cases") + "/" + c.name, end.status);
  output::append_sweep_journal(out_.file(output::group_journal_name(group_index_)),
                               journal_entry(plan_, k));
  const std::size_t done = resumed_ + static_cast<std::size_t>(fetch_add(1)) + 1;
  const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
  std::printf("  [%zu/%zu] %s: %s (%.1f s; %.0f s since the sweep began; group %d)\n", done,
              plan_.cases.size(), c.name.c_str(), case_line(c).c_str(), c.wall_s, elapsed,
              group_index_);
  std::fflush(stdout);
}

int GroupRunner::run() {
  simulation::GracefulStop stop;
  int stopped_by = 0;
  for (long k; (k = claim(stop, stopped_by)) >= 0;) {
    const CaseEnd end = run_case(static_cast<std::size_t>(k));
    const int signal_number = stop.agreed_signal(group_);
    if (signal_number != 0 && end.status != 0) {  // stopped: runs again on a resume
      stopped_by = signal_number;
      break;
    }
    if (group_rank_ == 0) journal(static_cast<std::size_t>(k), end);
  }
  int agreed = 0;
  MPI_Allreduce(&stopped_by, &agreed, 1, MPI_INT, MPI_MAX, ctx_.comm);
  return agreed;
}

}  // namespace

int sweep_ranks_per_case(const CommandContext& ctx) {
  char text[64] = "1";
  PetscBool set = PETSC_FALSE;
  PCSIM_PETSC(read_ranks_per_case(ctx.comm, text, sizeof text, &set));
  const long k = solvers::parse_int_option(kRanksPerCaseOption, text);
  if (k < 1 || ctx.size % k != 0)
    throw InputError("command line", kRanksPerCaseOption,
                     std::to_string(k) + " does not divide the " + std::to_string(ctx.size) +
                         " rank(s) of this sweep: the ranks are split into groups of this many, "
                         "one case per group (give a divisor of mpirun's -n)");
  return static_cast<int>(k);
}

int run_sweep_cases_mpi(const CommandContext& ctx, SweepPlan& plan, const output::OutputDir& out,
                        int ranks_per_case) {
  on_rank0(ctx, [&] { std::filesystem::create_directories(out.file("cases")); });
  // As the local mode's case processes (case_command): no accuracy pilot per
  // case unless the sweep asks for one; the cases read this process's options.
  PetscBool pilot_given = PETSC_FALSE;
  PCSIM_PETSC(PetscOptionsHasName(nullptr, nullptr, "-pcsim_accuracy_pilot", &pilot_given));
  if (!pilot_given) PCSIM_PETSC(PetscOptionsSetValue(nullptr, "-pcsim_accuracy_pilot", "false"));
  int signal_number = 0;
  {
    GroupRunner runner(ctx, plan, out, ranks_per_case);
    signal_number = runner.run();
  }
  on_rank0(ctx, [&] { output::merge_group_journals(out.file(output::kSweepJournalName)); });
  return signal_number;
}

}  // namespace pcsim::app
