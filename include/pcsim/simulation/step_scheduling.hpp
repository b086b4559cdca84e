// How the OS schedules the stepping thread, for hardware-in-the-loop use: a
// real-time policy (SCHED_FIFO or SCHED_RR, e.g. `chrt -f 10 pcsim run ...`)
// keeps ordinary threads from preempting a step, but under the kernel's
// real-time throttling (kernel.sched_rt_runtime_us below
// kernel.sched_rt_period_us, Linux's default 950000 of 1000000) a thread
// that has stepped the runtime in a period waits out the rest of it: a
// 50 ms stall each second (docs/benchmarks.md, "Real-time scheduling for the
// step"). Recorded in summary.json (step_time.scheduling) and warned.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace pcsim::simulation {

struct StepScheduling {
  std::string policy = "other";  // other, batch, idle, fifo, rr, deadline
  int priority = 0;              // sched_priority (fifo, rr)
  // kernel.sched_rt_runtime_us and _period_us; -1 runtime: no throttling.
  // Not readable (no /proc): read false.
  bool read = false;
  long rt_runtime_us = -1, rt_period_us = 0;

  // The calling thread's policy and the kernel's limits.
  static StepScheduling of_this_thread();
  bool real_time() const { return policy == "fifo" || policy == "rr"; }
  bool throttled() const {
    return real_time() && read && rt_runtime_us >= 0 && rt_runtime_us < rt_period_us;
  }
  // {policy, priority, rt_runtime_us, rt_period_us} (the last two null
  // when not read).
  nlohmann::json json() const;
  // The console's warning for a throttled real-time thread, else "".
  std::string throttle_warning() const;
};

}  // namespace pcsim::simulation
