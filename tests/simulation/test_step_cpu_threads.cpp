// The threads a pinned step starts (src/simulation/step_cpu.cpp): a thread
// started under StepCpuWidened begins with the process's CPUs, not the
// step's one CPU (it would wait there for the step's time slice before
// leave_step_cpu moved it); the step is on its CPU again after; while
// pinned, process_cpu_count() is the process's CPUs (the spare core of a
// records' thread), not the pinned thread's one; without a pin nothing
// changes. End to end (a pinned modal run keeps its records' thread):
// tests/simulation/test_step_cpu.sh.
#include <gtest/gtest.h>
#include <sched.h>

#include <thread>

#include "pcsim/simulation/step_cpu.hpp"

namespace {

using pcsim::simulation::process_cpu_count;
using pcsim::simulation::StepCpuPin;
using pcsim::simulation::StepCpuWidened;

cpu_set_t this_thread_cpus() {
  cpu_set_t set;
  CPU_ZERO(&set);
  EXPECT_EQ(sched_getaffinity(0, sizeof set, &set), 0);
  return set;
}

int first_cpu(const cpu_set_t& set) {
  for (int c = 0; c < CPU_SETSIZE; ++c)
    if (CPU_ISSET(c, &set)) return c;
  return -1;
}

// The CPUs a thread started now has at its first instruction.
cpu_set_t started_thread_cpus() {
  cpu_set_t seen;
  std::thread([&] { seen = this_thread_cpus(); }).join();
  return seen;
}

TEST(StepCpuThreads, StartedUnderWidenedOffTheStepCpu) {
  const cpu_set_t process = this_thread_cpus();
  const int cpu = first_cpu(process);
  cpu_set_t step;
  CPU_ZERO(&step);
  CPU_SET(cpu, &step);
  {
    const StepCpuPin pin(cpu);
    EXPECT_EQ(process_cpu_count(), CPU_COUNT(&process));
    cpu_set_t plain = started_thread_cpus();
    EXPECT_TRUE(CPU_EQUAL(&plain, &step));  // what StepCpuWidened is for
    cpu_set_t widened;
    {
      const StepCpuWidened w;
      widened = started_thread_cpus();
    }
    EXPECT_TRUE(CPU_EQUAL(&widened, &process));
    cpu_set_t after = this_thread_cpus();
    EXPECT_TRUE(CPU_EQUAL(&after, &step));
  }
  cpu_set_t released = this_thread_cpus();
  EXPECT_TRUE(CPU_EQUAL(&released, &process));
}

TEST(StepCpuThreads, NothingChangesUnpinned) {
  const cpu_set_t process = this_thread_cpus();
  EXPECT_EQ(process_cpu_count(), CPU_COUNT(&process));
  cpu_set_t inside;
  {
    const StepCpuWidened w;
    inside = this_thread_cpus();
  }
  EXPECT_TRUE(CPU_EQUAL(&inside, &process));
}

}  // namespace
