#include "pcsim/simulation/step_scheduling.hpp"

#include <sched.h>

#include <cstdio>
#include <fstream>

namespace pcsim::simulation {

namespace {

// A number from a /proc file, or false.
bool read_long(const char* path, long& value) {
  std::ifstream in(path);
  return static_cast<bool>(in >> value);
}

const char* policy_name(int policy) {
  switch (policy) {
    case SCHED_FIFO:
      return "fifo";
    case SCHED_RR:
      return "rr";
    case SCHED_BATCH:
      return "batch";
    case SCHED_IDLE:
      return "idle";
#ifdef SCHED_DEADLINE
    case SCHED_DEADLINE:
      return "deadline";
#endif
    default:
      return "other";
  }
}

}  // namespace

StepScheduling StepScheduling::of_this_thread() {
  StepScheduling s;
  const int policy = sched_getscheduler(0);  // Linux: the calling thread's
  if (policy >= 0) s.policy = policy_name(policy);
  sched_param param{};
  if (sched_getparam(0, &param) == 0) s.priority = param.sched_priority;
  s.read = read_long("/proc/sys/kernel/sched_rt_runtime_us", s.rt_runtime_us) &&
           read_long("/proc/sys/kernel/sched_rt_period_us", s.rt_period_us);
  return s;
}

nlohmann::json StepScheduling::json() const {
  nlohmann::json j = {{"policy", policy}, {"priority", priority}};
  j["rt_runtime_us"] = read ? nlohmann::json(rt_runtime_us) : nlohmann::json(nullptr);
  j["rt_period_us"] = read ? nlohmann::json(rt_period_us) : nlohmann::json(nullptr);
  return j;
}

std::string StepScheduling::throttle_warning() const {
  if (!throttled()) return "";
  char text[600];
  std::snprintf(text, sizeof text,
                "the stepping thread runs under SCHED_%s (priority %d) with the kernel's "
                "real-time throttling on (kernel.sched_rt_runtime_us %ld of "
                "kernel.sched_rt_period_us %ld): once real-time threads have run %.3g s of a "
                "period, a step stalls for the %.3g ms left of it (docs/benchmarks.md, "
                "\"Real-time scheduling for the step\"); as root, "
                "echo -1 > /proc/sys/kernel/sched_rt_runtime_us turns the throttling off",
                policy == "fifo" ? "FIFO" : "RR", priority, rt_runtime_us, rt_period_us,
                1e-6 * static_cast<double>(rt_runtime_us),
                1e-3 * static_cast<double>(rt_period_us - rt_runtime_us));
  return text;
}

}  // namespace pcsim::simulation
