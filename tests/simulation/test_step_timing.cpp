// The step-time report (step_timing.hpp): percentiles by nearest rank, the
// first step apart, and the slowest steps named with what happened in them.
#include <gtest/gtest.h>

#include "pcsim/simulation/step_timing.hpp"

namespace {

using pcsim::simulation::StepEvents;
using pcsim::simulation::StepTiming;

TEST(StepTiming, PercentilesLeaveTheFirstStepApart) {
  StepTiming timing;
  timing.add(1, 5e-3, {});  // the first step: factors J0, apart
  for (long step = 2; step <= 101; ++step) timing.add(step, 1e-5 * (step - 1), {});
  const auto j = timing.json();
  EXPECT_EQ(j["steps"], 101);
  EXPECT_DOUBLE_EQ(j["first_step_ms"].get<double>(), 5.0);
  // 100 steps of 0.01 .. 1.00 ms: the nearest rank of p % is p / 100 ms.
  EXPECT_DOUBLE_EQ(j["median_ms"].get<double>(), 0.50);
  EXPECT_DOUBLE_EQ(j["p99_ms"].get<double>(), 0.99);
  EXPECT_DOUBLE_EQ(j["max_ms"].get<double>(), 1.00);
  EXPECT_EQ(j["slowest"][0]["step"], 101);
  EXPECT_EQ(j["slowest"][0]["causes"], "none found");
  // Steps without a cause: no line of causes on the console.
  EXPECT_EQ(timing.summary_line().find("by cause"), std::string::npos);
}

// Each cause the reduced level's slow steps have (docs/results-format.md):
// before 2026-12-03 a step with an exact dropper anchor, a changed set of
// contacts and slack droppers or a records' batch beside it read "none found".
TEST(StepTiming, SlowestStepsNameTheirCauses) {
  StepTiming timing;
  timing.add(1, 1e-3, {});
  StepEvents anchor;
  anchor.exact_dropper_anchors = 1;
  StepEvents switched;
  switched.rank_one_set_changes = 1;
  switched.rank_one_terms = 4;
  switched.capacitance_rows = 3;
  switched.records_batch_beside = true;
  StepEvents moving_contact;  // its rows formed, the set the same: no cause
  moving_contact.capacitance_rows = 2;
  moving_contact.rank_one_terms = 2;
  StepEvents busy;
  busy.newton_iterations = 3;
  busy.reference_builds = 1;
  busy.involuntary_switches = 2;
  busy.page_faults = 3;
  timing.add(2, 4e-3, anchor);
  timing.add(3, 3e-3, switched);
  timing.add(4, 2e-3, moving_contact);
  timing.add(5, 5e-3, busy);
  const auto slowest = timing.json()["slowest"];
  ASSERT_EQ(slowest.size(), 4u);
  EXPECT_EQ(
      slowest[0]["causes"],
      "J0 refactored, 3 Newton iterations, 3 page fault(s), 2 involuntary context switch(es)");
  EXPECT_EQ(slowest[1]["causes"], "dropper check's exact anchor");
  EXPECT_EQ(slowest[2]["causes"],
            "contacts or slack droppers changed (4 rank-one terms, 3 capacitance rows formed), "
            "records' batch computing beside it");
  EXPECT_EQ(slowest[3]["causes"], "none found");
  // The context switch's step is left out of the quiet maximum.
  EXPECT_DOUBLE_EQ(timing.json()["max_without_context_switch_ms"].get<double>(), 4.0);
  // Each step counts under each of its causes; the first step is apart.
  const auto by_cause = timing.json()["by_cause"];
  EXPECT_EQ(by_cause.size(), 8u);
  EXPECT_DOUBLE_EQ(by_cause["page_faults"]["mean_ms"].get<double>(), 5.0);
  EXPECT_EQ(by_cause["none"]["steps"], 1);
  EXPECT_DOUBLE_EQ(by_cause["none"]["mean_ms"].get<double>(), 2.0);
  EXPECT_EQ(by_cause["dropper_exact_anchor"]["steps"], 1);
  EXPECT_DOUBLE_EQ(by_cause["dropper_exact_anchor"]["mean_ms"].get<double>(), 4.0);
  EXPECT_DOUBLE_EQ(by_cause["records_batch_beside"]["mean_ms"].get<double>(), 3.0);
  EXPECT_DOUBLE_EQ(by_cause["context_switch"]["mean_ms"].get<double>(), 5.0);
  const std::string line = timing.summary_line();
  EXPECT_NE(
      line.find("steps by cause (count, mean ms): contacts_or_slack_droppers_changed 1, 3.000;"),
      std::string::npos)
      << line;
  EXPECT_NE(line.find("dropper_exact_anchor 1, 4.000"), std::string::npos) << line;
}

// The CPU each step ended on (sched_getcpu in the run): a virtual machine's
// two CPUs can run at different speeds (docs/benchmarks.md, "The machine's
// two CPUs at different speeds"), so the steps' count and mean per CPU say
// where a run's time went. The first step is apart; an unknown CPU (-1) is
// not counted.
TEST(StepTiming, StepsCountedByTheirCpu) {
  StepTiming timing;
  StepEvents on0, on1, unknown;
  on0.cpu = 0;
  on1.cpu = 1;
  timing.add(1, 9e-3, on1);  // the first step: apart
  timing.add(2, 1e-3, on0);
  timing.add(3, 3e-3, on0);
  timing.add(4, 5e-3, on1);
  timing.add(5, 7e-3, unknown);
  const auto by_cpu = timing.json()["by_cpu"];
  ASSERT_EQ(by_cpu.size(), 2u);
  EXPECT_EQ(by_cpu["0"]["steps"], 2);
  EXPECT_DOUBLE_EQ(by_cpu["0"]["mean_ms"].get<double>(), 2.0);
  EXPECT_EQ(by_cpu["1"]["steps"], 1);
  EXPECT_DOUBLE_EQ(by_cpu["1"]["mean_ms"].get<double>(), 5.0);
  const std::string line = timing.summary_line();
  EXPECT_NE(line.find("    steps by CPU (count, mean ms): 0 2, 2.000; 1 1, 5.000\n"),
            std::string::npos)
      << line;
  // No CPU known: no line.
  StepTiming none;
  none.add(1, 1e-3, {});
  none.add(2, 1e-3, {});
  EXPECT_TRUE(none.json()["by_cpu"].empty());
  EXPECT_EQ(none.summary_line().find("by CPU"), std::string::npos);
}

}  // namespace
