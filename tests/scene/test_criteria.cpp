// Criteria sets as data (scene/criteria_reader.hpp, output/assessment.hpp,
// docs/assessment.md): the built-in sets, errors in a set file naming the
// file and key, the default choice of set, the 'assessment' keys, and the
// verdicts (an unsourced criterion is "unverified", never pass or fail).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "pcsim/output/assessment.hpp"
#include "pcsim/scene/composition.hpp"
#include "pcsim/scene/criteria_reader.hpp"

namespace {

using namespace pcsim;
namespace fs = std::filesystem;

const std::string kRuns = std::string(PCSIM_SOURCE_DIR) + "/runs/";

scene::RunScene load(const std::string& scene, const std::vector<std::string>& overrides = {}) {
  std::vector<scene::InputOverride> parsed;
  for (const auto& o : overrides) parsed.push_back(scene::parse_override(o, {"", "test --set " + o}));
  return scene::load_run_scene(scene::load_composed(kRuns + scene, parsed));
}

// The InputError of reading 'text' as a criteria set file.
InputError set_error(const std::string& text) {
  const std::string file = (fs::temp_directory_path() / "pcsim-test-criteria.yaml").string();
  std::ofstream(file) << text;
  try {
    scene::read_criteria_set(scene::InputNode::load_file(file), {300, 300, "AC"});
  } catch (const InputError& e) {
    fs::remove(file);
    return e;
  }
  fs::remove(file);
  ADD_FAILURE() << "no error for:\n" << text;
  return InputError("", "", "");
}

const char* const kGoodSet = R"(name: my-line
title: a line's own criteria
criteria:
  - {key: mean, figure: mean_N, label: mean, unit: N, upper: {speed_curve: [0.00047, 90]},
     clause: "spec 1.2", source: "our spec", sourced: true}
  - {key: sigma, figure: std_N, label: sigma, unit: N, upper: {factor: 0.3, of: mean_N},
     clause: "spec 1.3", source: "our spec", sourced: true}
  - {key: smin, figure: stat_min_N, label: min, unit: N, lower: {constant: 0, strict: true},
     clause: "spec 1.4", source: "a guess", sourced: false}
  - {key: uplift, figure: uplift_mm, label: S0, unit: mm, upper: {factor: 0.5, of: steady_arm_space_mm},
     clause: "spec 1.5", source: "our spec", sourced: true}
  - {key: fast, figure: max_N, upper: {constant: 350}, when: {line_speed_kmh: {above: 320}},
     clause: "spec 1.6", source: "our spec", sourced: true}
)";

TEST(CriteriaSets, BuiltInSetsAreReadable) {
  const auto names = scene::builtin_criteria_sets();
  EXPECT_EQ(names, (std::vector<std::string>{"en50318-2002", "en50367-ac", "en50367-dc"}));
  // EN 50318: its eight figures, ranged at 300 km/h, without ranges at 280 km/h.
  const auto en50318 = scene::builtin_criteria_set("en50318-2002", {300, 300, "AC"});
  ASSERT_EQ(en50318.criteria.size(), 8u);
  EXPECT_EQ(en50318.criteria[0].figure, "mean_N");
  EXPECT_EQ(en50318.criteria[0].upper.a, 120);
  EXPECT_TRUE(en50318.criteria[0].sourced);
  for (const auto& c : scene::builtin_criteria_set("en50318-2002", {280, 280, "AC"}).criteria)
    EXPECT_EQ(c.upper.kind, CriterionBound::Kind::none);
  // EN 50367 AC: the rows above 200 km/h; nothing in it is sourced.
  const auto ac = scene::builtin_criteria_set("en50367-ac", {300, 300, "AC"});
  EXPECT_EQ(ac.criteria.size(), 6u);
  for (const auto& c : ac.criteria) {
    EXPECT_FALSE(c.sourced) << c.key;
    EXPECT_FALSE(c.clause.empty()) << c.key;
  }
  EXPECT_EQ(scene::builtin_criteria_set("en50367-ac", {160, 160, "AC"}).criteria.size(), 6u);
  // EN 50367 DC: one mean-force curve per system.
  const auto dc3 = scene::builtin_criteria_set("en50367-dc", {200, 200, "DC3kV"});
  const auto dc15 = scene::builtin_criteria_set("en50367-dc", {200, 200, "DC1.5kV"});
  EXPECT_EQ(dc3.criteria[0].upper.a, 0.00097);
  EXPECT_EQ(dc15.criteria[0].upper.a, 0.00228);
}

