// Design files of real lines (meshes/lines/*.yaml): every committed design
// builds, the reader fills the new keys, and a bad value of every new key is
// one error naming the file, the key and the reason.
#include <stdlib.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "design_test_helpers.hpp"
#include "pcsim/catenary/geometry.hpp"

using namespace pcsim;
using namespace pcsim::design_test;
using catenary::CatenaryMesh;

namespace {

const std::string kLines = kMeshes + "lines/";

std::string text_of(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

TEST(LineDesignFiles, EveryCommittedDesignBuilds) {
  struct Expect {
    const char* file;
    std::size_t contact_wires;
  };
  for (const auto& e : {Expect{"three-sections.yaml", 3}, Expect{"three-sections-short.yaml", 3},
                        Expect{"stitched.yaml", 1}, Expect{"unstitched.yaml", 1},
                        Expect{"presag-droppers.yaml", 1}, Expect{"presag-heights.yaml", 1},
                        Expect{"supports.yaml", 1}, Expect{"irregular-profile.yaml", 1},
                        Expect{"irregular-random.yaml", 1}, Expect{"curved.yaml", 3}}) {
    CatenaryMesh m;
    ASSERT_NO_THROW(m = scene::load_catenary_design(kLines + e.file)) << e.file;
    EXPECT_EQ(m.contact_wire_list().size(), e.contact_wires) << e.file;
  }
}

TEST(LineDesignFiles, ReaderFillsTheNewKeys) {
  const auto root = scene::InputNode::load_file(kLines + "supports.yaml");
  const auto d = scene::read_parametric_design(root);
  EXPECT_EQ(d.messenger_supports.model, catenary::MessengerSupportModel::spring_mass);
  EXPECT_EQ(d.messenger_supports.stiffness, 2.0e6);
  EXPECT_EQ(d.messenger_supports.mass, 8.0);
  EXPECT_EQ(d.steady_arms.model, catenary::SteadyArmModel::hinged);
  EXPECT_EQ(d.steady_arms.length, 1.0);
  ASSERT_EQ(d.support_overrides.size(), 1u);
  EXPECT_EQ(d.support_overrides[0].supports, (std::vector<long>{4, 5}));
  EXPECT_EQ(d.support_overrides[0].steady_arm->model, catenary::SteadyArmModel::spring);
  EXPECT_EQ(d.tensioning.device, catenary::TensioningDeviceKind::spring);
  EXPECT_EQ(d.tensioning.stiffness, 2.0e5);
  const auto h =
      scene::read_parametric_design(scene::InputNode::load_file(kLines + "presag-heights.yaml"));
  EXPECT_EQ(h.presag_profile, catenary::PresagProfile::heights);
  ASSERT_EQ(h.droppers.spans.size(), 1u);
  EXPECT_EQ(h.droppers.spans[0].spans, (std::vector<long>{3, 4}));
  EXPECT_EQ(h.droppers.spans[0].sags.size(), 5u);
  const auto p =
      scene::read_parametric_design(scene::InputNode::load_file(kLines + "irregular-profile.yaml"));
  EXPECT_EQ(p.irregularities.profile_x.size(), 801u);  // 100..300 m every 0.25 m
  EXPECT_EQ(p.irregularities.wear.size(), 1u);
  const auto c = scene::read_parametric_design(scene::InputNode::load_file(kLines + "curved.yaml"));
  ASSERT_EQ(c.sections.size(), 3u);
  EXPECT_EQ(c.sections[1].radius, 1200.0);
  // overlap.anchor_raise defaults to twice the raise.
  const auto o = scene::read_parametric_design(scene::InputNode::load_string(
      replace_once(text_of(kLines + "three-sections-short.yaml"),
                   "overlap: {spans: 2, raise: 0.3, anchor_raise: 0.6, separation: 0.2}",
                   "overlap: {raise: 0.25}"),
      "v.yaml"));
  EXPECT_EQ(o.overlap.anchor_raise, 0.5);
  EXPECT_EQ(o.overlap.spans, 2);
}

TEST(LineDesignFiles, BadValuesOfEveryNewKey) {
  const std::string base = text_of(kLines + "three-sections-short.yaml");
  struct Case {
    std::string from, to, key, reason;
  };
  const std::string sections = "sections: [{spans: 3}, {spans: 3}, {spans: 3}]";
  const std::string overlap = "overlap: {spans: 2, raise: 0.3, anchor_raise: 0.6, separation: 0.2}";
  const std::string tensioning = "tensioning: {device: weight, ratio: 3}";
  const std::string arms = "steady_arms: {mass: 1.0, model: constraint}";
  const std::string positions = "positions: [5.0, 12.5, 20.0, 25.0, 30.0, 37.5, 45.0]";
  const std::vector<Case> cases = {
      {sections, "sections: [{spans: 3}, {spans: 3}, {spans: 4}]", "'sections'", "add up to 10"},
      {sections, "sections: [{spans: 3}, {spans: 0}, {spans: 6}]", "'sections[1].spans'",
       "at least 1"},
      // The section named is the short one (m = 2): a first section needs
      // 2 spans, a middle one 3, a last one 2.
      {sections, "sections: [{spans: 1}, {spans: 2}, {spans: 6}]", "'sections[0].spans'",
       "a first section needs at least 2"},
      {"spans: {count: 9, length: 50.0}\n" + sections,
       "spans: {count: 7, length: 50.0}\nsections: [{spans: 1}, {spans: 3}, {spans: 3}]",
       "'sections[0].spans'", "section 1 of 1 spans is too short"},
      {sections, "sections: [{spans: 3}, {spans: 2}, {spans: 4}]", "'sections[1].spans'",
       "a middle section needs at least 3"},
      {sections, "sections: [{spans: 4}, {spans: 4}, {spans: 1}]", "'sections[2].spans'",
       "a last section needs at least 2"},
      {sections, "sections: [{spans: 3}, {spans: 3, radius: 20}, {spans: 3}]",
       "'sections[1].radius'", "at least the span length"},
      {sections, "sections: [{spans: 3}, {spans: 3, curve: 20}, {spans: 3}]", "'sections[1].curve'",
       "unknown key"},
      {sections, "sections: []", "'sections'", "non-empty list"},
      {overlap, "overlap: {spans: 0}", "'overlap.spans'", "at least 1"},
      {overlap, "overlap: {raise: -0.1}", "'overlap.raise'", "must be positive"},
      {overlap, "overlap: {raise: 0.3, anchor_raise: 0.2}", "'overlap.anchor_raise'",
       "at least overlap.raise"},
      {overlap, "overlap: {separation: -1}", "'overlap.separation'", "must not be negative"},
      {tensioning, "tensioning: {device: weight, ratio: 0.5}", "'tensioning.ratio'", "at least 1"},
      {tensioning, "tensioning: {device: weight, weight_mass: -3}", "'tensioning.weight_mass'",
       "must be positive"},
      {tensioning, "tensioning: {device: pulley}", "'tensioning.device'",
       "must be one of fixed, weight, spring"},
      {tensioning, "tensioning: {device: spring}", "'tensioning.stiffness'", "missing"},
      {tensioning, "tensioning: {device: spring, stiffness: 0}", "'tensioning.stiffness'",
       "must be positive"},
      {tensioning, "tensioning: {device: spring, stiffness: 1e5, ratio: 3}", "'tensioning.ratio'",
       "only for device 'weight'"},
      {arms, "steady_arms: {model: hinged, mass: 1.0}", "'steady_arms.length'", "missing"},
      {arms, "steady_arms: {model: hinged, length: 0, mass: 1}", "'steady_arms.length'",
       "must be positive"},
      {arms, "steady_arms: {model: hinged, length: 1, axial_stiffness: -5}",
       "'steady_arms.axial_stiffness'", "must be positive"},
      {arms, "steady_arms: {model: spring, stiffness: -1}", "'steady_arms.stiffness'",
       "must be positive"},
      {arms, "steady_arms: {model: constraint, length: 1}", "'steady_arms.length'",
       "only for model 'hinged'"},
      {arms, "steady_arms: {mass: -1}", "'steady_arms.mass'", "must not be negative"},
      {"", "messenger_supports: {model: spring}", "'messenger_supports.stiffness'", "missing"},
      {"", "messenger_supports: {model: spring_mass, stiffness: 1e6, mass: 0}",
       "'messenger_supports.mass'", "must be positive"},
      {"", "messenger_supports: {model: rubber}", "'messenger_supports.model'",
       "must be one of fixed, spring, spring_mass"},
      // Keys the model does not use, and their signs.
      {"", "messenger_supports: {model: fixed, stiffness: -5}", "'messenger_supports.stiffness'",
       "only for models 'spring' and 'spring_mass'"},
      {"", "messenger_supports: {model: spring, stiffness: 1e6, mass: -2}",
       "'messenger_supports.mass'", "only for model 'spring_mass'"},
      {"", "messenger_supports: {model: spring, stiffness: -1e6}", "'messenger_supports.stiffness'",
       "must be positive"},
      {"", "support_overrides: [{supports: [3], messenger_supports: {mass: 8}}]",
       "'support_overrides[0].messenger_supports.mass'", "only for model 'spring_mass'"},
      {"",
       "support_overrides: [{supports: [3], messenger_supports: {model: spring_mass, "
       "stiffness: 1e6, mass: -8}}]",
       "'support_overrides[0].messenger_supports.mass'", "must be positive"},
      // A support in two entries, or twice in one.
      {"",
       "support_overrides: [{supports: [3, 4], steady_arms: {mass: 2}}, {supports: [4], "
       "messenger_supports: {model: spring, stiffness: 1e6}}]",
       "'support_overrides[1].supports[0]'", "listed twice (also in support_overrides[0])"},
      {"", "support_overrides: [{supports: [3, 3], steady_arms: {mass: 2}}]",
       "'support_overrides[0].supports[1]'", "support 3 is listed twice"},
      // Overrides without effect at the line's wire ends.
      {"",
       "support_overrides: [{supports: [9], messenger_supports: {model: spring, stiffness: 1e6}}]",
       "'support_overrides[0].supports[0]'", "support 9 is a wire end: the messenger is anchored"},
      {"", "support_overrides: [{supports: [2, 0], steady_arms: {model: spring, stiffness: 2000}}]",
       "'support_overrides[0].supports[1]'", "give model 'constraint'"},
      {"", "support_overrides: [{supports: [3, 12], steady_arms: {mass: 2}}]",
       "'support_overrides[0].supports[1]'", "not on the line (0..9)"},
      {"", "support_overrides: [{supports: [3]}]", "'support_overrides[0]'",
       "must give messenger_supports or steady_arms"},
      {"", "support_overrides: [{supports: [3], steady_arms: {model: spring, stiffness: 0}}]",
       "'support_overrides[0].steady_arms.stiffness'", "must be positive"},
      {"", "presag: {profile: sine, sag: 0.1}", "'presag.profile'",
       "must be one of parabola, droppers, heights"},
      {"", "presag: {profile: parabola, sag: -0.01}", "'presag.sag'", "must not be negative"},
      {"", "presag: -0.01", "key 'presag'", "must not be negative"},
      {positions, positions + "\n  sags: [0, 0, 0]", "'droppers.sags'",
       "only with the presag profile 'heights'"},
      {positions, positions + "\n  spans: [{spans: [2, 11], positions: [10, 20]}]",
       "'droppers.spans[0].spans[1]'", "not on the line (1..9)"},
      {positions, positions + "\n  spans: [{spans: [2], positions: [10, 60]}]",
       "'droppers.spans[0].positions[1]'", "outside the span"},
      {positions,
       positions + "\n  spans: [{spans: [2], positions: [10]}, {spans: [2], positions: [20]}]",
       "'droppers.spans[1].spans[0]'", "listed twice"},
      {"", "irregularities: {random: {rms: -0.001}}", "'irregularities.random.rms'",
       "must not be negative"},
      {"", "irregularities: {random: {rms: 0.001, wavelength_min: 5, wavelength_max: 2}}",
       "'irregularities.random.wavelength_max'", "must exceed wavelength_min"},
      {"", "irregularities: {random: {rms: 0.001, spectrum: pink}}",
       "'irregularities.random.spectrum'", "must be one of uniform, power_law"},
      {"", "irregularities: {random: {rms: 0.001, exponent: 2}}",
       "'irregularities.random.exponent'", "only for spectrum 'power_law'"},
      {"", "irregularities: {random: {rms: 0.5}}", "'irregularities.random.rms'",
       "below a tenth of the system height"},
      {"", "irregularities: {wear: [{from: 30, to: 10, section_loss: 0.1}]}",
       "'irregularities.wear[0].to'", "must exceed 'from'"},
      {"", "irregularities: {wear: [{from: 10, to: 30, section_loss: 1.0}]}",
       "'irregularities.wear[0].section_loss'", "must lie in [0, 1)"},
      // Stretches on the line (0..450 m), not overlapping.
      {"", "irregularities: {wear: [{from: -5, to: 30, section_loss: 0.1}]}",
       "'irregularities.wear[0].from'", "must lie on the line, in [0, 450) m"},
      {"", "irregularities: {wear: [{from: 460, to: 470, section_loss: 0.1}]}",
       "'irregularities.wear[0].from'", "must lie on the line"},
      {"", "irregularities: {wear: [{from: 400, to: 451, section_loss: 0.1}]}",
       "'irregularities.wear[0].to'", "at most its length 450 m"},
      {"",
       "irregularities: {wear: [{from: 10, to: 30, section_loss: 0.1}, "
       "{from: 50, to: 60, section_loss: 0.1}, {from: 20, to: 40, section_loss: 0.2}]}",
       "'irregularities.wear[2]'", "20..40 m overlaps irregularities.wear[0] (10..30 m)"},
      {"", "irregularities: {profile: no-such-file.csv}", "'irregularities.profile'",
       "cannot open the profile file"},
  };
  for (const auto& c : cases) {
    // An empty 'from': 'to' is a new top-level key.
    const std::string text = c.from.empty() ? base + c.to + "\n" : replace_once(base, c.from, c.to);
    const std::string msg = message_of([&] { build_text(text, "v.yaml"); });
    EXPECT_TRUE(contains(msg, "v.yaml")) << c.to << " -> " << msg;
    EXPECT_TRUE(contains(msg, c.key)) << c.to << " -> " << msg;
    EXPECT_TRUE(contains(msg, c.reason)) << c.to << " -> " << msg;
  }
}

TEST(LineDesignFiles, ProfileFileErrorsNameTheLine) {
  char folder[] = "/tmp/pcsim-profile-XXXXXX";
  ASSERT_NE(mkdtemp(folder), nullptr);
  const std::string dir = folder;
  auto write = [&](const std::string& name, const std::string& text) {
    std::ofstream(dir + "/" + name) << text;
  };
  write("bad-line.csv", "x,dz\n0,0\n10 0.001 7\n");
  // No data line, or a single point: not a profile.
  for (const char* name : {"empty.csv", "header-only.csv", "one-point.csv"}) {
    write(name, std::string(name) == "header-only.csv" ? "# dz [m]\nx,dz\n\n"
                : std::string(name) == "one-point.csv" ? "x,dz\n10,0.001\n"
                                                       : "");
    write("design.yaml", text_of(kLines + "three-sections-short.yaml") +
                             "irregularities: {profile: " + name + "}\n");
    const std::string msg =
        message_of([&] { scene::load_catenary_design(dir + "/design.yaml"); });
    EXPECT_TRUE(contains(msg, "design.yaml") && contains(msg, "'irregularities.profile'") &&
                contains(msg, name) && contains(msg, "needs at least two (x, dz) points"))
        << msg;
  }
  write("decreasing.csv", "0,0\n10,0.001\n5,0\n");
  write("design.yaml", text_of(kLines + "three-sections-short.yaml") +
                           "irregularities: {profile: bad-line.csv}\n");
  std::string msg = message_of([&] { scene::load_catenary_design(dir + "/design.yaml"); });
  EXPECT_TRUE(contains(msg, "'irregularities.profile'") && contains(msg, "line 3")) << msg;
  write("design.yaml", text_of(kLines + "three-sections-short.yaml") +
                           "irregularities: {profile: decreasing.csv}\n");
  msg = message_of([&] { scene::load_catenary_design(dir + "/design.yaml"); });
  EXPECT_TRUE(contains(msg, "'irregularities.profile'") && contains(msg, "increase strictly"))
      << msg;
  std::filesystem::remove_all(dir);
}
