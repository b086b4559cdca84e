// Strict YAML input: messages name file, key and reason.
#include <gtest/gtest.h>

#include <chrono>
#include <functional>
#include <string>
#include <vector>

#include "pcsim/scene/composition.hpp"
#include "pcsim/scene/run_scene.hpp"
#include "pcsim/scene/yaml_input.hpp"

using pcsim::InputError;
using pcsim::scene::InputNode;

namespace {
std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(YamlInput, MissingFileNamesFile) {
  auto msg = message_of([] { InputNode::load_file("/nonexistent/design.yaml"); });
  EXPECT_NE(msg.find("/nonexistent/design.yaml"), std::string::npos);
  EXPECT_NE(msg.find("cannot open"), std::string::npos);
}

TEST(YamlInput, UnknownKeyNamesKeyPath) {
  auto root =
      InputNode::load_string("wires:\n  contact:\n    tension: 20000\n    tensoin: 1\n", "d.yaml");
  auto msg = message_of([&] { root["wires"]["contact"].allow_only({"tension"}); });
  EXPECT_NE(msg.find("d.yaml"), std::string::npos);
  EXPECT_NE(msg.find("wires.contact.tensoin"), std::string::npos);
  EXPECT_NE(msg.find("unknown key"), std::string::npos);
}

TEST(YamlInput, NegativeValueRejected) {
  auto root = InputNode::load_string("tension: -5\n", "d.yaml");
  auto msg = message_of([&] { root.get_positive("tension"); });
  EXPECT_NE(msg.find("'tension'"), std::string::npos);
  EXPECT_NE(msg.find("positive"), std::string::npos);
}

TEST(YamlInput, WrongTypeRejected) {
  auto root = InputNode::load_string("spans: ten\n", "d.yaml");
  auto msg = message_of([&] { root.get_int("spans"); });
  EXPECT_NE(msg.find("integer"), std::string::npos);
  EXPECT_DOUBLE_EQ(InputNode::load_string("a: 2.5\n", "x").get_double("a"), 2.5);
}

TEST(YamlInput, ChoiceAndDefaults) {
  auto root = InputNode::load_string("slack: force\n", "d.yaml");
  EXPECT_EQ(root.get_choice("slack", {"none", "length", "force"}, "none"), "force");
  EXPECT_EQ(root.get_choice("other", {"a"}, "a"), "a");
  EXPECT_FALSE(message_of([&] { root.get_choice("slack", {"none"}, "none"); }).empty());
}

// Issue 22: a key given twice, a second document and an empty value are
// errors naming the key (scenes, designs and models are read alike).
TEST(YamlInput, DuplicateKeyNamesKeyAndLines) {
  const auto msg =
      message_of([] { InputNode::load_string("a:\n  dt: 1\n  b: 2\n  dt: 3\n", "s.yaml"); });
  EXPECT_NE(msg.find("s.yaml: key 'a.dt'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("duplicate key (first at line 2, again at line 4)"), std::string::npos) << msg;
  const auto in_list =
      message_of([] { pcsim::scene::load_composed_text("l: [{x: 1, x: 2}]\n", "s.yaml"); });
  EXPECT_NE(in_list.find("key 'l[0].x'"), std::string::npos) << in_list;
}

TEST(YamlInput, SecondDocumentRejected) {
  const auto msg = message_of([] { InputNode::load_string("a: 1\n---\nb: 2\n", "s.yaml"); });
  EXPECT_NE(msg.find("s.yaml"), std::string::npos) << msg;
  EXPECT_NE(msg.find("more than one YAML document"), std::string::npos) << msg;
  EXPECT_EQ(message_of([] { InputNode::load_string("---\na: 1\n", "s.yaml"); }), "");
}

TEST(YamlInput, EmptyValueRejected) {
  for (const char* text : {"sim:\n  dt:\n", "sim: {dt: ~}\n", "sim: {dt: null}\n"}) {
    const auto msg = message_of([&] { pcsim::scene::load_composed_text(text, "s.yaml"); });
    EXPECT_NE(msg.find("key 'sim.dt': has no value"), std::string::npos) << text << msg;
  }
  const auto set = message_of([] {
    pcsim::scene::load_composed_text("a: 1\n", "s.yaml",
                              {pcsim::scene::parse_override("sim.dt=~", {"", "command line"})});
  });
  EXPECT_NE(set.find("key 'sim.dt'"), std::string::npos) << set;
}

TEST(YamlInput, UpperBoundsNameKey) {
  const auto root = InputNode::load_string("t: 1.0e300\nf: 5.0e-324\nx: -2.0e9\n", "d.yaml");
  const auto big = message_of([&] { root.get_positive("t", pcsim::limits::tension); });
  EXPECT_NE(big.find("key 't': must be at most 1e+07 N"), std::string::npos) << big;
  const auto tiny = message_of([&] { root.get_positive("f", pcsim::limits::frequency); });
  EXPECT_NE(tiny.find("key 'f': must be at least 0.001 Hz"), std::string::npos) << tiny;
  const auto neg = message_of([&] { root.get_real("x", pcsim::limits::force); });
  EXPECT_NE(neg.find("key 'x': must be at most 1e+06 N in magnitude"), std::string::npos) << neg;
  EXPECT_EQ(root.get_positive("missing", pcsim::limits::tension, 7.0), 7.0);
}

// Thousands of keys compose in linear time (a 'set' map of 20000 entries and
// a map of 20000 keys took minutes with a linear search per key).
TEST(YamlInput, ThousandsOfKeysComposeFast) {
  std::string text = "m:\n";
  for (int i = 0; i < 20000; ++i)
    text += "  k" + std::to_string(i) + ": " + std::to_string(i) + "\n";
  text += "set:\n";
  for (int i = 0; i < 20000; ++i)
    text += "  n.k" + std::to_string(i) + ": " + std::to_string(i) + "\n";
  const auto start = std::chrono::steady_clock::now();
  const InputNode root = pcsim::scene::load_composed_text(text, "big.yaml");
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(root["m"].size(), 20000u);
  EXPECT_EQ(root["n"].size(), 20000u);
  EXPECT_EQ(root["n"].get_int("k19999"), 19999);
  EXPECT_LT(seconds, 10.0);  // a sanity limit; quadratic work took minutes
}

// A pantograph name is one HDF5 link name (/pantographs/<name>).
TEST(YamlInput, PantographNames) {
  using pcsim::scene::pantograph_name_problem;
  for (const char* good : {"leading", "p 1", "trailing-2", "abs"})
    EXPECT_EQ(pantograph_name_problem(good), "");
  const std::vector<std::string> bad = {
      "", ".", "..", "a/", "/abs", "a/b", std::string("a\0b", 3), "t\tab"};
  for (const auto& name : bad) EXPECT_NE(pantograph_name_problem(name), "") << name;
}
