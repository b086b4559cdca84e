// Where the accuracy pilot runs (simulation::pilot_stretch): every
// pantograph starts where the run starts it, however far along the line the
// analysis section lies (the figures of a stretch are those of the trajectory
// that reaches it: a pilot whose train started two spans before its stretch
// estimated EN 50318's sigma error on spans 15-16 of 20 at 0.30 % against an
// actual 0.94 %), and the rearmost one crosses all of the stretch.
#include <gtest/gtest.h>

#include <algorithm>

#include "pcsim/scene/composition.hpp"
#include "pcsim/scene/run_scene.hpp"
#include "pcsim/simulation/accuracy_pilot.hpp"

namespace {

using namespace pcsim;

scene::RunScene load(const std::string& relative, const std::vector<std::string>& sets) {
  std::vector<scene::InputOverride> overrides;
  for (const auto& set : sets)
    overrides.push_back(scene::parse_override(set, {"", "--set " + set}));
  return scene::load_run_scene(
      scene::load_composed(std::string(PCSIM_SOURCE_DIR) + "/" + relative, overrides));
}

// The rearmost pantograph's travel past the stretch when the first one
// stops (filter edge 3 / cutoff_hz).
void expect_crossed(const scene::RunScene& run, const simulation::PilotStretch& s) {
  const double edge = 3 / run.cutoff_hz * run.speed;
  double rear = run.pantographs.front().start_x;
  for (const auto& p : run.pantographs) rear = std::min(rear, p.start_x);
  const double rear_at_end = s.end_x - (run.pantographs.front().start_x - rear);
  EXPECT_GE(rear_at_end, s.to_x + edge);
  EXPECT_LE(s.end_x, run.end_x);
}

TEST(PilotStretch, TwoPantographsFarAlongALongLine) {
  // 40 spans of 60 m, the section at spans 29-32 (1680-1920 m), the train's
  // front at 205 m, its rear at 5 m: the pilot's stretch is the section's
  // first two spans, its train the run's until the rear is past them.
  const auto run = load("runs/interaction/two-pantographs-300.yaml",
                        {"catenary.design.spans.count=40", "simulation.end_x=2300",
                         "analysis.from_span=29", "analysis.to_span=32"});
  const auto s = simulation::pilot_stretch(run);
  EXPECT_EQ(s.from_span, 29);
  EXPECT_EQ(s.to_span, 30);
  EXPECT_DOUBLE_EQ(s.from_x, 1680);
  EXPECT_DOUBLE_EQ(s.to_x, 1800);
  // The rear past 1800 m by the filter's edge (12.5 m) and a metre: the
  // front 200 m further.
  EXPECT_NEAR(s.end_x, 1800 + 12.5 + 1 + 200, 1e-9);
  expect_crossed(run, s);
}

TEST(PilotStretch, OnePantographFarAlongALongLine) {
  const auto run = load("runs/interaction/en50318-300.yaml",
                        {"catenary.design.spans.count=40", "simulation.end_x=2300",
                         "analysis.from_span=29", "analysis.to_span=32"});
  const auto s = simulation::pilot_stretch(run);
  EXPECT_NEAR(s.end_x, 1800 + 12.5 + 1, 1e-9);
  expect_crossed(run, s);
}

TEST(PilotStretch, TheTrainStopsOnceTheRearIsPast) {
  const auto run = load("runs/interaction/two-pantographs-300.yaml", {});
  const auto s = simulation::pilot_stretch(run);
  EXPECT_DOUBLE_EQ(s.from_x, 480);
  EXPECT_DOUBLE_EQ(s.to_x, 600);
  expect_crossed(run, s);
  EXPECT_LT(s.end_x, run.end_x);  // the pilot stops once the trailing one is past
  EXPECT_TRUE(s.spans_alike);
}

// Where the spans differ, two of them do not stand for the others: on
// supports-300 (stiffer supports 4 and 5, section spans 3-6) a two-span
// pilot missed the loss of contact at the support at 300 m. The pilot
// covers the whole section there, and at most kPilotMaxSpans of a longer one.
TEST(PilotStretch, SpansThatDifferGetTheWholeSection) {
  const auto run = load("runs/lines/supports-300.yaml", {});
  const auto s = simulation::pilot_stretch(run);
  EXPECT_FALSE(s.spans_alike);
  EXPECT_EQ(s.from_span, 3);
  EXPECT_EQ(s.to_span, 6);
  EXPECT_DOUBLE_EQ(s.from_x, 120);
  EXPECT_DOUBLE_EQ(s.to_x, 360);
  expect_crossed(run, s);
}

TEST(PilotStretch, ALongSectionOfSpansThatDifferIsCapped) {
  // three-sections-300: analysis section spans 2-59.
  const auto run = load("runs/lines/three-sections-300.yaml", {});
  const auto s = simulation::pilot_stretch(run);
  EXPECT_FALSE(s.spans_alike);
  EXPECT_EQ(s.from_span, 2);
  EXPECT_EQ(s.to_span, 2 + simulation::kPilotMaxSpans - 1);
  expect_crossed(run, s);
}

TEST(PilotStretch, AStitchedLineHasSpansAlike) {
  const auto run = load("runs/lines/stitched-300.yaml", {});
  const auto s = simulation::pilot_stretch(run);
  EXPECT_TRUE(s.spans_alike);
  EXPECT_EQ(s.to_span, s.from_span + 1);
}

}  // namespace
