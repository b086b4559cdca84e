// Pantograph model files through the registry of kinds and the `pcsim pantograph` study
// scenes: the model built per kind, its stated default working height, and strict
// messages (file, key, reason) for unknown kinds, effects of another kind and studies
// the model cannot run.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <functional>
#include <iterator>

#include "pcsim/scene/pantograph_reader.hpp"
#include "pcsim/scene/pantograph_scene.hpp"

using namespace pcsim;

namespace {

const std::string kModels = std::string(PCSIM_SOURCE_DIR) + "/meshes/pantographs/";

std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// A file in the build folder (the tests run there), removed at the end of the test.
struct TempFile {
  std::string path;
  TempFile(const std::string& name, const std::string& text) : path(name) {
    std::ofstream(path) << text;
  }
  ~TempFile() { std::remove(path.c_str()); }
};

}  // namespace

TEST(PantographReader, RegistryBuildsEachKind) {
  const auto& kinds = scene::pantograph_kinds();
  EXPECT_EQ(kinds.count("lumped"), 1u);
  EXPECT_EQ(kinds.count("dsa380"), 1u);
  const auto lumped = scene::load_pantograph_model(kModels + "en50318_two_mass.yaml", nullptr, 0);
  EXPECT_EQ(lumped->kind(), "lumped");
  EXPECT_EQ(lumped->dof_count(), 2);
  EXPECT_EQ(lumped->default_working_height(), 0.0);  // absolute heights
  const auto dsa = scene::load_pantograph_model(kModels + "dsa380_rigid.yaml", nullptr, 0);
  EXPECT_EQ(dsa->kind(), "dsa380");
  EXPECT_EQ(dsa->dof_count(), 4);
  EXPECT_EQ(dsa->default_working_height(), 1.2);  // above the base
}

