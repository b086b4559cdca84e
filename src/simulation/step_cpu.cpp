// The stepping thread's CPU (step_cpu.hpp).
#include "pcsim/simulation/step_cpu.hpp"

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <string>
#include <vector>

#include "pcsim/core/error.hpp"
#include "pcsim/simulation/auto_option.hpp"

namespace pcsim::simulation {

namespace {

constexpr const char* kOption = "-pcsim_step_cpu";

std::atomic<int> g_pinned_cpu{-1};  // the stepping thread's CPU while pinned
cpu_set_t g_process_cpus;           // the pinned thread's CPUs before (leave_step_cpu)

cpu_set_t only(int cpu) {
  cpu_set_t set;
  CPU_ZERO(&set);
  CPU_SET(cpu, &set);
  return set;
}

// The calling thread's CPUs into 'set'; false (errno set) when unreadable.
bool read_thread_cpus(cpu_set_t& set) {
  CPU_ZERO(&set);
  return sched_getaffinity(0, sizeof set, &set) == 0;  // 0: the calling thread
}

std::string allowed_list(const cpu_set_t& set) {
  std::string list;
  for (int c = 0; c < CPU_SETSIZE; ++c)
    if (CPU_ISSET(c, &set)) list += (list.empty() ? "" : ", ") + std::to_string(c);
  return list;
}

// Passes a second of a loop over 256 KiB of doubles (a level-2 cache's
// worth, as a modal step's vectors) on the calling thread, over 'seconds'.
double probe_passes_per_s(double seconds) {
  std::vector<double> x(32768, 1.0);
  const auto pass = [&] {
    for (double& v : x) v = v * 0.999999 + 1e-6;
  };
  pass();  // the caches and the clock settled
  const auto start = std::chrono::steady_clock::now();
  long passes = 0;
  double elapsed = 0;
  do {
    pass();
    ++passes;
    elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  } while (elapsed < seconds);
  volatile double keep = x[passes % x.size()];  // the loop's results used
  (void)keep;
  return passes / elapsed;
}

// The CPU of 'allowed' where the probe ran fastest; 'probe' gets each
// CPU's passes a second. The thread is on the last CPU probed after.
int fastest_cpu(const cpu_set_t& allowed, nlohmann::json& probe) {
  probe = nlohmann::json::object();
  int best = -1;
  double best_rate = 0;
  for (int c = 0; c < CPU_SETSIZE; ++c) {
    if (!CPU_ISSET(c, &allowed)) continue;
    const cpu_set_t one = only(c);
    if (sched_setaffinity(0, sizeof one, &one) != 0) continue;
    const double rate = probe_passes_per_s(0.04);
    probe[std::to_string(c)] = rate;
    if (rate > best_rate) best = c, best_rate = rate;
  }
  if (best < 0) throw SolverError("-pcsim_step_cpu fastest: no CPU could be probed");
  return best;
}

}  // namespace

int step_cpu_choice(int ranks) {
  char value[64] = "";
  if (!read_option_string("pcsim run: the stepping thread", kOption,
                          "the CPU the stepping thread runs on (a number, or fastest: the one a "
                          "short probe finds fastest), the run's other threads off it (one rank; "
                          "docs/benchmarks.md)",
                          "", value, sizeof value))
    return -1;
  const std::string v = value;
  if (ranks > 1)
    throw InputError("command line", kOption,
                     "pins the stepping thread of a run of one rank; on " + std::to_string(ranks) +
                         " ranks mpirun binds them (--bind-to core)");
  if (v == "fastest") return kFastestCpu;
  std::size_t used = 0;
  int cpu = -1;
  try {
    cpu = std::stoi(v, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (v.empty() || used != v.size() || cpu < 0)
    throw InputError("command line", kOption,
                     "'" + v + "' is not a CPU number (0, 1, ...) or fastest");
  cpu_set_t allowed;
  if (!read_thread_cpus(allowed))
    throw InputError("command line", kOption,
                     std::string("the process's CPUs cannot be read: ") + std::strerror(errno));
  if (cpu >= CPU_SETSIZE || !CPU_ISSET(cpu, &allowed))
    throw InputError(
        "command line", kOption,
        "CPU " + v + " is not one this process may run on (" + allowed_list(allowed) + ")");
  return cpu;
}

StepCpuPin::StepCpuPin(int cpu) {
  if (cpu == -1) return;
  if (!read_thread_cpus(before_))
    throw SolverError(std::string("-pcsim_step_cpu: the thread's CPUs: ") + std::strerror(errno));
  if (cpu == kFastestCpu) cpu = fastest_cpu(before_, probe_);
  const cpu_set_t one = only(cpu);
  if (sched_setaffinity(0, sizeof one, &one) != 0)  // 0: the calling thread
    throw SolverError("-pcsim_step_cpu: the stepping thread not moved to CPU " +
                      std::to_string(cpu) + ": " + std::strerror(errno));
  g_process_cpus = before_;
  g_pinned_cpu = cpu;
  cpu_ = cpu;
}

nlohmann::json StepCpuPin::json() const {
  if (cpu_ < 0) return nullptr;
  nlohmann::json j = {{"cpu", cpu_}};
  if (!probe_.is_null()) j["probe_passes_per_s"] = probe_;
  return j;
}

StepCpuPin::~StepCpuPin() {
  if (cpu_ < 0) return;
  g_pinned_cpu = -1;
  sched_setaffinity(0, sizeof before_, &before_);  // (no throw from a destructor)
}

StepCpuWidened::StepCpuWidened() : cpu_(g_pinned_cpu.load()) {
  if (cpu_ >= 0) sched_setaffinity(0, sizeof g_process_cpus, &g_process_cpus);
}

StepCpuWidened::~StepCpuWidened() {
  if (cpu_ < 0) return;
  const cpu_set_t one = only(cpu_);
  sched_setaffinity(0, sizeof one, &one);  // (no throw from a destructor)
}

int process_cpu_count() {
  if (g_pinned_cpu.load() >= 0) return CPU_COUNT(&g_process_cpus);
  cpu_set_t allowed;
  return read_thread_cpus(allowed) ? CPU_COUNT(&allowed) : 1;
}

void leave_step_cpu() {
  const int cpu = g_pinned_cpu.load();
  if (cpu < 0) return;
  cpu_set_t others = g_process_cpus;
  CPU_CLR(cpu, &others);
  if (CPU_COUNT(&others) > 0) sched_setaffinity(0, sizeof others, &others);
}

}  // namespace pcsim::simulation
