// Explicit design files (meshes/*.yaml, type: explicit) -> CatenaryMesh, the
// messages of bad files, and the consistency of every committed design.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>

#include "design_test_helpers.hpp"

using namespace pcsim::catenary;
using namespace pcsim::scene;
using namespace pcsim::design_test;

// ---------------------------------------------------------------- errors ----

struct BadFileCase {
  const char* file;
  const char* key;
  const char* reason;
};

TEST(DesignFileErrors, BadFilesNameFileKeyAndReason) {
  const BadFileCase cases[] = {
      {"bad/negative-tension.yaml", "'wires.contact.tension'", "must be positive (got -20000)"},
      {"bad/dropper-outside-span.yaml", "'droppers.positions[3]'",
       "dropper at 61 m lies outside the span (0, 60) m"},
      {"bad/unknown-key.yaml", "'droppers.stiffnes'", "unknown key"},
      {"bad/node-out-of-range.yaml", "'bars[0].nodes[1]'", "node index 7 is out of range"},
      {"bad/bar-same-node.yaml", "'bars[0].nodes'", "impossible geometry"},
  };
  for (const auto& c : cases) {
    const std::string path = kMeshes + c.file;
    const std::string msg = message_of([&] { load_catenary_design(path); });
    EXPECT_TRUE(contains(msg, path)) << msg;
    EXPECT_TRUE(contains(msg, c.key)) << msg;
    EXPECT_TRUE(contains(msg, c.reason)) << msg;
  }
}

TEST(DesignFileErrors, ExplicitValidation) {
  const std::string head =
      "type: explicit\n"
      "nodes: [[0, 0, 1], [10, 0, 1], [0, 0, 0], [10, 0, 0]]\n"
      "wires:\n"
      "  - {name: upper, nodes: {from: 0, to: 1, elements: 5}, mass_per_length: 1.0, EA: 1.0e7, "
      "EI: 100.0, tension: 1000.0}\n";
  struct Case {
    std::string tail, key, reason;
  };
  const std::vector<Case> cases = {
      {"bars:\n  - {nodes: [0, 9], stiffness: 1.0e5}\n", "'bars[0].nodes[1]'",
       "node index 9 is out of range (the design has 8 nodes"},
      {"bars:\n  - {nodes: [{wire: upper, node: 6}, 2], stiffness: 1.0e5}\n",
       "'bars[0].nodes[0].node'", "wire 'upper' has nodes 0..5 (got 6)"},
      {"bars:\n  - {nodes: [{wire: lower, node: 1}, 2], stiffness: 1.0e5}\n",
       "'bars[0].nodes[0].wire'", "no wire named 'lower'"},
      {"bars:\n  - {nodes: [0, 2], stiffness: -1}\n", "'bars[0].stiffness'", "must be positive"},
      {"bars:\n  - {nodes: [0, 2], stiffness: 1, form_find: maybe}\n", "'bars[0].form_find'",
       "must be true or false"},
      {"bars:\n  - {nodes: [0, 2], stiffness: 1}\ntargets:\n  - {node: 2, bar: 0}\n",
       "'targets[0].bar'", "not a form-finding bar"},
      {"bars:\n  - {nodes: [0, 2], stiffness: 1, form_find: true}\ntargets:\n  - {node: 2, bar: "
       "3}\n",
       "'targets[0].bar'", "out of range"},
      {"supports:\n  - {node: 0, fix: [x, w]}\n", "'supports[0].fix[1]'",
       "unknown degree of freedom"},
      {"springs:\n  - {node: 0, dof: dz, stiffness: 10}\n", "'springs[0].dof'", "position DOF"},
      {"point_masses:\n  - {node: 0, mass: 0}\n", "'point_masses[0].mass'", "must be positive"},
      {"tension_segments:\n  - {wire: lower}\n", "'tension_segments[0].wire'", "no wire named"},
      {"  - {name: lower, nodes: [2, 2], mass_per_length: 1, EA: 1, EI: 0}\n", "'wires[1].nodes'",
       "already belongs to this wire"},
      {"  - {name: lower, nodes: [2, 1], mass_per_length: 1, EA: 1, EI: 0}\n", "'wires[1].nodes'",
       "already belongs to wire 'upper'"},
      {"  - {name: lower, nodes: {from: 3, to: 3, elements: 2}, mass_per_length: 1, EA: 1, EI: "
       "0}\n",
       "'wires[1].nodes'", "same node"},
      {"  - {name: upper, nodes: [2, 3], mass_per_length: 1, EA: 1, EI: 0}\n", "'wires[1].name'",
       "defined twice"},
      {"  - {name: lower, nodes: [2, 3], mass_per_length: 1, EA: 1, EI: 0, unstressed: slack}\n",
       "'wires[1].unstressed'", "must be 'taut' or a positive ratio"},
      {"  - {name: lower, nodes: [2, 3], mass_per_length: 1, EA: 0, EI: 0}\n", "'wires[1].EA'",
       "must be positive"},
      {"gravity: 9.81\nlength: 3\n", "'length'", "unknown key"},
  };
  for (const auto& c : cases) {
    const std::string msg = message_of([&] { build_text(head + c.tail, "e.yaml"); });
    EXPECT_TRUE(contains(msg, "e.yaml")) << c.tail << " -> " << msg;
    EXPECT_TRUE(contains(msg, c.key)) << c.tail << " -> " << msg;
    EXPECT_TRUE(contains(msg, c.reason)) << c.tail << " -> " << msg;
  }
  // Nodes at the same position joined by a bar.
  const std::string msg = message_of([&] {
    build_text(
        "type: explicit\nnodes: [[0, 0, 0], [0, 0, 0]]\nbars:\n  - {nodes: [0, 1], stiffness: 1}\n",
        "e.yaml");
  });
  EXPECT_TRUE(contains(msg, "'bars[0].nodes'") && contains(msg, "same position")) << msg;
}

