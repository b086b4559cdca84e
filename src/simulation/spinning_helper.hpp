// A second thread for one burst of work that must start at once (a modal
// window's shift: moving_window.cpp): started ahead of the work, it spins
// until handed its share, so the idle core's wake-up is paid before the work
// and not in it (a thread made at the shift began 0.3-2.6 ms later on a
// virtual machine: docs/benchmarks.md, "A window shift's pass on two threads").
// Its work makes no MPI call. Private to src/simulation.
#pragma once

#include <atomic>
#include <functional>
#include <thread>

namespace pcsim::simulation {

class SpinningHelper {
 public:
  SpinningHelper() = default;
  SpinningHelper(const SpinningHelper&) = delete;
  SpinningHelper& operator=(const SpinningHelper&) = delete;
  ~SpinningHelper() { stop(); }
  bool started() const { return thread_.joinable(); }
  // Starts the thread (spinning) unless it is already.
  void start();
  // Runs 'here' on this thread and 'there' on the helper; returns when both
  // are done. The helper has ended then (start() makes the next one).
  void run(const std::function<void()>& here, const std::function<void()>& there);
  // Ends a helper that was given no work.
  void stop();

 private:
  enum : int { kSpin, kWork, kQuit };
  std::atomic<int> state_{kSpin};
  std::function<void()> work_;
  std::thread thread_;
};

}  // namespace pcsim::simulation