TEST(PantographReader, UnknownOrMissingKindNamesFileAndKey) {
  const TempFile bad("pantograph_reader_bad_kind.yaml", "kind: flexibel\nname: x\n");
  const auto msg = message_of([&] { scene::load_pantograph_model(bad.path, nullptr, 0); });
  EXPECT_NE(msg.find(bad.path), std::string::npos) << msg;
  EXPECT_NE(msg.find("'kind'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("must be one of dsa380, dsa380_flexible, lumped"), std::string::npos) << msg;
  EXPECT_NE(msg.find("(got 'flexibel')"), std::string::npos) << msg;
  const TempFile none("pantograph_reader_no_kind.yaml", "name: x\n");
  const auto msg2 = message_of([&] { scene::load_pantograph_model(none.path, nullptr, 0); });
  EXPECT_NE(msg2.find("'kind'"), std::string::npos) << msg2;
  EXPECT_NE(msg2.find("missing"), std::string::npos) << msg2;
}

TEST(PantographReader, EffectOfAnotherKindRejected) {
  const auto effects = scene::InputNode::load_string("head_restraint: rotation\n", "scene.yaml");
  const auto msg = message_of(
      [&] { scene::load_pantograph_model(kModels + "en50318_two_mass.yaml", &effects, 0); });
  EXPECT_NE(msg.find("scene.yaml"), std::string::npos) << msg;
  EXPECT_NE(msg.find("head_restraint"), std::string::npos) << msg;
}

TEST(PantographReader, RegisteredKindIsUsed) {
  scene::register_pantograph_kind("test_single_mass", [](const scene::InputNode& model, const scene::InputNode*,
                                                         double speed) {
    model.allow_only({"kind", "mass", "stiffness"});
    pantograph::LumpedParameters p;
    p.stages.push_back({"head", model.get_positive("mass"), model.get_positive("stiffness"), 0.0});
    return std::make_unique<pantograph::LumpedPantograph>(p, false, speed);
  });
  const TempFile file("pantograph_reader_single.yaml",
                      "kind: test_single_mass\nmass: 3\nstiffness: 300\n");
  const auto m = scene::load_pantograph_model(file.path, nullptr, 0);
  EXPECT_EQ(m->dof_count(), 1);
  // One stage under F0 = 30 N: K q0 = −F0, so q0 = −0.1 m.
  EXPECT_NEAR(m->static_equilibrium(30.0, 1.0)[0], -0.1, 1e-14);
}

TEST(PantographScene, CalibrationNeedsDsa380AndTypeIsRequired) {
  const TempFile calib(
      "pantograph_scene_calibrate.yaml",
      "pantograph: {model: " + kModels + "en50318_two_mass.yaml}\nstudy: {type: calibrate}\n");
  const auto msg =
      message_of([&] { scene::load_pantograph_study_scene(scene::InputNode::load_file(calib.path)); });
  EXPECT_NE(msg.find(calib.path), std::string::npos) << msg;
  EXPECT_NE(msg.find("calibrate needs a dsa380 model"), std::string::npos) << msg;
  const TempFile untyped("pantograph_scene_untyped.yaml",
                         "pantograph: {model: " + kModels + "dsa380_rigid.yaml}\nstudy: {}\n");
  const auto msg2 =
      message_of([&] { scene::load_pantograph_study_scene(scene::InputNode::load_file(untyped.path)); });
  EXPECT_NE(msg2.find("'study.type'"), std::string::npos) << msg2;
}

TEST(PantographScene, TimeStudyRead) {
  const TempFile file("pantograph_scene_time.yaml",
                      "pantograph: {model: " + kModels +
                          "dsa380_rigid.yaml, effects: {head_restraint: rotation}}\n"
                          "equilibrium: {contact_force: 100, working_height: 1.1}\n"
                          "study: {type: time, schemes: [hht], dt: 2.0e-3, t_end: 0.5,\n"
                          "        force: {type: harmonic, mean: 120, amplitude: 30,"
                          " frequency_hz: 2}}\n");
  const auto s = scene::load_pantograph_study_scene(scene::InputNode::load_file(file.path));
  EXPECT_EQ(s.study_type, "time");
  EXPECT_EQ(s.contact_force, 100.0);
  EXPECT_EQ(s.working_height, 1.1);
  const auto& d = dynamic_cast<const pantograph::Dsa380Pantograph&>(*s.model);
  EXPECT_EQ(d.effects().head_restraint, pantograph::Dsa380Effects::HeadRestraint::rotation);
  const auto& t = std::get<pantograph::TimeStudy>(s.study);
  EXPECT_EQ(t.schemes, std::vector<std::string>{"hht"});
  EXPECT_EQ(t.options.dt, 2e-3);
  EXPECT_EQ(t.options.t_end, 0.5);
  EXPECT_NEAR(t.force(0.125), 150.0, 1e-12);  // 120 + 30 sin(2π·2·0.125)
}

// The DSA-380 model file's `bellows:` section (uplift characteristic) and the scene's
// switch `uplift_characteristic`: the pressure loop adds one coordinate; a bad curve or a
// loop without its valve lag is rejected naming the file and the key.
TEST(PantographReader, BellowsCharacteristicReadAndChecked) {
  std::ifstream in(kModels + "dsa380_rigid.yaml");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto begin = text.find("bellows:\n"), end = text.find("aerodynamic:", begin);
  ASSERT_NE(begin, std::string::npos);
  auto model_with = [&](const std::string& name, const std::string& bellows) {
    return TempFile(name, text.substr(0, begin) + bellows + text.substr(end));
  };
  const auto on = scene::InputNode::load_string("uplift_characteristic: true\n", "scene.yaml");
  const auto dsa = scene::load_pantograph_model(kModels + "dsa380_rigid.yaml", &on, 0);
  EXPECT_EQ(dsa->dof_count(), 4);  // the set's characteristic acts at once
  const auto loop = model_with("pantograph_reader_bellows_loop.yaml",
                               "bellows:\n  time_constant: 0.5\n  valve_time_constant: 0.05\n");
  const auto with_loop = scene::load_pantograph_model(loop.path, &on, 0);
  EXPECT_EQ(with_loop->dof_count(), 5);  // the loop's torque change
  EXPECT_EQ(with_loop->dof_names().back(), "bellows_dM");
  const auto table = model_with("pantograph_reader_bellows_table.yaml",
                                "bellows:\n  characteristic: {height: [1.0, 1.2, 1.4], force: "
                                "[110, 120, 125]}\n");
  const auto at_once = scene::load_pantograph_model(table.path, &on, 0);
  EXPECT_EQ(at_once->dof_count(), 4);  // no time constant: the torque follows at once
  const auto& d = dynamic_cast<const pantograph::Dsa380Pantograph&>(*at_once);
  EXPECT_EQ(d.parameters().bellows.forces, (std::vector<double>{110, 120, 125}));
  struct Bad {
    const char* bellows;
    const char* key;
    const char* reason;
  };
  for (const Bad& b :
       {Bad{"bellows:\n  characteristic: {height: [1.2, 1.1], force: [100, 120]}\n",
            "'bellows.characteristic.height'", "heights must increase"},
        Bad{"bellows:\n  characteristic: {height: [1.1, 1.2], force: [100, 0]}\n",
            "'bellows.characteristic.force'", "forces must be positive"},
        Bad{"bellows:\n  characteristic: linear\n", "'bellows.characteristic'", "must be"},
        Bad{"bellows:\n  time_constant: 1.0\n", "'bellows.valve_time_constant'", "must be > 0"},
        Bad{"bellows:\n  tau: 1.0\n", "tau", ""}}) {
    const auto file = model_with("pantograph_reader_bellows_bad.yaml", b.bellows);
    const auto msg = message_of([&] { scene::load_pantograph_model(file.path, nullptr, 0); });
    EXPECT_NE(msg.find(file.path), std::string::npos) << msg;
    EXPECT_NE(msg.find(b.key), std::string::npos) << msg;
    EXPECT_NE(msg.find(b.reason), std::string::npos) << msg;
  }
}
