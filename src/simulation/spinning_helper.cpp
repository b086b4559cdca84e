#include "spinning_helper.hpp"

#include "pcsim/simulation/step_cpu.hpp"

namespace pcsim::simulation {

namespace {

void cpu_relax() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();  // spin politely: the core stays the thread's
#endif
}

}  // namespace

void SpinningHelper::start() {
  if (started()) return;
  state_.store(kSpin, std::memory_order_relaxed);
  const StepCpuWidened widened;  // (the thread begins off a pinned step's CPU)
  thread_ = std::thread([this] {
    leave_step_cpu();  // -pcsim_step_cpu: the step's CPU is the step's
    int state;
    while ((state = state_.load(std::memory_order_acquire)) == kSpin) cpu_relax();
    if (state == kWork) work_();
  });
}

void SpinningHelper::run(const std::function<void()>& here, const std::function<void()>& there) {
  if (!started()) {
    here();
    there();
    return;
  }
  work_ = there;
  state_.store(kWork, std::memory_order_release);
  here();
  thread_.join();
}

void SpinningHelper::stop() {
  if (!started()) return;
  state_.store(kQuit, std::memory_order_release);
  thread_.join();
}

}  // namespace pcsim::simulation