// -------------------------------------------------------------- explicit ----

TEST(ExplicitDesignFile, ReaderKeepsNodeReferences) {
  const auto root = pcsim::scene::InputNode::load_file(kMeshes + "two-wires-droppers.yaml");
  const ExplicitDesign d = read_explicit_design(root);
  EXPECT_EQ(d.name, "two-wires-droppers");
  EXPECT_TRUE(d.form_finding);
  ASSERT_EQ(d.nodes.size(), 4u);
  EXPECT_EQ(d.nodes[1], Eigen::Vector3d(30.0, 0.0, 6.5));
  ASSERT_EQ(d.wires.size(), 2u);
  EXPECT_EQ(d.wires[1].kind, WireKind::contact);
  ASSERT_TRUE(d.wires[1].run.has_value());
  EXPECT_EQ(d.wires[1].run->from.index, 2);
  EXPECT_EQ(d.wires[1].run->to.index, 3);
  EXPECT_EQ(d.wires[1].run->elements, 30);
  EXPECT_FALSE(d.wires[1].unstressed_ratio.has_value());  // taut
  ASSERT_EQ(d.bars.size(), 5u);
  EXPECT_EQ(d.bars[2].nodes[0].wire, std::optional<std::string>("messenger"));
  EXPECT_EQ(d.bars[2].nodes[0].node, 15);
  EXPECT_EQ(d.bars[2].kind, BarKind::dropper);
  EXPECT_FALSE(d.bars[2].unstressed_length.has_value());
  ASSERT_EQ(d.supports.size(), 4u);
  EXPECT_EQ(d.supports[0].dofs, (std::vector<int>{0, 1, 2}));  // no 'fix': x, y, z
}

TEST(ExplicitDesignFile, SingleWire) {
  const CatenaryMesh m = load_catenary_design(kMeshes + "single-wire.yaml");
  EXPECT_EQ(mesh_consistency_error(m), "");
  ASSERT_EQ(m.wires.size(), 1u);
  ASSERT_EQ(m.nodes.size(), 121u);
  ASSERT_EQ(m.cables.size(), 120u);
  EXPECT_FALSE(m.form_finding_default);
  EXPECT_EQ(m.contact_wire, -1);
  const Wire& w = m.wires[0];
  EXPECT_EQ(w.nodes.front(), 0);
  EXPECT_EQ(w.nodes.back(), 1);
  // Interior nodes 2..120 in order, evenly spaced.
  for (std::size_t k = 1; k + 1 < w.nodes.size(); ++k) {
    EXPECT_EQ(w.nodes[k], static_cast<int>(k) + 1);
    EXPECT_NEAR(m.nodes[w.nodes[k]].position.x(), 0.5 * k, 1e-12);
  }
  for (const auto& n : m.nodes) {
    EXPECT_NEAR((n.slope - Eigen::Vector3d(1, 0, 0)).norm(), 0.0, 1e-15);
  }
  // 'taut': the element law of elements.hpp (T = EA eps lambda, Green strain,
  // lambda = Lref/L0) gives the design tension in the straight wire.
  for (const auto& e : m.cables) {
    EXPECT_NEAR(e.ref_length, 0.5, 1e-12);
    const double lambda = e.ref_length / e.unstressed_length;
    EXPECT_NEAR(1.44e7 * 0.5 * (lambda * lambda - 1.0) * lambda, 20000.0, 1e-6);
    EXPECT_EQ(e.tension_segment, 0);
  }
  ASSERT_EQ(m.tension_segments.size(), 1u);
  EXPECT_DOUBLE_EQ(m.tension_segments[0].tension, 20000.0);
  for (int support : {0, 1}) {
    for (int d = 0; d < 3; ++d) EXPECT_TRUE(m.nodes[support].fixed[d]);
    for (int d = 3; d < 6; ++d) EXPECT_FALSE(m.nodes[support].fixed[d]);
  }
  EXPECT_FALSE(m.nodes[60].fixed[2]);
}