TEST(CriteriaSets, AUserSetIsReadAndItsRowsChosenBySpeed) {
  const std::string file = (fs::temp_directory_path() / "pcsim-test-good-set.yaml").string();
  std::ofstream(file) << kGoodSet;
  const auto at300 = scene::read_criteria_set(scene::InputNode::load_file(file), {300, 300, "AC"});
  const auto at330 = scene::read_criteria_set(scene::InputNode::load_file(file), {300, 330, "AC"});
  fs::remove(file);
  EXPECT_EQ(at300.name, "my-line");
  EXPECT_EQ(at300.criteria.size(), 4u);
  EXPECT_EQ(at330.criteria.size(), 5u);  // the line speed chooses the 'fast' row
  EXPECT_EQ(at300.criteria[1].upper.kind, CriterionBound::Kind::factor);
  EXPECT_EQ(at300.criteria[1].upper.of, "mean_N");
}

TEST(CriteriaSets, ErrorsNameTheFileAndTheKey) {
  struct Case {
    std::string text, key, reason;
  };
  const std::string head = "name: x\ncriteria:\n";
  const std::string ok = "clause: c, source: s, sourced: true";
  const std::vector<Case> cases = {
      {head + "  - {key: a, figure: mean_force, upper: {constant: 1}, " + ok + "}\n",
       "criteria[0].figure", "must be one of"},
      {head + "  - {key: a, figure: mean_N, uper: {constant: 1}, " + ok + "}\n", "criteria[0].uper",
       ""},
      {head + "  - {key: a, figure: mean_N, upper: {constant: 1}, clause: c, source: s}\n",
       "criteria[0]", "sourced"},
      {head + "  - {key: a, figure: mean_N, upper: {constant: 1, factor: 2}, " + ok + "}\n",
       "criteria[0].upper", "exactly one"},
      {head + "  - {key: a, figure: mean_N, upper: {factor: 2, of: speed}, " + ok + "}\n",
       "criteria[0].upper.of", "must be a figure"},
      {head + "  - {key: a, figure: mean_N, upper: {speed_curve: [1]}, " + ok + "}\n",
       "criteria[0].upper.speed_curve", "a v^2 + b"},
      {"name: x\nelectrification: AC25kV\ncriteria: []\n", "electrification", "DC1.5kV"},
      {"name: x\n", "", "either 'criteria'"},
  };
  for (const auto& c : cases) {
    const InputError e = set_error(c.text);
    EXPECT_NE(e.file().find("pcsim-test-criteria.yaml"), std::string::npos) << e.what();
    EXPECT_EQ(e.key(), c.key) << e.what();
    EXPECT_NE(e.reason().find(c.reason), std::string::npos) << e.what();
  }
}

TEST(CriteriaChoice, TheReferenceCaseGetsEn50318) {
  const auto run = load("en50318-300.yaml");
  EXPECT_EQ(run.assessment.set.name, "en50318-2002");
  EXPECT_EQ(run.assessment.choice, "default: the EN 50318 reference case");
  // Shortened (spans.count) and at 250 km/h it is still the reference case.
  EXPECT_EQ(load("interaction/en50318-250.yaml").assessment.set.name, "en50318-2002");
  EXPECT_EQ(load("en50318-300.yaml", {"catenary.design.spans.count=8", "simulation.end_x=475"})
                .assessment.set.name,
            "en50318-2002");
}

TEST(CriteriaChoice, OtherScenesGetEn50367) {
  const auto two = load("interaction/two-pantographs-300.yaml");
  EXPECT_EQ(two.assessment.set.name, "en50367-ac");
  EXPECT_NE(two.assessment.choice.find("2 pantographs"), std::string::npos);
  const auto cases = std::vector<std::pair<std::vector<std::string>, std::string>>{
      {{"simulation.speed_kmh=280"}, "no ranges at 280"},
      {{"pantographs[0].static_force=100"}, "static force 100"},
      {{"catenary.design.wires.contact.tension=22000"}, "not the reference catenary"},
      {{"pantographs[0].model.stages[0].mass=7.5"}, "not the reference two-mass model"}};
  for (const auto& [overrides, why] : cases) {
    const auto run = load("en50318-300.yaml", overrides);
    EXPECT_EQ(run.assessment.set.name, "en50367-ac") << overrides[0];
    EXPECT_NE(run.assessment.choice.find(why), std::string::npos) << run.assessment.choice;
  }
  // A DC line gets the DC set; a scene names any set.
  EXPECT_EQ(load("en50318-300.yaml", {"assessment.electrification=DC3kV"}).assessment.set.name,
            "en50367-dc");
  const auto named =
      load("interaction/two-pantographs-300.yaml", {"assessment.criteria=en50318-2002"});
  EXPECT_EQ(named.assessment.set.name, "en50318-2002");
  EXPECT_EQ(named.assessment.choice, "scene");
}

