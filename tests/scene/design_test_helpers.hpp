// Helpers of the design-file reader tests (tests/scene/test_design_*.cpp).
#pragma once

#include <gtest/gtest.h>

#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "pcsim/scene/design_reader.hpp"

namespace pcsim::design_test {

using catenary::CatenaryMesh;

const std::string kMeshes = std::string(PCSIM_SOURCE_DIR) + "/meshes/";

// Message of the InputError thrown by f.
inline std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no InputError thrown)";
}

inline bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// The EN 50318 reference design with one line replaced (for variants).
inline std::string reference_text() {
  std::ifstream in(kMeshes + "en50318-reference.yaml");
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}
inline std::string replace_once(std::string text, const std::string& from, const std::string& to) {
  auto pos = text.find(from);
  EXPECT_NE(pos, std::string::npos) << "variant pattern not found: " << from;
  if (pos != std::string::npos) text.replace(pos, from.size(), to);
  return text;
}
inline CatenaryMesh build_text(const std::string& text, const std::string& name = "variant.yaml") {
  return scene::build_catenary_design(scene::InputNode::load_string(text, name));
}

const std::vector<double> kDropperPositions = {5.0, 10.5, 17.0, 23.5, 30.0, 36.5, 43.0, 49.5, 55.0};

inline bool is_wire_node(const CatenaryMesh& m, int wire, int node) {
  for (int n : m.wires[wire].nodes)
    if (n == node) return true;
  return false;
}

}  // namespace pcsim::design_test
