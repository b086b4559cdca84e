// Catenary geometry builders (geometry.hpp) on designs given by their
// parameters, without a design file: node and element counts, dropper
// positions, node references, and errors that name the key of the bad value.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <set>

#include "design_fixtures.hpp"
#include "pcsim/catenary/geometry.hpp"

using namespace pcsim::catenary;
using pcsim::InputError;
using pcsim::design_fixtures::reference_design;
using pcsim::design_fixtures::taut_string_design;

namespace {

// The InputError thrown by f (an empty one if none is thrown).
InputError error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e;
  }
  return InputError("", "", "(no InputError thrown)");
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

}  // namespace

// ------------------------------------------------------------ parametric ----

TEST(BuildParametric, TwoSpanLineCountsAndDropperPositions) {
  const ParametricDesign design = reference_design(2);
  const CatenaryMesh m = build_parametric(design);
  EXPECT_EQ(mesh_consistency_error(m), "");
  EXPECT_EQ(m.source_file, "reference-parameters");
  EXPECT_EQ(m.name, "en50318-reference");
  // Gaps between key points 0, 5, 10.5, ..., 55, 60 m cut into 0.5 m
  // elements: 10 + 11 + 6 x 13 + 11 + 10 = 120 elements per span.
  const int per_wire = 2 * 120;
  ASSERT_EQ(m.wires.size(), 2u);
  EXPECT_EQ(static_cast<int>(m.wires[0].elements.size()), per_wire);
  EXPECT_EQ(static_cast<int>(m.wires[1].elements.size()), per_wire);
  EXPECT_EQ(static_cast<int>(m.nodes.size()), 2 * (per_wire + 1));
  EXPECT_EQ(m.tension_segments.size(), 4u);  // one per span and wire
  EXPECT_EQ(m.support_x, (std::vector<double>{0.0, 60.0, 120.0}));
  // 9 droppers per span, 2 clamps each, 3 steady arms.
  ASSERT_EQ(m.bars.size(), 18u);
  EXPECT_EQ(m.height_targets.size(), 18u);
  EXPECT_EQ(m.point_masses.size(), 18u * 2 + 3u);
  const int S = per_wire + 1;  // messenger node S + i lies above contact node i
  for (const BarElement& bar : m.bars) {
    EXPECT_EQ(bar.kind, BarKind::dropper);
    const Eigen::Vector3d& lower = m.nodes[bar.nodes[1]].position;
    const double x = 60.0 * bar.span + design.droppers.positions.at(bar.index_in_span);
    // The station x is j L + s: exact in binary for these positions.
    EXPECT_EQ(lower.x(), x);
    EXPECT_EQ(bar.nodes[0], S + bar.nodes[1]);
    EXPECT_EQ(m.nodes[bar.nodes[0]].position.x(), x);
    EXPECT_GT(m.nodes[bar.nodes[0]].position.z(), lower.z());
  }
}

TEST(BuildParametric, ElementLengthThatDoesNotDivideTheGaps) {
  ParametricDesign design = reference_design(1);
  design.element_length = 0.7;
  const CatenaryMesh m = build_parametric(design);
  std::vector<double> keys = {0.0};
  keys.insert(keys.end(), design.droppers.positions.begin(), design.droppers.positions.end());
  keys.push_back(60.0);
  int elements = 0;
  for (std::size_t k = 0; k + 1 < keys.size(); ++k)
    elements += static_cast<int>(std::ceil((keys[k + 1] - keys[k]) / 0.7 - 1e-9));
  EXPECT_EQ(static_cast<int>(m.wires[0].elements.size()), elements);
  // Every key point is a node; no element is longer than 0.7 m along x.
  std::set<double> node_x;
  for (int n : m.wires[0].nodes) node_x.insert(m.nodes[n].position.x());
  for (double key : keys) EXPECT_EQ(node_x.count(key), 1u) << key;
  for (const CableElement& e : m.cables)
    EXPECT_LE(m.nodes[e.nodes[1]].position.x() - m.nodes[e.nodes[0]].position.x(), 0.7 + 1e-12);
}

