// The warning for an FE level that integrates the whole of a long line a
// moving window would serve (scene/run_modal_method.cpp, warn_whole_fe_line).
#include <gtest/gtest.h>

#include <string>

#include "pcsim/scene/composition.hpp"
#include "pcsim/scene/run_scene.hpp"

namespace {

using namespace pcsim;

// The warnings of a run scene with the overrides.
std::vector<InputWarning> warnings(const std::string& scene_file,
                                   const std::vector<std::string>& overrides) {
  std::vector<scene::InputOverride> parsed;
  for (const auto& o : overrides)
    parsed.push_back(scene::parse_override(o, {"", "test --set " + o}));
  const auto scene = scene::load_composed(std::string(PCSIM_SOURCE_DIR) + "/" + scene_file, parsed);
  return scene::load_run_scene(scene).warnings;
}

// The warning on the key 'window', or "" if there is none.
std::string window_warning(const std::vector<InputWarning>& list) {
  for (const auto& w : list)
    if (w.key == "window") return w.reason;
  return "";
}

const char* kOne = "runs/en50318-300.yaml";  // one pantograph: a window of 2 + 2 + 3 = 7 spans
const char* kTwo = "runs/interaction/two-pantographs-300.yaml";  // 200 m apart: 11 spans

TEST(WholeLineWarning, TheFactorIsTheThreshold) {
  // 10 x 7 spans: the first line that warns.
  EXPECT_EQ(window_warning(warnings(kOne, {"catenary.design.spans.count=69"})), "");
  const std::string w = window_warning(warnings(kOne, {"catenary.design.spans.count=70"}));
  EXPECT_NE(w.find("the linear catenary integrates the whole line, 70 identical spans"),
            std::string::npos)
      << w;
  EXPECT_NE(w.find("a moving window would integrate 7 of them"), std::string::npos) << w;
}

TEST(WholeLineWarning, ATrainsWindowCountsItsSpans) {
  EXPECT_EQ(window_warning(warnings(kTwo, {"catenary.design.spans.count=109"})), "");
  const std::string w = window_warning(
      warnings(kTwo, {"catenary.design.spans.count=1000", "catenary.model=nonlinear"}));
  EXPECT_NE(w.find("the nonlinear catenary integrates the whole line, 1000 identical spans"),
            std::string::npos)
      << w;
  EXPECT_NE(w.find("would integrate 11 of them"), std::string::npos) << w;
}

TEST(WholeLineWarning, NoneWhereTheSceneChoseOrAWindowDoesNotFit) {
  // A window given, the modal level (it chooses a window itself), an output
  // that needs the whole line, a pantograph starting beyond a window's reach.
  EXPECT_EQ(
      window_warning(warnings(kOne, {"catenary.design.spans.count=80", "window.spans_behind=2"})),
      "");
  EXPECT_EQ(
      window_warning(warnings(kOne, {"catenary.design.spans.count=80", "catenary.model=modal"})),
      "");
  EXPECT_EQ(window_warning(
                warnings(kOne, {"catenary.design.spans.count=80", "output.dropper_forces=true"})),
            "");
  EXPECT_EQ(window_warning(warnings(
                kOne, {"catenary.design.spans.count=80", "pantographs[0].start_x=1000",
                       "simulation.end_x=1400", "analysis.from_span=18", "analysis.to_span=20"})),
            "");
}

}  // namespace
