// The stepping thread's CPU (step_cpu.hpp).
#include "pcsim/simulation/step_cpu.hpp"

#include <petscsys.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <string>

#include "pcsim/core/error.hpp"

namespace pcsim::simulation {

namespace {

constexpr const char* kOption = "-pcsim_step_cpu";

std::atomic<int> g_pinned_cpu{-1};  // the stepping thread's CPU while pinned
cpu_set_t g_process_cpus;           // the pinned thread's CPUs before (leave_step_cpu)

std::string allowed_list(const cpu_set_t& set) {
  std::string list;
  for (int c = 0; c < CPU_SETSIZE; ++c)
    if (CPU_ISSET(c, &set)) list += (list.empty() ? "" : ", ") + std::to_string(c);
  return list;
}

}  // namespace

int step_cpu_choice(int ranks) {
  char value[64] = "";
  PetscBool given = PETSC_FALSE;
  auto read = [&]() -> PetscErrorCode {  // PETSc's macros return an error code
    PetscFunctionBeginUser;
    PetscOptionsBegin(PETSC_COMM_WORLD, nullptr, "pcsim run: the stepping thread", "");
    PetscCall(PetscOptionsString(kOption,
                                 "the CPU the stepping thread runs on, the run's other threads "
                                 "off it (one rank; docs/benchmarks.md)",
                                 "", "", value, sizeof value, &given));
    PetscOptionsEnd();
    PetscFunctionReturn(0);
  };
  PCSIM_PETSC(read());
  if (!given) return -1;
  const std::string v = value;
  std::size_t used = 0;
  int cpu = -1;
  try {
    cpu = std::stoi(v, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (v.empty() || used != v.size() || cpu < 0)
    throw InputError("command line", kOption, "'" + v + "' is not a CPU number (0, 1, ...)");
  if (ranks > 1)
    throw InputError("command line", kOption,
                     "pins the stepping thread of a run of one rank; on " + std::to_string(ranks) +
                         " ranks mpirun binds them (--bind-to core)");
  cpu_set_t allowed;
  CPU_ZERO(&allowed);
  if (sched_getaffinity(0, sizeof allowed, &allowed) != 0)
    throw InputError("command line", kOption,
                     std::string("the process's CPUs cannot be read: ") + std::strerror(errno));
  if (cpu >= CPU_SETSIZE || !CPU_ISSET(cpu, &allowed))
    throw InputError(
        "command line", kOption,
        "CPU " + v + " is not one this process may run on (" + allowed_list(allowed) + ")");
  return cpu;
}

StepCpuPin::StepCpuPin(int cpu) {
  if (cpu < 0) return;
  CPU_ZERO(&before_);
  if (sched_getaffinity(0, sizeof before_, &before_) != 0)
    throw SolverError(std::string("-pcsim_step_cpu: the thread's CPUs: ") + std::strerror(errno));
  cpu_set_t one;
  CPU_ZERO(&one);
  CPU_SET(cpu, &one);
  if (sched_setaffinity(0, sizeof one, &one) != 0)  // 0: the calling thread
    throw SolverError("-pcsim_step_cpu: the stepping thread not moved to CPU " +
                      std::to_string(cpu) + ": " + std::strerror(errno));
  g_process_cpus = before_;
  g_pinned_cpu = cpu;
  pinned_ = true;
}

StepCpuPin::~StepCpuPin() {
  if (!pinned_) return;
  g_pinned_cpu = -1;
  sched_setaffinity(0, sizeof before_, &before_);  // (no throw from a destructor)
}

void leave_step_cpu() {
  const int cpu = g_pinned_cpu.load();
  if (cpu < 0) return;
  cpu_set_t others = g_process_cpus;
  CPU_CLR(cpu, &others);
  if (CPU_COUNT(&others) > 0) sched_setaffinity(0, sizeof others, &others);
}

}  // namespace pcsim::simulation
