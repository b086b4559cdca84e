// The CPU a run's stepping thread runs on (-pcsim_step_cpu N|fastest), for
// hardware-in-the-loop use: a rig keeps a CPU for the step (Linux's
// isolcpus, or a virtual machine's fastest CPU: two CPUs of one machine can
// run at different speeds, docs/benchmarks.md, "The machine's two CPUs at
// different speeds"). While a run steps, its stepping thread is pinned to N
// and the threads the run starts (a records' batch, a window shift's helper)
// run on the process's other CPUs. One rank only: on several, mpirun binds
// the ranks (--bind-to core).
#pragma once

#include <sched.h>

#include <nlohmann/json.hpp>

namespace pcsim::simulation {

// -pcsim_step_cpu: -1 when not given, kFastestCpu for "fastest". Checked
// (InputError, exit 2): "fastest" or an integer naming a CPU this process
// may run on, on a run of one rank ('ranks': the run's).
constexpr int kFastestCpu = -2;
int step_cpu_choice(int ranks);

// While alive, the calling thread on 'cpu' (-1: nothing changes; a run of the
// accuracy pilot beside its second process is not pinned); its CPUs
// as before when it ends. One at a time per process.
// kFastestCpu: the process's CPU on which a short probe ran fastest
// (a loop over 256 KiB of doubles, 40 ms on each CPU, just before the
// steps: a virtual machine's CPUs can differ by half at the same moment).
class StepCpuPin {
 public:
  explicit StepCpuPin(int cpu);
  // {cpu: the CPU pinned} or, after a probe, {cpu, probe_passes_per_s: {cpu:
  // passes}}; null when not pinned (summary.json step_time.pinned).
  nlohmann::json json() const;
  ~StepCpuPin();
  StepCpuPin(const StepCpuPin&) = delete;
  StepCpuPin& operator=(const StepCpuPin&) = delete;

 private:
  cpu_set_t before_{};
  int cpu_ = -1;          // the CPU pinned (-1: none)
  nlohmann::json probe_;  // passes a second per CPU (kFastestCpu)
};

// The CPUs this process may run on: while the stepping thread is pinned, its
// CPUs before (a pinned thread's own affinity is one CPU, and a run's spare
// core for its records' thread or its window's helper is the process's);
// else the calling thread's.
int process_cpu_count();

// While alive on the stepping thread, pinned: its CPUs the process's, so that
// a thread it starts begins off the step's CPU (a new thread has its
// creator's CPUs, and one begun on the step's CPU waited there for the
// step's time slice, milliseconds, before leave_step_cpu moved it:
// docs/benchmarks.md, "A pinned step's threads started off its CPU").
// Nothing while not pinned.
class StepCpuWidened {
 public:
  StepCpuWidened();
  ~StepCpuWidened();
  StepCpuWidened(const StepCpuWidened&) = delete;
  StepCpuWidened& operator=(const StepCpuWidened&) = delete;

 private:
  int cpu_ = -1;  // the step's CPU, restored at the end (-1: not pinned)
};

// First thing on a thread a run starts: the process's CPUs but the stepping
// thread's, while one is pinned (else nothing changes).
void leave_step_cpu();

}  // namespace pcsim::simulation