TEST(BuildParametric, ErrorsNameFileKeyAndReason) {
  struct Case {
    std::function<void(ParametricDesign&)> change;
    std::string key, reason;
  };
  const std::vector<Case> cases = {
      {[](ParametricDesign& d) { d.droppers.positions[1] = 70.0; }, "droppers.positions[1]",
       "dropper at 70 m lies outside the span (0, 60) m"},
      {[](ParametricDesign& d) { d.droppers.positions[3] = d.droppers.positions[2] + 0.01; },
       "droppers.positions[3]", "minimum spacing 0.05 m"},
      {[](ParametricDesign& d) { d.span_count = 0; }, "spans.count", "must be at least 1 (got 0)"},
      {[](ParametricDesign& d) { d.contact.tension = -20000.0; }, "wires.contact.tension",
       "must be positive (got -20000)"},
      {[](ParametricDesign& d) { d.messenger.EI = -1.0; }, "wires.messenger.EI",
       "must not be negative (got -1)"},
      {[](ParametricDesign& d) { d.system_height = 0.3; }, "system_height",
       "reaches the contact wire"},
      {[](ParametricDesign& d) { d.damping.alpha = -1.0; }, "damping.rayleigh_alpha",
       "must not be negative"},
      {[](ParametricDesign& d) {
         d.stitch_wire = StitchWireDesign{10.02, 3500.0, 0.6, 5e6};
       },
       "stitch_wire.length", "minimum spacing"},
  };
  for (const auto& c : cases) {
    ParametricDesign design = reference_design(3);
    c.change(design);
    const InputError e = error_of([&] { build_parametric(design); });
    EXPECT_EQ(e.file(), "reference-parameters") << e.what();
    EXPECT_EQ(e.key(), c.key) << e.what();
    EXPECT_TRUE(contains(e.reason(), c.reason)) << e.what();
  }
}

// -------------------------------------------------------------- explicit ----

TEST(BuildExplicit, TautStringFromParameters) {
  const CatenaryMesh m = build_explicit(taut_string_design());
  EXPECT_EQ(mesh_consistency_error(m), "");
  ASSERT_EQ(m.nodes.size(), 41u);
  ASSERT_EQ(m.cables.size(), 40u);
  // The run creates nodes 2..40 from node 0 towards node 1.
  EXPECT_EQ(m.wires[0].nodes.front(), 0);
  EXPECT_EQ(m.wires[0].nodes[1], 2);
  EXPECT_EQ(m.wires[0].nodes.back(), 1);
  EXPECT_NEAR(m.nodes[2].position.x(), 0.5, 1e-15);
  EXPECT_TRUE(m.nodes[1].fixed[2]);
  EXPECT_FALSE(m.nodes[1].fixed[3]);
  EXPECT_EQ(m.gravity.norm(), 0.0);
}

TEST(BuildExplicit, NodeReferencesAlongWires) {
  ExplicitDesign d = taut_string_design();
  d.nodes.push_back({0.0, 0.0, -1.0});   // node 2, before the wire's interior nodes
  d.nodes.push_back({20.0, 0.0, -1.0});  // node 3
  ExplicitWire lower = d.wires[0];
  lower.name = "lower";
  lower.run = WireRun{NodeRef::at(2), NodeRef::at(3), 4};
  d.wires.push_back(lower);
  ExplicitBar bar;
  bar.nodes = {NodeRef::on_wire("string", 20), NodeRef::on_wire("lower", -3)};
  bar.stiffness = 1e5;
  bar.form_find = true;
  d.bars.push_back(bar);
  d.targets.push_back({NodeRef::on_wire("lower", 2), std::nullopt, 0});
  d.tension_segments.push_back({"lower", std::nullopt});
  const CatenaryMesh m = build_explicit(d);
  EXPECT_EQ(mesh_consistency_error(m), "");
  // string: 0, 4..42, 1; lower: 2, 43, 44, 45, 3.
  ASSERT_EQ(m.bars.size(), 1u);
  EXPECT_EQ(m.bars[0].nodes[0], 23);
  EXPECT_EQ(m.bars[0].nodes[1], 44);
  EXPECT_NEAR(m.nodes[23].position.x(), 10.0, 1e-12);
  EXPECT_NEAR(m.nodes[44].position.x(), 10.0, 1e-12);
  EXPECT_NEAR(m.bars[0].unstressed_length, 1.0, 1e-15);  // default: design length
  ASSERT_EQ(m.height_targets.size(), 1u);
  EXPECT_EQ(m.height_targets[0].z, -1.0);  // default: the node's design height
  ASSERT_EQ(m.tension_segments.size(), 1u);
  EXPECT_EQ(m.tension_segments[0].tension, 20000.0);  // default: the wire's tension
}

