// The accuracy pilot's second process (pilot_process.hpp).
#include "pilot_process.hpp"

#include <petscsys.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "pcsim/core/error.hpp"
#include "pcsim/core/profiling.hpp"
#include "pcsim/core/vec_root.hpp"
#include "pcsim/simulation/accuracy_pilot.hpp"
#include "pcsim/simulation/auto_option.hpp"
#include "pcsim/simulation/run_session.hpp"

namespace pcsim::simulation {

namespace {

std::atomic<bool> g_running{false};

// A double exactly, NaN and infinities included ("%a": strtod reads it back).
std::string exact(double v) {
  char text[48];
  std::snprintf(text, sizeof text, "%a", v);
  return text;
}

double from_exact(const nlohmann::json& j) {
  return std::strtod(j.get<std::string>().c_str(), nullptr);
}

nlohmann::json figures_json(const PilotFigures& f, double seconds) {
  nlohmann::json force = nlohmann::json::array();
  for (const auto& s : f.force)
    force.push_back({s.samples, exact(s.mean), exact(s.std_dev), exact(s.statistical_max),
                     exact(s.statistical_min), exact(s.actual_max), exact(s.actual_min),
                     exact(s.loss_of_contact_percent), exact(s.unfiltered_min)});
  return {{"names", f.names},
          {"force", force},
          {"uplift_m", exact(f.uplift_m)},
          {"seconds", exact(seconds)}};
}

PilotProcess::Result result_from_json(const nlohmann::json& j) {
  PilotProcess::Result r;
  r.figures.names = j.at("names").get<std::vector<std::string>>();
  for (const auto& a : j.at("force")) {
    output::ForceStatistics s;
    s.samples = a.at(0).get<std::size_t>();
    double* fields[] = {
        &s.mean,       &s.std_dev,    &s.statistical_max,         &s.statistical_min,
        &s.actual_max, &s.actual_min, &s.loss_of_contact_percent, &s.unfiltered_min};
    for (std::size_t k = 0; k < std::size(fields); ++k) *fields[k] = from_exact(a.at(k + 1));
    r.figures.force.push_back(s);
  }
  r.figures.uplift_m = from_exact(j.at("uplift_m"));
  r.seconds = from_exact(j.at("seconds"));
  return r;
}

void write_all(int fd, const std::string& text) {
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) _exit(5);  // the parent is gone
    done += static_cast<std::size_t>(n);
  }
}

// The second process: its runs in turn, a line each, then _exit (no
// destructor of the parent's objects, no MPI_Finalize, no stdio flush of
// the parent's buffers).
[[noreturn]] void second_process(int fd, pid_t parent, const std::vector<PilotProcess::Run>& runs,
                                 bool dies) {
  prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (getppid() != parent) _exit(6);  // the parent ended before prctl
  if (dies) raise(SIGKILL);
  for (const auto& run : runs) {
    nlohmann::json line;
    try {
      const double start = wall_clock_s();
      const auto figures = run();
      line = figures_json(figures, wall_clock_s() - start);
    } catch (const SolverError& e) {
      line = {{"error", e.what()}, {"solver", true}};
    } catch (const std::exception& e) {
      line = {{"error", e.what()}, {"solver", false}};
    } catch (...) {
      line = {{"error", "an unknown exception"}, {"solver", false}};
    }
    write_all(fd, line.dump() + "\n");
    if (line.contains("error")) _exit(1);
  }
  _exit(0);
}

std::string ended_how(int status) {
  if (WIFSIGNALED(status))
    return "killed by signal " + std::to_string(WTERMSIG(status)) + " (" +
           strsignal(WTERMSIG(status)) + ")";
  if (WIFEXITED(status)) return "exit status " + std::to_string(WEXITSTATUS(status));
  return "status " + std::to_string(status);
}

}  // namespace

AutoChoice pilot_process_choice() {
  return read_auto_option("pcsim run: the accuracy pilot", "-pcsim_pilot_process",
                          "the accuracy pilot's linear FE runs in a second process beside its "
                          "other runs (auto: one rank with a core to spare; true; false; "
                          "docs/fidelity.md)");
}

bool use_pilot_process(const Context& ctx) {
  const AutoChoice choice = pilot_process_choice();
  if (ctx.size > 1 || choice == AutoChoice::off) return false;  // size: the same on every rank
  // As a run's record thread: a CPU more than this node's processes of the
  // job (a sweep's other groups run on the others).
  return choice == AutoChoice::on || core_to_spare_here(ctx.comm);
}

bool pilot_process_running() {
  return g_running.load();
}

PilotProcess::PilotProcess(std::vector<Run> runs) {
  // Tests: the second process dies before its first run (a crash, the
  // system's out-of-memory killer).
  PetscBool dies = PETSC_FALSE;
  PCSIM_PETSC(
      PetscOptionsGetBool(nullptr, nullptr, "-pcsim_debug_pilot_process_dies", &dies, nullptr));
  int fds[2];
  if (pipe(fds) != 0)
    throw SolverError(std::string("the accuracy pilot: no pipe to a second process: ") +
                      std::strerror(errno));
  // Nothing the parent printed is printed again by the child.
  std::fflush(stdout);
  std::fflush(stderr);
  const pid_t parent = getpid();
  g_running = true;  // the child sees it too: neither spares the other's core
  pid_ = fork();
  if (pid_ == 0) {
    ::close(fds[0]);
    second_process(fds[1], parent, runs, dies == PETSC_TRUE);
  }
  ::close(fds[1]);
  if (pid_ < 0) {
    const int error = errno;
    ::close(fds[0]);
    g_running = false;
    throw SolverError(std::string("the accuracy pilot: no second process: ") +
                      std::strerror(error));
  }
  fd_ = fds[0];
}

PilotProcess::~PilotProcess() {
  reap(true);
}

PilotProcess::Result PilotProcess::next() {
  std::size_t end;
  while ((end = buffer_.find('\n')) == std::string::npos) {
    char chunk[4096];
    const ssize_t n = fd_ >= 0 ? ::read(fd_, chunk, sizeof chunk) : 0;
    if (n < 0 && errno == EINTR) continue;  // a signal (GracefulStop's handler)
    if (n <= 0) {
      reap(false);
      throw SolverError("the accuracy pilot's second process ended without its result (" +
                        ended_how(last_status_) + ")");
    }
    buffer_.append(chunk, static_cast<std::size_t>(n));
  }
  const auto line = nlohmann::json::parse(buffer_.substr(0, end));
  buffer_.erase(0, end + 1);
  if (line.contains("error")) {
    const std::string what = line.at("error").get<std::string>();
    reap(false);
    if (line.at("solver").get<bool>()) throw SolverError(what);
    throw std::runtime_error("the accuracy pilot's second process: " + what);
  }
  return result_from_json(line);
}

double PilotProcess::finish() {
  reap(false);
  return peak_mb_;
}

void PilotProcess::reap(bool kill_first) {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  if (pid_ <= 0) return;
  if (kill_first) kill(pid_, SIGKILL);
  int status = 0;
  struct rusage usage {};
  while (wait4(pid_, &status, 0, &usage) < 0 && errno == EINTR) {
  }
  pid_ = -1;
  last_status_ = status;
  peak_mb_ = usage.ru_maxrss / 1024.0;
  g_running = false;
}

PilotFigures broadcast_figures(MPI_Comm comm, const PilotFigures& figures) {
  const std::string text = broadcast_text(comm, figures_json(figures, 0).dump());
  return result_from_json(nlohmann::json::parse(text)).figures;
}

}  // namespace pcsim::simulation
