// Composition of input files: base files, 'set' entries, --set overrides,
// and the origin every value keeps (the file for relative paths, the
// override in messages).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "pcsim/scene/catenary_scene.hpp"
#include "pcsim/scene/composition.hpp"
#include "pcsim/scene/run_scene.hpp"

namespace fs = std::filesystem;
using pcsim::InputError;
using pcsim::scene::InputNode;
using pcsim::scene::InputOverride;

namespace {

// A scratch folder with a base scene in a sub-folder (relative paths differ).
class Composition : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ =
        fs::temp_directory_path() /
        ("pcsim-composition-" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
         "-" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "base");
    const std::string meshes = std::string(PCSIM_SOURCE_DIR) + "/meshes/";
    write("base/run.yaml",
          "name: base-run\n"
          "catenary: {design: " +
              meshes +
              "en50318-reference.yaml}\n"
              "pantographs:\n"
              "  - {name: p, model: ../model.yaml, static_force: 120}\n"
              "simulation: {speed_kmh: 300, end_x: 595.0, dt: 0.001}\n"
              "analysis: {from_span: 5, to_span: 6}\n");
    fs::copy_file(meshes + "pantographs/en50318_two_mass.yaml", dir_ / "model.yaml");
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name) << text;
    return (dir_ / name).string();
  }
  static std::string message(const std::function<void()>& f) {
    try {
      f();
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }
  static InputOverride cli(const std::string& assignment) {
    return pcsim::scene::parse_override(assignment, {"", "command line --set " + assignment});
  }
  fs::path dir_;
};

}  // namespace

TEST_F(Composition, IncludingFileWinsMapsMergeListsReplace) {
  const auto path = write("study.yaml",
                          "base: base/run.yaml\nname: study\n"
                          "simulation: {speed_kmh: 250}\n"
                          "analysis: {to_span: 7}\n");
  const auto scene = pcsim::scene::load_composed(path);
  EXPECT_EQ(scene.get_string("name"), "study");
  EXPECT_EQ(scene["simulation"].get_double("speed_kmh"), 250);
  EXPECT_EQ(scene["simulation"].get_double("end_x"), 595.0);  // from the base
  EXPECT_EQ(scene["analysis"].get_int("from_span"), 5);
  EXPECT_EQ(scene["analysis"].get_int("to_span"), 7);
  EXPECT_FALSE(scene.has("base"));
  // Values keep their files: the base's model path resolves from base/.
  EXPECT_EQ(scene["pantographs"].at(0).path_value("model"), (dir_ / "base/../model.yaml").string());
  EXPECT_EQ(scene["simulation"]["end_x"].file(), (dir_ / "base/run.yaml").string());
  EXPECT_EQ(scene["simulation"]["speed_kmh"].file(), path);
  const auto run = pcsim::scene::load_run_scene(scene);
  EXPECT_NEAR(run.speed * 3.6, 250, 1e-12);
  // A list in the including file replaces the base's list whole.
  const auto two = write("two.yaml",
                         "base: base/run.yaml\npantographs:\n"
                         "  - {model: model.yaml}\n  - {model: model.yaml}\n");
  EXPECT_EQ(pcsim::scene::load_composed(two)["pantographs"].size(), 2u);
  EXPECT_FALSE(pcsim::scene::load_composed(two)["pantographs"].at(0).has("static_force"));
}

TEST_F(Composition, SetEntriesAndOverridesApplyInOrder) {
  const auto path = write("study.yaml",
                          "base: base/run.yaml\n"
                          "set:\n  pantographs[0].static_force: 100\n"
                          "  simulation.dt: 0.002\n");
  const auto scene = pcsim::scene::load_composed(
      path,
      {cli("simulation.dt=5e-4"), cli("pantographs.0.name=lead"), cli("output.snapshot_every=10")});
  EXPECT_EQ(scene["pantographs"].at(0).get_double("static_force"), 100);
  EXPECT_EQ(scene["simulation"].get_double("dt"), 5e-4);  // the command line comes last
  EXPECT_EQ(scene["pantographs"].at(0).get_string("name"), "lead");
  EXPECT_EQ(scene["output"].get_int("snapshot_every"), 10);  // a new section
  EXPECT_EQ(scene["pantographs"].at(0)["static_force"].file(),
            path + " (set pantographs[0].static_force)");
}

TEST_F(Composition, ErrorsNameTheOverride) {
  const auto path = write("study.yaml", "base: base/run.yaml\n");
  auto read = [&](const std::string& assignment) {
    return message(
        [&] { pcsim::scene::load_run_scene(pcsim::scene::load_composed(path, {cli(assignment)})); });
  };
  EXPECT_EQ(read("simulation.speed_kmh=-3"),
            "command line --set simulation.speed_kmh=-3: key 'simulation.speed_kmh': must be "
            "positive (got -3)");
  EXPECT_NE(read("simulation.sped_kmh=3")
                .find("command line --set simulation.sped_kmh=3: key "
                      "'simulation.sped_kmh': unknown key"),
            std::string::npos);
  EXPECT_NE(read("pantographs[2].name=x").find("'pantographs' has 1 entry"), std::string::npos);
  EXPECT_NE(read("simulation.speed_kmh.x=1").find("not a file whose keys can be set"),
            std::string::npos);
  // Through a file reference: a key of the design, checked by the design's builder.
  const std::string design = read("catenary.design.spans.count=0");
  EXPECT_EQ(design.rfind("command line --set catenary.design.spans.count=0 (in ", 0), 0u) << design;
  EXPECT_NE(design.find("key 'spans.count'"), std::string::npos) << design;
  EXPECT_NE(read("pantographs[0].model.stages[0].mass=-1")
                .find("key 'stages[0].mass': must be "
                      "positive"),
            std::string::npos);
  // Syntax.
  EXPECT_NE(message([] { cli("no-equals"); }).find("expected KEY=VALUE"), std::string::npos);
  EXPECT_NE(message([] { cli("a..b=1"); }).find("is not a key path"), std::string::npos);
  EXPECT_NE(message([] { cli("a.b="); }).find("needs a value"), std::string::npos);
}

TEST_F(Composition, DesignKeysThroughTheReference) {
  const auto path = write("study.yaml",
                          "base: base/run.yaml\n"
                          "set: {catenary.design.spans.count: 12}\n");
  const auto cat = pcsim::scene::load_catenary_scene(pcsim::scene::load_composed(path));
  EXPECT_EQ(cat.mesh.support_x.size(), 13u);
  const auto more = pcsim::scene::load_catenary_scene(
      pcsim::scene::load_composed(path, {cli("catenary.design.spans.count=14")}));
  EXPECT_EQ(more.mesh.support_x.size(), 15u);
}

TEST_F(Composition, BadBaseChains) {
  write("a.yaml", "base: b.yaml\nname: a\n");
  write("b.yaml", "base: a.yaml\n");
  EXPECT_NE(message([&] {
              pcsim::scene::load_composed((dir_ / "a.yaml").string());
            }).find("key 'base': circular base chain"),
            std::string::npos);
  write("c.yaml", "base: missing.yaml\n");
  EXPECT_NE(message([&] {
              pcsim::scene::load_composed((dir_ / "c.yaml").string());
            }).find("cannot open base file"),
            std::string::npos);
  write("d.yaml", "base: base/run.yaml\nset: [1, 2]\n");
  EXPECT_NE(message([&] {
              pcsim::scene::load_composed((dir_ / "d.yaml").string());
            }).find("key 'set': must be a map"),
            std::string::npos);
}
