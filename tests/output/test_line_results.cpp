// Statistics over the zones of a line (output/line_results.hpp): a zone the
// pantograph crossed gets the EN 50318 figures of the filtered force over its
// stretch (the same as output::force_statistics over that window), loss of contact
// counted on the raw force inside the zone only; a zone not crossed is
// incomplete.
#include <gtest/gtest.h>

#include <cmath>

#include "pcsim/output/line_results.hpp"
#include "pcsim/output/run_results.hpp"

using namespace pcsim;

TEST(LineResults, ZoneStatisticsOverEachStretch) {
  output::ContactHistory h;
  h.name = "p";
  const double v = 80.0, dt = 1e-3;
  int lost = 0, in_overlap = 0;
  for (int i = 0; i <= 5000; ++i) {  // 0..400 m
    const double t = i * dt, x = v * t;
    h.time.push_back(t);
    h.x.push_back(x);
    // 120 N with a 2 Hz wave; contact lost for a few steps around 250 m.
    double f = 120.0 + 30.0 * std::sin(2 * M_PI * 2.0 * t);
    if (std::abs(x - 250.0) < 0.4) f = 0.0, ++lost;
    in_overlap += x >= 200.0 && x <= 300.0;
    h.force.push_back(f);
    h.wire_force.push_back({f, 0.0});
  }
  const std::vector<catenary::LineZone> zones = {{"section 1", false, 60.0, 200.0},
                                                 {"overlap 1-2", true, 200.0, 300.0},
                                                 {"section 2", false, 300.0, 500.0}};
  const auto stats = output::zone_statistics(zones, h, 20.0);
  ASSERT_EQ(stats.size(), 3u);
  EXPECT_TRUE(stats[0].complete);
  EXPECT_TRUE(stats[1].complete);
  EXPECT_FALSE(stats[2].complete);  // the run ends at 400 m
  const auto filtered = output::filter_uniformly_sampled(h.time, h.force, 20.0);
  for (int z = 0; z < 2; ++z) {
    const auto ref = output::force_statistics(h.x, filtered, h.force, zones[z].from_x, zones[z].to_x);
    EXPECT_EQ(stats[z].force.samples, ref.samples);
    EXPECT_DOUBLE_EQ(stats[z].force.mean, ref.mean);
    EXPECT_DOUBLE_EQ(stats[z].force.std_dev, ref.std_dev);
    EXPECT_DOUBLE_EQ(stats[z].force.actual_min, ref.actual_min);
  }
  // The lost samples, all in the overlap.
  EXPECT_EQ(stats[0].force.loss_of_contact_percent, 0.0);
  EXPECT_GT(lost, 5);
  EXPECT_NEAR(stats[1].force.loss_of_contact_percent, 100.0 * lost / in_overlap, 1e-12);
  // The wave (amplitude 30 N below 20 Hz) passes the filter: sigma 30/sqrt(2)
  // over whole periods (section 1: 1.75 s = 3.5 periods: 2 % off).
  EXPECT_NEAR(stats[0].force.std_dev, 30.0 / std::sqrt(2.0), 0.02 * 30.0 / std::sqrt(2.0));
}