TEST(BuildExplicit, ErrorsNameFileKeyAndReason) {
  struct Case {
    std::function<void(ExplicitDesign&)> change;
    std::string key, reason;
  };
  auto bar_between = [](NodeRef a, NodeRef b) {
    ExplicitBar bar;
    bar.nodes = {a, b};
    bar.stiffness = 1.0;
    return bar;
  };
  const std::vector<Case> cases = {
      {[&](ExplicitDesign& d) { d.bars.push_back(bar_between(NodeRef::at(0), NodeRef::at(41))); },
       "bars[0].nodes[1]", "node index 41 is out of range (the design has 41 nodes, 0..40)"},
      {[&](ExplicitDesign& d) {
         d.bars.push_back(bar_between(NodeRef::on_wire("other", 1), NodeRef::at(0)));
       },
       "bars[0].nodes[0].wire", "no wire named 'other'"},
      {[&](ExplicitDesign& d) { d.bars.push_back(bar_between(NodeRef::at(3), NodeRef::at(3))); },
       "bars[0].nodes", "impossible geometry"},
      {[](ExplicitDesign& d) { d.wires[0].run->elements = 0; }, "wires[0].nodes.elements",
       "must be a positive number of elements (got 0)"},
      {[](ExplicitDesign& d) { d.wires[0].EA = 0.0; }, "wires[0].EA", "must be positive (got 0)"},
      {[](ExplicitDesign& d) {
         d.supports[1].dofs = {2, 7};
       },
       "supports[1].fix[1]", "DOF index 7 is out of range"},
      {[](ExplicitDesign& d) {
         d.springs.push_back({NodeRef::at(5), 4, 1.0});
       },
       "springs[0].dof", "position DOF"},
      {[](ExplicitDesign& d) {
         d.tension_segments.push_back({"string", 0.0});
       },
       "tension_segments[0].tension", "must be positive (got 0)"},
  };
  for (const auto& c : cases) {
    ExplicitDesign design = taut_string_design();
    c.change(design);
    const InputError e = error_of([&] { build_explicit(design); });
    EXPECT_EQ(e.file(), "taut-string-parameters") << e.what();
    EXPECT_EQ(e.key(), c.key) << e.what();
    EXPECT_TRUE(contains(e.reason(), c.reason)) << e.what();
  }
}

// ------------------------------------------------------------ consistency ----

TEST(MeshConsistency, FindsTheFirstProblem) {
  const CatenaryMesh good = build_parametric(reference_design(1));
  ASSERT_EQ(mesh_consistency_error(good), "");
  CatenaryMesh m = good;
  m.cables[3].nodes[1] = static_cast<int>(m.nodes.size());
  EXPECT_EQ(mesh_consistency_error(m), "cable element 3 has a node out of range");
  m = good;
  m.bars[2].form_find_length = false;
  EXPECT_EQ(mesh_consistency_error(m), "a height target does not point at a form-finding bar");
  m = good;
  m.tension_segments[1].elements.push_back(0);
  EXPECT_EQ(mesh_consistency_error(m), "tension segment 1 lists element 0 that is not its own");
  m = good;
  m.support_x.pop_back();
  EXPECT_EQ(mesh_consistency_error(m), "support_x and support_nodes differ");
}
