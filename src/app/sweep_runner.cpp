#include "sweep_runner.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <map>

#include "pcsim/core/error.hpp"
#include "pcsim/output/modal_cache.hpp"
#include "pcsim/output/output_dir.hpp"
#include "pcsim/output/sweep_journal.hpp"
#include "pcsim/simulation/interrupt.hpp"
#include "processes.hpp"

namespace pcsim::app {

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using nlohmann::json;

// After SIGINT/SIGTERM, the running cases get this long to stop at their
// next step (checkpoint written) before they are killed; a second signal
// kills them at once.
constexpr double kStopGraceS = 30;

std::string number_text(double v) {
  char s[32];
  std::snprintf(s, sizeof s, "%.10g", v);
  return s;
}

// Environment variables of an MPI launcher, which a case must not inherit
// (it would take itself for this process).
const std::vector<std::string> kLauncherVariables = {"OMPI_COMM_WORLD",
                                                     "OMPI_MCA_orte",
                                                     "OMPI_MCA_ess",
                                                     "OMPI_MCA_pmix",
                                                     "OMPI_MCA_initial_wdir",
                                                     "OMPI_MCA_shmem",
                                                     "OMPI_MCA_mpi_oversubscribe",
                                                     "OMPI_FILE_LOCATION",
                                                     "OMPI_UNIVERSE_SIZE",
                                                     "OMPI_COMMAND",
                                                     "OMPI_ARGV",
                                                     "OMPI_NUM_APP_CTX",
                                                     "OMPI_FIRST_RANKS",
                                                     "OMPI_APP_CTX",
                                                     "PMIX_",
                                                     "PMI_"};

}  // namespace

std::vector<std::string> case_command(const CommandContext& ctx, const SweepPlan& plan,
                                      std::size_t k, const std::string& folder) {
  std::vector<std::string> argv;
  const std::string ranks = ctx.options.count("--ranks") ? ctx.options.at("--ranks") : "1";
  if (ranks != "1") argv = {PCSIM_MPIEXEC, "-n", ranks};
  argv.insert(argv.end(), {own_executable(), "run", ctx.scene_path, "-o", folder, "--no-report"});
  if (ctx.cache_dir != output::kDefaultCacheDir)  // the sweep's cache folder (was: the default)
    argv.insert(argv.end(), {"--cache", ctx.cache_dir});
  for (const auto& o : plan.fixed) argv.insert(argv.end(), {"--set", o});
  for (const auto& a : plan.assignments[k]) argv.insert(argv.end(), {"--set", a});
  // The cases' figures are the sweep's result: no accuracy pilot per case
  // unless asked for (-pcsim_accuracy_pilot true on the sweep's command line).
  if (std::find(ctx.petsc_arguments.begin(), ctx.petsc_arguments.end(), "-pcsim_accuracy_pilot") ==
      ctx.petsc_arguments.end())
    argv.insert(argv.end(), {"-pcsim_accuracy_pilot", "false"});
  argv.insert(argv.end(), ctx.petsc_arguments.begin(), ctx.petsc_arguments.end());
  return argv;
}

json read_case_summary(const std::string& folder, int status) {
  std::ifstream summary(folder + "/summary.json");
  if (status != 0 || !summary) return nullptr;
  json parsed = json::parse(summary, nullptr, false);
  return parsed.is_discarded() ? json(nullptr) : parsed;
}

std::string case_line(const output::SweepCase& c) {
  if (c.status != 0)
    return "failed (exit " + std::to_string(c.status) + (c.error.empty() ? "" : ": " + c.error) +
           "), see cases/" + c.name + ".log";
  std::string line = "ok";
  for (const auto& p : c.summary.value("pantographs", json::array()))
    if (p.contains("std_N"))
      line += ", " + p.value("name", std::string()) + ": mean " +
              number_text(std::round(10 * p["mean_N"].get<double>()) / 10) + " N, sigma " +
              number_text(std::round(10 * p["std_N"].get<double>()) / 10) + " N";
  return line;
}

// The journal line of a finished case.
json journal_entry(const SweepPlan& plan, std::size_t k) {
  const auto& c = plan.cases[k];
  json values = json::object();
  for (const auto& [key, value] : c.values) values[key] = value;
  std::vector<std::string> overrides = plan.fixed;
  overrides.insert(overrides.end(), plan.assignments[k].begin(), plan.assignments[k].end());
  json summary = c.summary;
  if (summary.is_object()) summary.erase("provenance");  // in cases/<case>/summary.json
  return {{"case", c.name},         {"index", k},         {"values", values},
          {"overrides", overrides}, {"status", c.status}, {"error", c.error},
          {"wall_s", c.wall_s},     {"cpu_s", c.cpu_s},   {"finished", output::utc_timestamp()},
          {"summary", summary}};
}

