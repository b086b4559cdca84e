// The run's extremes against its accuracy pilot's stretch
// (simulation/pilot_extremes.hpp): an actual maximum or minimum outside the
// stretch is listed in summary.json and on the console, one inside it or at
// its ends (within round-off) is not, nor is a loss of contact wholly inside, a pantograph that did
// not cross the section is left out, and a run without a pilot's estimate gets no list.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "pcsim/simulation/accuracy_pilot.hpp"
#include "pcsim/simulation/pilot_extremes.hpp"

namespace {

using namespace pcsim;

output::PantographStatistics pantograph(const std::string& name, double max_x, double min_x,
                                        bool complete = true) {
  output::PantographStatistics p;
  p.name = name;
  p.complete = complete;
  p.force.actual_max_x = max_x;
  p.force.actual_min_x = min_x;
  return p;
}

nlohmann::json facts_with_pilot(double from_x, double to_x) {
  nlohmann::json facts;
  facts["accuracy_estimate"]["pilot"] = {{"from_x", from_x}, {"to_x", to_x}};
  return facts;
}

TEST(PilotExtremes, OnlyExtremesOutsideTheStretchAreListed) {
  output::RunStatistics stats;
  stats.pantographs = {pantograph("leading", 165.0, 275.0),   // the stretch's ends: inside
                       pantograph("trailing", 327.8, 282.7),  // both beyond it
                       pantograph("third", 100.0, 200.0),     // the maximum before it
                       pantograph("late", 400.0, 400.0, false)};
  const auto out = simulation::extremes_outside_pilot(stats, 165.0, 275.0);
  ASSERT_EQ(out.size(), 3u);
  EXPECT_EQ(out[0].pantograph, "trailing");
  EXPECT_STREQ(simulation::kPilotFigureKeys[out[0].figure], "actual_max_percent");
  EXPECT_EQ(out[0].at_x, 327.8);
  EXPECT_STREQ(simulation::kPilotFigureKeys[out[1].figure], "actual_min_percent_of_mean");
  EXPECT_EQ(out[1].at_x, 282.7);
  EXPECT_EQ(out[2].pantograph, "third");
  EXPECT_STREQ(simulation::kPilotFigureKeys[out[2].figure], "actual_max_percent");
}

// A support that ends the stretch, its x from another sum of span lengths,
// is inside within 1e-9 m (the section's bounds' tolerance); a millimetre
// beyond is not.
TEST(PilotExtremes, AnExtremeAtTheStretchsEndWithinRoundOffIsInside) {
  output::RunStatistics stats;
  const double from_x = 0.1 + 0.2, to_x = 3 * 55.3;  // 0.30000000000000004, 165.89999999999998
  stats.pantographs = {pantograph("leading", 165.9, 0.3), pantograph("trailing", to_x + 1e-3, 0.3)};
  stats.max_uplift_x = 165.9;
  const auto out = simulation::extremes_outside_pilot(stats, from_x, to_x);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].pantograph, "trailing");
  EXPECT_STREQ(simulation::kPilotFigureKeys[out[0].figure], "actual_max_percent");
}

TEST(PilotExtremes, SummaryAndConsoleSayWhichAndWhere) {
  output::RunStatistics stats;
  stats.pantographs = {pantograph("leading", 170.0, 180.0), pantograph("trailing", 327.8, 200.0)};
  auto facts = facts_with_pilot(165.0, 275.0);
  simulation::add_extremes_outside_pilot(stats, facts);
  const auto& list = facts["accuracy_estimate"]["extremes_outside_pilot"];
  ASSERT_EQ(list.size(), 1u);
  EXPECT_EQ(list[0]["pantograph"], "trailing");
  EXPECT_EQ(list[0]["figure"], "actual_max_percent");
  EXPECT_EQ(list[0]["at_x_m"].get<double>(), 327.8);
  const std::string text = simulation::extremes_outside_pilot_text(facts);
  EXPECT_NE(text.find("the actual maximum of 'trailing' falls at x = 327.8 m, outside the "
                      "pilot's stretch (x 165-275 m)"),
            std::string::npos)
      << text;
  EXPECT_EQ(text.find("leading"), std::string::npos) << text;
}