TEST(ExplicitDesignFile, TautStringHasNoGravity) {
  const CatenaryMesh m = load_catenary_design(kMeshes + "taut-string.yaml");
  EXPECT_EQ(mesh_consistency_error(m), "");
  EXPECT_EQ(m.gravity.norm(), 0.0);
  EXPECT_EQ(m.nodes.size(), 41u);
  EXPECT_EQ(m.cables.size(), 40u);
  EXPECT_DOUBLE_EQ(m.wires[0].EI, 195.0);
  EXPECT_TRUE(m.bars.empty());
  EXPECT_TRUE(m.tension_segments.empty());
}

TEST(ExplicitDesignFile, TwoWiresWithDroppers) {
  const CatenaryMesh m = load_catenary_design(kMeshes + "two-wires-droppers.yaml");
  EXPECT_EQ(mesh_consistency_error(m), "");
  ASSERT_EQ(m.wires.size(), 2u);
  EXPECT_EQ(m.contact_wire, 1);
  EXPECT_EQ(m.nodes.size(), 4u + 2u * 29u);
  EXPECT_EQ(m.cables.size(), 60u);
  ASSERT_EQ(m.bars.size(), 5u);
  for (std::size_t b = 0; b < 5; ++b) {
    const auto& bar = m.bars[b];
    EXPECT_EQ(bar.kind, BarKind::dropper);
    EXPECT_TRUE(bar.form_find_length);
    EXPECT_EQ(bar.index_in_span, static_cast<int>(b));
    EXPECT_EQ(bar.nodes[0], m.wires[0].nodes[5 * (b + 1)]);
    EXPECT_EQ(bar.nodes[1], m.wires[1].nodes[5 * (b + 1)]);
    EXPECT_NEAR(m.nodes[bar.nodes[0]].position.x(), 5.0 * (b + 1), 1e-12);
    EXPECT_NEAR(m.nodes[bar.nodes[1]].position.x(), 5.0 * (b + 1), 1e-12);
    EXPECT_NEAR(bar.unstressed_length, 1.2, 1e-12);  // default: design length
  }
  ASSERT_EQ(m.height_targets.size(), 5u);
  for (const auto& t : m.height_targets) EXPECT_DOUBLE_EQ(t.z, 5.3);
  ASSERT_EQ(m.tension_segments.size(), 2u);
  EXPECT_DOUBLE_EQ(m.tension_segments[0].tension, 16000.0);
  EXPECT_DOUBLE_EQ(m.tension_segments[1].tension, 20000.0);
  EXPECT_EQ(m.point_masses.size(), 10u);
  EXPECT_EQ(m.support_nodes, (std::vector<int>{2, 3}));
  EXPECT_EQ(m.support_x, (std::vector<double>{0.0, 30.0}));
  EXPECT_TRUE(m.form_finding_default);
}

TEST(ExplicitDesignFile, UnstressedRatioAndSlopeFixes) {
  const CatenaryMesh m = build_text(
      "type: explicit\nnodes: [[0, 0, 0], [3, 4, 0], [3, 4, 5]]\n"
      "wires:\n  - {name: a, nodes: [0, 1, 2], mass_per_length: 1, EA: 1e6, EI: 1, "
      "unstressed: 0.99}\n"
      "supports:\n  - {node: 0, fix: [x, dz]}\n",
      "e.yaml");
  EXPECT_NEAR(m.cables[0].ref_length, 5.0, 1e-12);
  EXPECT_NEAR(m.cables[0].unstressed_length, 4.95, 1e-12);
  EXPECT_TRUE(m.nodes[0].fixed[0]);
  EXPECT_FALSE(m.nodes[0].fixed[1]);
  EXPECT_TRUE(m.nodes[0].fixed[5]);
  // Corner node: mean of the two element directions.
  const Eigen::Vector3d expected =
      (Eigen::Vector3d(0.6, 0.8, 0) + Eigen::Vector3d(0, 0, 1)).normalized();
  EXPECT_NEAR((m.nodes[1].slope - expected).norm(), 0.0, 1e-14);
}

TEST(DesignFiles, AllCommittedDesignsAreConsistent) {
  for (const char* f : {"en50318-reference.yaml", "single-wire.yaml", "taut-string.yaml",
                        "two-wires-droppers.yaml"}) {
    const CatenaryMesh m = load_catenary_design(kMeshes + f);
    EXPECT_EQ(mesh_consistency_error(m), "") << f;
    EXPECT_EQ(m.source_file, kMeshes + f);
  }
}