namespace {

// The plan's cases as the journal has them (a case it lacks: status -1);
// the number of cases found. A line of another case list is left out.
std::size_t load_journal(SweepPlan& plan, const output::SweepJournal& journal) {
  for (auto& c : plan.cases) {
    c.status = -1;
    c.summary = nullptr;
    c.error.clear();
    c.wall_s = c.cpu_s = 0;
  }
  std::size_t found = 0;
  for (const auto& e : journal.entries) {
    try {
      const std::size_t k = e.at("index").get<std::size_t>();
      if (k >= plan.cases.size() || plan.cases[k].name != e.at("case").get<std::string>() ||
          plan.cases[k].status >= 0)
        continue;
      auto& c = plan.cases[k];
      c.status = e.at("status").get<int>();
      c.summary = e.value("summary", json());
      c.error = e.value("error", std::string());
      c.wall_s = e.value("wall_s", 0.0);
      c.cpu_s = e.value("cpu_s", 0.0);
      ++found;
    } catch (const json::exception&) {
      continue;  // not a line of this sweep's cases
    }
  }
  return found;
}

output::SweepJournal read_journal(const std::string& file) {
  output::SweepJournal journal;
  std::string why;
  if (!output::read_sweep_journal(file, journal, why)) throw OutputError(file, why);
  return journal;
}

}  // namespace

void discard_case_leftovers(const std::string& folder) {
  const std::string partial = folder + ".partial";
  std::error_code ec;
  if (!fs::exists(partial + "/.pcsim-result", ec)) return;
  const int fd = open((folder + ".pcsim-lock").c_str(), O_RDONLY | O_CLOEXEC);
  const bool held = fd >= 0 && flock(fd, LOCK_EX | LOCK_NB) != 0;
  if (fd >= 0) close(fd);
  if (!held) fs::remove_all(partial, ec);
}

output::OutputRequest::Leftover sweep_leftover(const std::string& partial, const std::string& definition,
                                       bool overwrite, std::string& why) {
  output::SweepJournal journal;
  std::string reason;
  if (!output::read_sweep_journal(partial + "/" + output::kSweepJournalName, journal, reason)) {
    why = "'" + partial + "' holds an interrupted pcsim result that cannot be resumed (" + reason +
          "); move it away or delete it, then run again";
    return output::OutputRequest::Leftover::refuse;
  }
  if (journal.header.value("definition", std::string()) == definition)
    return output::OutputRequest::Leftover::resume;
  if (overwrite) return output::OutputRequest::Leftover::replace;
  why = "'" + partial + "' holds an interrupted sweep of another definition (" +
        std::to_string(journal.entries.size()) + " of " +
        std::to_string(journal.header.value("cases", 0)) +
        " cases finished; the scene, the swept keys or values, the case table or the PETSc "
        "options differ), which a rerun of the same sweep would resume; give --overwrite to "
        "discard it, or another folder with -o";
  return output::OutputRequest::Leftover::refuse;
}

std::size_t open_sweep_journal(SweepPlan& plan, const output::OutputDir& out,
                               const std::string& definition) {
  const std::string file = out.file(output::kSweepJournalName);
  if (out.resumed()) output::merge_group_journals(file);  // an MPI sweep's group files
  if (!out.resumed()) {
    output::append_sweep_journal(file, {{"pcsim_sweep_journal", output::kSweepJournalVersion},
                                        {"definition", definition},
                                        {"cases", plan.cases.size()},
                                        {"started", output::utc_timestamp()}});
    return 0;
  }
  output::SweepJournal journal = read_journal(file);
  const std::size_t resumed = load_journal(plan, journal);
  // Written anew with the lines of this plan's cases only (a line torn by a kill is gone).
  std::vector<json> kept;
  for (std::size_t k = 0; k < plan.cases.size(); ++k)
    if (plan.cases[k].status >= 0)
      for (const auto& e : journal.entries)
        if (e.value("case", std::string()) == plan.cases[k].name) {
          kept.push_back(e);
          break;
        }
  journal.entries = kept;
  output::rewrite_sweep_journal(file, journal);
  return resumed;
}

namespace {

// A case's process: which case, since when.
struct RunningCase {
  std::size_t index;
  Clock::time_point start;
};

class Runner {
 public:
  Runner(const CommandContext& ctx, SweepPlan& plan, const output::OutputDir& out)
      : ctx_(ctx), plan_(plan), out_(out), journal_(out.file(output::kSweepJournalName)) {
    for (std::size_t k = 0; k < plan.cases.size(); ++k)
      if (plan.cases[k].status < 0) todo_.push_back(k);
    done_ = plan.cases.size() - todo_.size();
  }
  int run(int jobs);
  // SIGINT/SIGTERM (or an error): no new case starts, the running ones get
  // the signal (each stops at its next step, its data and checkpoint kept in
  // its .partial folder) and are waited for, killed after kStopGraceS or a
  // second signal. A case that ends with exit 0 meanwhile is journaled.
  void stop_running(int signal_number);

 private:
  void start_case(std::size_t k);
  void finished(pid_t pid, int status, double cpu_s, bool stopping);

