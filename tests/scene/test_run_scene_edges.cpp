// The warning for an analysis section within the filter's edge transient of
// the record's start or end (scene/run_scene_edges.cpp).
#include <gtest/gtest.h>

#include <string>

#include "pcsim/scene/composition.hpp"
#include "pcsim/scene/run_scene.hpp"

namespace {

using namespace pcsim;

// The warnings of EN 50318 at 300 km/h (analysis section 240-360 m, pantograph
// from 5 m, 20 Hz filter: transient length 3 / 20 Hz x 83.3 m/s = 12.5 m)
// with the overrides.
std::vector<InputWarning> warnings(const std::vector<std::string>& overrides) {
  std::vector<scene::InputOverride> parsed;
  for (const auto& o : overrides) parsed.push_back(scene::parse_override(o, {"", "test --set " + o}));
  const auto scene =
      scene::load_composed(std::string(PCSIM_SOURCE_DIR) + "/runs/en50318-300.yaml", parsed);
  return scene::load_run_scene(scene).warnings;
}

bool warns_about(const std::vector<InputWarning>& w, const std::string& key) {
  for (const auto& x : w)
    if (x.key == key && x.reason.find("transient length 12.5 m") != std::string::npos) return true;
  return false;
}

TEST(FilterEdges, TheReferenceCaseHasRoomOnBothSides) {
  EXPECT_TRUE(warnings({}).empty());
}

TEST(FilterEdges, AnEndWithinTheTransientWarns) {
  EXPECT_TRUE(warns_about(warnings({"simulation.end_x=372"}), "simulation.end_x"));
  EXPECT_FALSE(warns_about(warnings({"simulation.end_x=373"}), "simulation.end_x"));
}

TEST(FilterEdges, AStartWithinTheTransientWarns) {
  EXPECT_TRUE(warns_about(warnings({"pantographs[0].start_x=230"}), "pantographs[0].start_x"));
  EXPECT_FALSE(warns_about(warnings({"pantographs[0].start_x=227"}), "pantographs[0].start_x"));
}

}  // namespace