TEST(CriteriaChoice, WrongAssessmentKeysNameTheKey) {
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"assessment.criteria=en50368"}, "assessment.criteria"},
      {{"assessment.criteria=missing/set.yaml"}, "assessment.criteria"},
      {{"assessment.electrification=DC"}, "assessment.electrification"},
      {{"assessment.criteria=en50367-ac", "assessment.electrification=DC3kV"},
       "assessment.electrification"},
      {{"assessment.criteria=en50367-dc"}, "assessment.electrification"},
      {{"assessment.line_speed_kmh=-3"}, "assessment.line_speed_kmh"},
      {{"assessment.speed=3"}, "assessment.speed"}};
  for (const auto& [overrides, key] : cases) {
    try {
      load("en50318-300.yaml", overrides);
      ADD_FAILURE() << "accepted " << overrides.back();
    } catch (const InputError& e) {
      EXPECT_EQ(e.key(), key) << e.what();
    }
  }
}

TEST(Verdicts, UnsourcedCriteriaAreUnverifiedNeverPassOrFail) {
  Assessment a;
  a.set = scene::builtin_criteria_set("en50367-ac", {300, 300, "AC"});
  const nlohmann::json stats = {{"mean_N", 500.0},    {"std_N", 1.0},
                                {"stat_min_N", -5.0}, {"max_N", 900.0},
                                {"min_N", 10.0},      {"loss_of_contact_percent", 9.0}};
  const auto judged = output::judge(a, output::criteria_values(stats, 0.05, a), 300);
  ASSERT_EQ(judged.size(), 6u);
  for (const auto& j : judged)
    if (j.criterion.figure == "uplift_mm")
      EXPECT_EQ(j.verdict, "no input");  // no steady_arm_space_mm
    else
      EXPECT_EQ(j.verdict, "unverified") << j.criterion.key;
  EXPECT_EQ(output::overall_verdict(judged), "unverified");
  EXPECT_EQ(output::limit_text(judged[0]), "<= 132.3");  // 0.00047 * 300^2 + 90
  const auto json = output::assessment_json(a, {{"p", judged}});
  EXPECT_EQ(json["criteria"], "en50367-ac");
  EXPECT_EQ(json["pantographs"]["p"]["verdict"], "unverified");
  EXPECT_EQ(json["pantographs"]["p"]["criteria"][0]["sourced"], false);
  const std::string table = output::assessment_table(a, judged);
  EXPECT_EQ(table.find("FAIL"), std::string::npos);
  EXPECT_EQ(table.find("pass"), std::string::npos);
  EXPECT_NE(table.find("unverified"), std::string::npos);
}

TEST(Verdicts, SourcedCriteriaPassOrFail) {
  const std::string file = (fs::temp_directory_path() / "pcsim-test-good-set2.yaml").string();
  std::ofstream(file) << kGoodSet;
  Assessment a;
  a.set = scene::read_criteria_set(scene::InputNode::load_file(file), {300, 300, "AC"});
  fs::remove(file);
  a.steady_arm_space_mm = 100;
  const nlohmann::json stats = {{"mean_N", 120.0}, {"std_N", 40.0}, {"stat_min_N", 0.0}};
  const auto judged = output::judge(a, output::criteria_values(stats, 0.06, a), 300);
  ASSERT_EQ(judged.size(), 4u);
  EXPECT_EQ(judged[0].verdict, "pass");        // 120 <= 132.3
  EXPECT_EQ(judged[1].verdict, "fail");        // 40 > 0.3 * 120
  EXPECT_EQ(judged[2].verdict, "unverified");  // sourced: false
  EXPECT_EQ(judged[3].verdict, "fail");        // 60 mm > 0.5 * 100 mm
  EXPECT_EQ(output::limit_text(judged[2]), "> 0");
  EXPECT_EQ(output::overall_verdict(judged), "fail");
}

}  // namespace