  const CommandContext& ctx_;
  SweepPlan& plan_;
  const output::OutputDir& out_;
  std::string journal_;
  std::vector<std::size_t> todo_;
  std::map<pid_t, RunningCase> running_;
  std::size_t done_ = 0;
  Clock::time_point start_ = Clock::now();
};

void Runner::start_case(std::size_t k) {
  const std::string cases = out_.file("cases");
  const std::string folder = cases + "/" + plan_.cases[k].name;
  fs::create_directories(cases);
  discard_case_leftovers(folder);
  const pid_t pid =
      start_process(case_command(ctx_, plan_, k, folder), folder + ".log", kLauncherVariables);
  running_[pid] = {k, Clock::now()};
}

void Runner::finished(pid_t pid, int status, double cpu_s, bool stopping) {
  const auto it = running_.find(pid);
  if (it == running_.end()) return;  // not a case (the MPI singleton's helper)
  const RunningCase rc = it->second;
  running_.erase(it);
  if (stopping && status != 0) return;  // interrupted: not finished, runs again on a resume
  auto& c = plan_.cases[rc.index];
  c.status = status;
  const std::string folder = out_.file("cases") + "/" + c.name;
  c.summary = read_case_summary(folder, status);
  c.error = status == 0 ? "" : last_line_of(folder + ".log");
  const auto now = Clock::now();
  c.wall_s = std::chrono::duration<double>(now - rc.start).count();
  c.cpu_s = cpu_s;
  output::append_sweep_journal(journal_, journal_entry(plan_, rc.index));
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  print0(ctx_, "  [%zu/%zu] %s: %s (%.1f s; %.0f s since the sweep began)\n", ++done_,
         plan_.cases.size(), c.name.c_str(), case_line(c).c_str(), c.wall_s, elapsed);
}

void Runner::stop_running(int signal_number) {
  sigset_t signals, previous;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &signals, &previous);
  print0(ctx_, "  %s: stopping %zu running case(s)\n", simulation::signal_name(signal_number),
         running_.size());
  for (const auto& [pid, c] : running_) kill(pid, signal_number);
  const auto deadline = Clock::now() + std::chrono::duration<double>(kStopGraceS);
  bool killed = false;
  while (!running_.empty()) {
    int status = 0;
    double cpu_s = 0;
    const pid_t pid = poll_any_process(status, &cpu_s);
    if (pid < 0) break;
    if (pid > 0) {
      try {
        finished(pid, status, cpu_s, true);
      } catch (const std::exception& e) {  // not journaled: it runs again on a resume
        std::fprintf(stderr, "pcsim: warning: %s\n", e.what());
      }
      continue;
    }
    timespec tick{0, 50000000};
    const bool again = sigtimedwait(&signals, nullptr, &tick) > 0;
    if (!killed && (again || Clock::now() > deadline)) {
      print0(ctx_, "  killing %zu case(s)\n", running_.size());
      for (const auto& [p, c] : running_) kill(p, SIGKILL);
      killed = true;
    }
  }
  timespec none{0, 0};
  while (sigtimedwait(&signals, nullptr, &none) > 0) {
  }
  pthread_sigmask(SIG_SETMASK, &previous, nullptr);
}

int Runner::run(int jobs) {
  simulation::GracefulStop stop;
  const auto stop_asked = [&] { return stop.agreed_signal(MPI_COMM_SELF) != 0; };
  std::size_t next = 0;
  try {
    while (next < todo_.size() || !running_.empty()) {
      while (next < todo_.size() && static_cast<int>(running_.size()) < jobs && !stop_asked())
        start_case(todo_[next++]);
      int status = 0;
      double cpu_s = 0;
      const pid_t pid = running_.empty() || stop_asked()
                            ? kWaitStopped
                            : wait_any_process(status, stop_asked, &cpu_s);
      if (pid == kWaitStopped) {
        const int signal_number = stop.agreed_signal(MPI_COMM_SELF);
        stop_running(signal_number);
        return signal_number;
      }
      if (pid < 0) throw std::runtime_error("the sweep lost its case processes");
      finished(pid, status, cpu_s, false);
    }
  } catch (...) {
    stop_running(SIGTERM);  // no case left running behind an error
    throw;
  }
  return 0;
}

}  // namespace

int run_sweep_cases(const CommandContext& ctx, SweepPlan& plan, const output::OutputDir& out, int jobs) {
  Runner runner(ctx, plan, out);
  if (const int signal_number = runner.run(jobs)) return signal_number;
  fill_cases_from_journal(plan, out);
  return 0;
}

void fill_cases_from_journal(SweepPlan& plan, const output::OutputDir& out) {
  const std::size_t found = load_journal(plan, read_journal(out.file(output::kSweepJournalName)));
  if (found != plan.cases.size())
    throw OutputError(out.file(output::kSweepJournalName),
                      "it holds " + std::to_string(found) + " of the " +
                          std::to_string(plan.cases.size()) + " cases");
}

}  // namespace pcsim::app
