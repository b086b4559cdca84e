// The window shift's helper thread (src/simulation/spinning_helper.hpp): the
// work handed to a started helper runs on another thread and both shares are
// done when run() returns; without start() both run here; a started helper
// given no work ends on stop() or with its owner (no hang); a helper serves
// again after start().
#include <gtest/gtest.h>

#include <numeric>
#include <thread>
#include <vector>

#include "../../src/simulation/spinning_helper.hpp"

namespace {

using pcsim::simulation::SpinningHelper;

// Sums of 1..n in two halves, the back one on the helper; the thread ids of both.
struct Halves {
  std::vector<long> values = std::vector<long>(100000);
  long front = 0, back = 0;
  std::thread::id front_thread, back_thread;
  Halves() { std::iota(values.begin(), values.end(), 1L); }
  void run(SpinningHelper& helper) {
    const auto half = values.begin() + static_cast<long>(values.size() / 2);
    helper.run(
        [&] {
          front_thread = std::this_thread::get_id();
          front = std::accumulate(values.begin(), half, 0L);
        },
        [&] {
          back_thread = std::this_thread::get_id();
          back = std::accumulate(half, values.end(), 0L);
        });
  }
};

constexpr long kTotal = 100000L * 100001L / 2;

// A started helper: the back half on another thread, this thread the front.
void expect_shared(SpinningHelper& helper) {
  helper.start();
  EXPECT_TRUE(helper.started());
  Halves h;
  h.run(helper);
  EXPECT_EQ(h.front + h.back, kTotal);
  EXPECT_EQ(h.front_thread, std::this_thread::get_id());
  EXPECT_NE(h.back_thread, std::this_thread::get_id());
  EXPECT_FALSE(helper.started());  // it ended with its work
}

TEST(SpinningHelper, StartedHelperTakesTheBackHalf) {
  SpinningHelper helper;
  expect_shared(helper);
  expect_shared(helper);  // started again, it serves again
}

TEST(SpinningHelper, WithoutStartBothSharesRunHere) {
  SpinningHelper helper;
  Halves h;
  h.run(helper);
  EXPECT_EQ(h.front + h.back, kTotal);
  EXPECT_EQ(h.back_thread, std::this_thread::get_id());
}

TEST(SpinningHelper, UnusedHelperEnds) {
  SpinningHelper stopped;
  stopped.start();
  stopped.stop();
  EXPECT_FALSE(stopped.started());
  SpinningHelper destroyed;  // its destructor ends the spinning thread
  destroyed.start();
}

}  // namespace
