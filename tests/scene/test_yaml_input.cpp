// Strict YAML input: messages name file, key and reason.
#include <gtest/gtest.h>

#include "pcsim/scene/yaml_input.hpp"

using pcsim::InputError;
using pcsim::InputNode;

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
