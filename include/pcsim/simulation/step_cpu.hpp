// The CPU a run's stepping thread runs on (-pcsim_step_cpu N), for
// hardware-in-the-loop use: a rig keeps a CPU for the step (Linux's
// isolcpus, or a virtual machine's fastest CPU: two CPUs of one machine can
// run at different speeds, docs/benchmarks.md, "The machine's two CPUs at
// different speeds"). While a run steps, its stepping thread is pinned to N
// and the threads the run starts (a records' batch, a window shift's helper)
// run on the process's other CPUs. One rank only: on several, mpirun binds
// the ranks (--bind-to core).
#pragma once

#include <sched.h>

namespace pcsim::simulation {

// -pcsim_step_cpu: -1 when not given. Checked (InputError, exit 2): an
// integer naming a CPU this process may run on, on a run of one rank
// ('ranks': the run's).
int step_cpu_choice(int ranks);

// While alive, the calling thread on 'cpu' (-1: nothing changes; a run of the
// accuracy pilot beside its second process is not pinned); its CPUs
// as before when it ends. One at a time per process.
class StepCpuPin {
 public:
  explicit StepCpuPin(int cpu);
  ~StepCpuPin();
  StepCpuPin(const StepCpuPin&) = delete;
  StepCpuPin& operator=(const StepCpuPin&) = delete;

 private:
  cpu_set_t before_{};
  bool pinned_ = false;
};

// First thing on a thread a run starts: the process's CPUs but the stepping
// thread's, while one is pinned (else nothing changes).
void leave_step_cpu();

}  // namespace pcsim::simulation