// The line's largest uplift at a support is each pantograph's uplift figure:
// listed for each where its support lies outside, said once on the console.
TEST(PilotExtremes, TheUpliftsSupportOutsideIsListedForEachPantographAndSaidOnce) {
  output::RunStatistics stats;
  stats.pantographs = {pantograph("leading", 170.0, 180.0), pantograph("trailing", 200.0, 210.0),
                       pantograph("late", 400.0, 400.0, false)};
  stats.max_uplift_x = 330.0;
  auto facts = facts_with_pilot(165.0, 275.0);
  simulation::add_extremes_outside_pilot(stats, facts);
  const auto& list = facts["accuracy_estimate"]["extremes_outside_pilot"];
  ASSERT_EQ(list.size(), 2u) << list.dump();
  for (const auto& e : list) {
    EXPECT_EQ(e["figure"], "uplift_percent");
    EXPECT_EQ(e["at_x_m"].get<double>(), 330.0);
  }
  EXPECT_EQ(list[0]["pantograph"], "leading");
  EXPECT_EQ(list[1]["pantograph"], "trailing");
  const std::string text = simulation::extremes_outside_pilot_text(facts);
  const std::string said = "the largest uplift at a support falls at x = 330.0 m, outside";
  ASSERT_NE(text.find(said), std::string::npos) << text;
  EXPECT_EQ(text.find(said, text.find(said) + 1), std::string::npos) << text;
  for (double inside_or_none : {275.0, std::nan("")}) {  // the stretch's end; no support rose
    stats.max_uplift_x = inside_or_none;
    EXPECT_TRUE(simulation::extremes_outside_pilot(stats, 165.0, 275.0).empty());
  }
}

// A loss of contact is counted where the contact is lost: listed with its
// first sample outside the stretch and how many of its samples are, said on
// the console; one wholly inside the stretch, or none, is not listed.
TEST(PilotExtremes, ALossOfContactOutsideTheStretchIsListedWithItsSamples) {
  output::RunStatistics stats;
  stats.pantographs = {pantograph("leading", 200.0, 210.0), pantograph("trailing", 220.0, 230.0),
                       pantograph("third", 240.0, 250.0)};
  stats.pantographs[0].force.lost_x = {170.0, 275.0};                // inside, its end included
  stats.pantographs[1].force.lost_x = {160.0, 200.0, 301.5, 301.6};  // three of four outside
  auto facts = facts_with_pilot(165.0, 275.0);
  simulation::add_extremes_outside_pilot(stats, facts);
  const auto& list = facts["accuracy_estimate"]["extremes_outside_pilot"];
  ASSERT_EQ(list.size(), 1u) << list.dump();
  EXPECT_EQ(list[0]["pantograph"], "trailing");
  EXPECT_EQ(list[0]["figure"], "loss_of_contact_points");
  EXPECT_EQ(list[0]["at_x_m"].get<double>(), 160.0);
  EXPECT_EQ(list[0]["samples_outside"].get<int>(), 3);
  EXPECT_EQ(list[0]["samples"].get<int>(), 4);
  const std::string text = simulation::extremes_outside_pilot_text(facts);
  EXPECT_NE(text.find("the loss of contact of 'trailing' has 3 of its 4 samples at zero outside "
                      "the pilot's stretch (x 165-275 m), the first at x = 160.0 m"),
            std::string::npos)
      << text;
  EXPECT_EQ(text.find("leading"), std::string::npos) << text;
}

TEST(PilotExtremes, EveryExtremeInsideGivesAnEmptyListAndNoLine) {
  output::RunStatistics stats;
  stats.pantographs = {pantograph("pantograph", 200.0, 250.0)};
  auto facts = facts_with_pilot(165.0, 275.0);
  simulation::add_extremes_outside_pilot(stats, facts);
  EXPECT_TRUE(facts["accuracy_estimate"]["extremes_outside_pilot"].is_array());
  EXPECT_TRUE(facts["accuracy_estimate"]["extremes_outside_pilot"].empty());
  EXPECT_EQ(simulation::extremes_outside_pilot_text(facts), "");
}

TEST(PilotExtremes, NoPilotNoList) {
  output::RunStatistics stats;
  stats.pantographs = {pantograph("pantograph", 900.0, 900.0)};
  for (nlohmann::json facts :
       {nlohmann::json::object(), nlohmann::json{{"accuracy_estimate", {{"pilot", nullptr}}}}}) {
    simulation::add_extremes_outside_pilot(stats, facts);
    EXPECT_FALSE(facts.contains("accuracy_estimate") &&
                 facts["accuracy_estimate"].contains("extremes_outside_pilot"))
        << facts.dump();
    EXPECT_EQ(simulation::extremes_outside_pilot_text(facts), "");
  }
}

}  // namespace
