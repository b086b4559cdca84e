// Parametric design files (meshes/*.yaml, type: parametric) -> CatenaryMesh:
// the EN 50318 reference design and variants of it, and the messages of bad files.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>

#include "design_test_helpers.hpp"

using namespace pcsim::catenary;
using namespace pcsim::scene;
using namespace pcsim::design_test;

// ------------------------------------------------------------ reference ----

TEST(ParametricDesignFile, ReferenceCounts) {
  const CatenaryMesh m = load_catenary_design(kMeshes + "en50318-reference.yaml");
  EXPECT_EQ(m.name, "en50318-reference");
  // Elements per span: every interval between key points cut into
  // ceil(gap / 0.5) elements.
  std::vector<double> keys = {0.0};
  keys.insert(keys.end(), kDropperPositions.begin(), kDropperPositions.end());
  keys.push_back(60.0);
  int per_span = 0;
  for (std::size_t k = 0; k + 1 < keys.size(); ++k)
    per_span += static_cast<int>(std::ceil((keys[k + 1] - keys[k]) / 0.5 - 1e-9));
  const int elements_per_wire = 10 * per_span;
  ASSERT_EQ(m.wires.size(), 2u);
  EXPECT_EQ(static_cast<int>(m.wires[0].elements.size()), elements_per_wire);
  EXPECT_EQ(static_cast<int>(m.wires[1].elements.size()), elements_per_wire);
  EXPECT_EQ(static_cast<int>(m.cables.size()), 2 * elements_per_wire);
  EXPECT_EQ(static_cast<int>(m.nodes.size()), 2 * (elements_per_wire + 1));
  EXPECT_EQ(m.bars.size(), 90u);
  EXPECT_EQ(m.height_targets.size(), 90u);
  // 1 contact-wire segment and 1 messenger segment per span.
  ASSERT_EQ(m.tension_segments.size(), 20u);
  // Clamps: 2 per dropper; steady arms: 1 per support.
  EXPECT_EQ(m.point_masses.size(), 90u * 2 + 11u);
  EXPECT_EQ(m.contact_wire, 0);
  EXPECT_EQ(m.wires[0].kind, WireKind::contact);
  EXPECT_EQ(m.wires[1].kind, WireKind::messenger);
  EXPECT_TRUE(m.form_finding_default);
  EXPECT_DOUBLE_EQ(m.rayleigh_alpha, 0.0125);
  EXPECT_DOUBLE_EQ(m.rayleigh_beta, 1.0e-4);
  EXPECT_DOUBLE_EQ(m.gravity.z(), -9.81);
  ASSERT_EQ(m.support_x.size(), 11u);
  ASSERT_EQ(m.support_nodes.size(), 11u);
  for (int k = 0; k <= 10; ++k) {
    EXPECT_DOUBLE_EQ(m.support_x[k], 60.0 * k);
    EXPECT_TRUE(is_wire_node(m, 0, m.support_nodes[k]));
    EXPECT_NEAR(m.nodes[m.support_nodes[k]].position.x(), 60.0 * k, 1e-12);
  }
  EXPECT_EQ(mesh_consistency_error(m), "");
}

TEST(ParametricDesignFile, ReferenceWireProperties) {
  const CatenaryMesh m = load_catenary_design(kMeshes + "en50318-reference.yaml");
  const Wire& c = m.wires[0];
  const Wire& ms = m.wires[1];
  EXPECT_DOUBLE_EQ(c.mass_per_length, 1.35);
  EXPECT_DOUBLE_EQ(c.EA, 1.44e7);
  EXPECT_DOUBLE_EQ(c.EI, 195.0);
  EXPECT_DOUBLE_EQ(c.tension, 20000.0);
  EXPECT_DOUBLE_EQ(ms.mass_per_length, 1.07);
  EXPECT_DOUBLE_EQ(ms.EA, 1.0e7);
  EXPECT_DOUBLE_EQ(ms.EI, 131.7);
  EXPECT_DOUBLE_EQ(ms.tension, 16000.0);
  // Elements: design length, first-guess unstressed length, segments.
  std::map<int, int> segment_of_span;
  for (std::size_t e = 0; e < m.cables.size(); ++e) {
    const CableElement& el = m.cables[e];
    const Wire& w = m.wires[el.wire];
    const double chord = (m.nodes[el.nodes[1]].position - m.nodes[el.nodes[0]].position).norm();
    EXPECT_NEAR(el.ref_length, chord, 1e-12);
    // element_length is measured along the track.
    EXPECT_LE(m.nodes[el.nodes[1]].position.x() - m.nodes[el.nodes[0]].position.x(), 0.5 + 1e-12);
    EXPECT_NEAR(el.unstressed_length, el.ref_length / (1.0 + w.tension / w.EA), 1e-14);
    ASSERT_GE(el.tension_segment, 0);
    const TensionSegment& seg = m.tension_segments[el.tension_segment];
    EXPECT_EQ(seg.wire, el.wire);
    EXPECT_DOUBLE_EQ(seg.tension, w.tension);
    if (el.wire == 1) {  // messenger: one segment per span
      const double mid_x =
          0.5 * (m.nodes[el.nodes[0]].position.x() + m.nodes[el.nodes[1]].position.x());
      const int span = static_cast<int>(std::floor(mid_x / 60.0));
      auto known = segment_of_span.emplace(span, el.tension_segment);
      EXPECT_EQ(known.first->second, el.tension_segment) << "span " << span;
    }
  }
  EXPECT_EQ(segment_of_span.size(), 10u);
  std::set<int> distinct;
  for (const auto& kv : segment_of_span) distinct.insert(kv.second);
  EXPECT_EQ(distinct.size(), 10u);
  int contact_segments = 0;
  for (const auto& seg : m.tension_segments) {
    if (seg.wire == 0) {
      ++contact_segments;
      EXPECT_EQ(seg.elements.size(), m.wires[0].elements.size() / 10);
    } else {
      EXPECT_EQ(seg.elements.size(), m.wires[1].elements.size() / 10);
    }
  }
  EXPECT_EQ(contact_segments, 10);
}

TEST(ParametricDesignFile, StaggerAndSupports) {
  const CatenaryMesh m = load_catenary_design(kMeshes + "en50318-reference.yaml");
  for (int k = 0; k <= 10; ++k) {
    const Node& c = m.nodes[m.support_nodes[k]];
    EXPECT_NEAR(c.position.y(), k % 2 == 0 ? 0.2 : -0.2, 1e-12) << "support " << k;
    EXPECT_NEAR(c.position.z(), 5.3, 1e-12);
    const bool end = k == 0 || k == 10;
    EXPECT_TRUE(c.fixed[1]);     // lateral: steady arm or anchor
    EXPECT_EQ(c.fixed[0], end);  // x anchored at the ends only
    EXPECT_EQ(c.fixed[2], end);  // vertical free at intermediate supports
    for (int d = 3; d < 6; ++d) EXPECT_FALSE(c.fixed[d]);
    // Messenger above, pinned, straight above the track centre.
    int messenger_node = -1;
    for (int n : m.wires[1].nodes)
      if (std::abs(m.nodes[n].position.x() - 60.0 * k) < 1e-9) messenger_node = n;
    ASSERT_GE(messenger_node, 0);
    const Node& ms = m.nodes[messenger_node];
    EXPECT_NEAR(ms.position.z(), 5.3 + 1.2, 1e-12);
    EXPECT_NEAR(ms.position.y(), 0.0, 1e-15);
    EXPECT_TRUE(ms.fixed[0] && ms.fixed[1] && ms.fixed[2]);
  }
  // Stagger linear in between: y(x) = +-0.2 (1 - 2 s / L), zero at mid-span.
  for (int n : m.wires[0].nodes) {
    const Node& c = m.nodes[n];
    const int span = std::min(9, static_cast<int>(std::floor(c.position.x() / 60.0)));
    const double s = c.position.x() - 60.0 * span;
    const double sign = span % 2 == 0 ? 1.0 : -1.0;
    EXPECT_NEAR(c.position.y(), sign * 0.2 * (1.0 - 2.0 * s / 60.0), 1e-12);
    EXPECT_NEAR(c.position.z(), 5.3, 1e-12);  // no presag
    const bool support = std::abs(s) < 1e-9 || std::abs(s - 60.0) < 1e-9;
    if (!support) {
      for (int d = 0; d < 6; ++d) EXPECT_FALSE(c.fixed[d]);
    }
  }
  // Steady-arm masses on the contact wire at every support.
  std::set<int> arms;
  for (const auto& pm : m.point_masses)
    if (pm.label == "steady_arm") {
      EXPECT_DOUBLE_EQ(pm.mass, 1.0);
      arms.insert(pm.node);
    }
  EXPECT_EQ(arms, std::set<int>(m.support_nodes.begin(), m.support_nodes.end()));
}

TEST(ParametricDesignFile, DroppersAtListedPositionsOnBothWires) {
  const CatenaryMesh m = load_catenary_design(kMeshes + "en50318-reference.yaml");
  std::map<std::pair<int, int>, int> seen;
  std::map<int, int> clamp_messenger, clamp_contact;
  for (const auto& pm : m.point_masses) {
    if (pm.label == "dropper_clamp_messenger") {
      EXPECT_DOUBLE_EQ(pm.mass, 0.195);
      ++clamp_messenger[pm.node];
    }
    if (pm.label == "dropper_clamp_contact") {
      EXPECT_DOUBLE_EQ(pm.mass, 0.165);
      ++clamp_contact[pm.node];
    }
  }
  for (std::size_t b = 0; b < m.bars.size(); ++b) {
    const BarElement& bar = m.bars[b];
    EXPECT_EQ(bar.kind, BarKind::dropper);
    ASSERT_GE(bar.span, 0);
    ASSERT_LT(bar.span, 10);
    ASSERT_GE(bar.index_in_span, 0);
    ASSERT_LT(bar.index_in_span, 9);
    EXPECT_TRUE(seen.insert({{bar.span, bar.index_in_span}, static_cast<int>(b)}).second);
    const Node& upper = m.nodes[bar.nodes[0]];
    const Node& lower = m.nodes[bar.nodes[1]];
    EXPECT_TRUE(is_wire_node(m, 1, bar.nodes[0]));
    EXPECT_TRUE(is_wire_node(m, 0, bar.nodes[1]));
    EXPECT_NEAR(upper.position.x(), lower.position.x(), 1e-12);
    EXPECT_NEAR(lower.position.x() - 60.0 * bar.span, kDropperPositions[bar.index_in_span], 1e-9);
    const double l = (upper.position - lower.position).norm();
    EXPECT_GT(l, 0.0);
    EXPECT_NEAR(bar.unstressed_length, l, 1e-12);
    EXPECT_NEAR(bar.mass, 0.117 * l, 1e-12);
    EXPECT_DOUBLE_EQ(bar.stiffness, 1.0e5);
    EXPECT_EQ(bar.slack, SlackCriterion::force);
    EXPECT_TRUE(bar.form_find_length);
    EXPECT_EQ(clamp_messenger[bar.nodes[0]], 1);
    EXPECT_EQ(clamp_contact[bar.nodes[1]], 1);
  }
  EXPECT_EQ(seen.size(), 90u);
  // One height target per dropper, at the contact node, at the design height.
  std::set<int> target_bars;
  for (const auto& t : m.height_targets) {
    ASSERT_GE(t.bar, 0);
    EXPECT_EQ(t.node, m.bars[t.bar].nodes[1]);
    EXPECT_NEAR(t.z, 5.3, 1e-12);
    target_bars.insert(t.bar);
  }
  EXPECT_EQ(target_bars.size(), 90u);
}

TEST(ParametricDesignFile, MessengerParabolaCarriesTheHungWeight) {
  const CatenaryMesh m = load_catenary_design(kMeshes + "en50318-reference.yaml");
  // Weight per metre: both wires + droppers + clamps of one span + the
  // steady arms (11 over 10 spans), all averaged over the 60 m span.
  double hung = 0;
  for (const auto& bar : m.bars)
    if (bar.span == 0) hung += bar.mass + 0.195 + 0.165;
  hung += 1.0 * 11.0 / 10.0;
  const double w = 9.81 * (1.07 + 1.35 + hung / 60.0);
  const double sag = w * 60.0 * 60.0 / (8.0 * 16000.0);
  EXPECT_GT(sag, 0.5);  // a sag of the usual order (~0.7 m)
  EXPECT_LT(sag, 1.0);
  for (int n : m.wires[1].nodes) {
    const Node& node = m.nodes[n];
    const int span = std::min(9, static_cast<int>(std::floor(node.position.x() / 60.0)));
    const double s = node.position.x() - 60.0 * span;
    EXPECT_NEAR(node.position.z(), 6.5 - 4.0 * sag * s * (60.0 - s) / 3600.0, 1e-9);
    // Slope: unit tangent of the parabola (mean of both sides at supports).
    EXPECT_NEAR(node.slope.norm(), 1.0, 1e-12);
    const bool support = std::abs(s) < 1e-9 || std::abs(s - 60.0) < 1e-9;
    if (!support) {
      const double dz = -4.0 * sag * (60.0 - 2.0 * s) / 3600.0;
      EXPECT_NEAR(node.slope.z() / node.slope.x(), dz, 1e-12);
      EXPECT_NEAR(node.slope.y(), 0.0, 1e-15);
    } else if (n != m.wires[1].nodes.front() && n != m.wires[1].nodes.back()) {
      EXPECT_NEAR(node.slope.z(), 0.0, 1e-12);  // symmetric kink at a support
    }
  }
  // Contact wire slope: stagger gradient, level.
  for (int n : m.wires[0].nodes) {
    const Node& node = m.nodes[n];
    const int span = std::min(9, static_cast<int>(std::floor(node.position.x() / 60.0)));
    const double s = node.position.x() - 60.0 * span;
    if (std::abs(s) < 1e-9 || std::abs(s - 60.0) < 1e-9) continue;
    const double sign = span % 2 == 0 ? 1.0 : -1.0;
    EXPECT_NEAR(node.slope.y() / node.slope.x(), -sign * 0.4 / 60.0, 1e-12);
    EXPECT_NEAR(node.slope.z(), 0.0, 1e-15);
  }
}

TEST(ParametricDesignFile, MessengerStaggerAndNoSteadyArmBlock) {
  std::string text =
      replace_once(reference_text(), "stagger: 0.2 ", "stagger: 0.2\nmessenger_stagger: 0.1 ");
  text = replace_once(text, "steady_arms: {mass: 1.0, model: constraint}", "");
  const CatenaryMesh m = build_text(text, "mstagger.yaml");
  for (std::size_t i = 0; i < m.wires[1].nodes.size(); ++i) {
    const Node& ms = m.nodes[m.wires[1].nodes[i]];
    const Node& c = m.nodes[m.wires[0].nodes[i]];
    EXPECT_NEAR(ms.position.x(), c.position.x(), 1e-12);
    EXPECT_NEAR(ms.position.y(), 0.5 * c.position.y(), 1e-12);  // same pattern, half amplitude
  }
  // Without a steady_arms block: no steady-arm masses, lateral constraint kept.
  for (const auto& pm : m.point_masses) EXPECT_NE(pm.label, "steady_arm");
  for (int k = 1; k < 10; ++k) EXPECT_TRUE(m.nodes[m.support_nodes[k]].fixed[1]);
}

TEST(ParametricDesignFile, PresagSetsDesignHeights) {
  const double presag = 0.06;
  const CatenaryMesh m =
      build_text(replace_once(reference_text(), "presag: 0.0 ", "presag: 0.06 "), "presag.yaml");
  ASSERT_EQ(m.height_targets.size(), 90u);
  for (const auto& t : m.height_targets) {
    const BarElement& bar = m.bars[t.bar];
    const double s = kDropperPositions[bar.index_in_span];
    const double expected = 5.3 - 4.0 * presag * s * (60.0 - s) / 3600.0;
    EXPECT_NEAR(t.z, expected, 1e-12);
    EXPECT_NEAR(m.nodes[t.node].position.z(), expected, 1e-12);
  }
  // Mid-span dropper (30 m) sits exactly presag below the support height.
  for (const auto& t : m.height_targets)
    if (m.bars[t.bar].index_in_span == 4) EXPECT_NEAR(t.z, 5.3 - presag, 1e-12);
}

TEST(ParametricDesignFile, StitchWireCarriesDroppersNearSupports) {
  // Droppers at 4.5 and 55.5 m lie inside an 18 m stitch wire (+-9 m).
  std::string text = replace_once(
      reference_text(), "positions: [5.0, 10.5, 17.0, 23.5, 30.0, 36.5, 43.0, 49.5, 55.0]",
      "positions: [4.5, 10.5, 17.0, 23.5, 30.0, 36.5, 43.0, 49.5, 55.5]");
  text = replace_once(text, "spans: {count: 10,", "spans: {count: 3,");
  text += "stitch_wire: {length: 18.0, tension: 3500.0, mass_per_length: 0.6, EA: 5.0e6}\n";
  const CatenaryMesh m = build_text(text, "stitch.yaml");
  EXPECT_EQ(mesh_consistency_error(m), "");
  int stitch_bars = 0;
  std::set<int> stitch_nodes;
  for (const auto& bar : m.bars) {
    if (bar.kind != BarKind::stitch) continue;
    ++stitch_bars;
    const double l = (m.nodes[bar.nodes[1]].position - m.nodes[bar.nodes[0]].position).norm();
    EXPECT_NEAR(bar.stiffness * (l - bar.unstressed_length), 3500.0, 1e-6);  // design tension
    EXPECT_NEAR(bar.mass, 0.6 * l, 1e-12);
    for (int n : bar.nodes)
      if (!is_wire_node(m, 1, n)) stitch_nodes.insert(n);
  }
  // 2 intermediate supports x (clamp, dropper, dropper, clamp) = 3 bars each.
  EXPECT_EQ(stitch_bars, 6);
  EXPECT_EQ(stitch_nodes.size(), 4u);
  int from_stitch = 0;
  for (const auto& bar : m.bars) {
    if (bar.kind != BarKind::dropper) continue;
    const double x = m.nodes[bar.nodes[1]].position.x();
    const bool inside = std::abs(x - 60.0) < 9.0 || std::abs(x - 120.0) < 9.0;
    EXPECT_EQ(stitch_nodes.count(bar.nodes[0]) == 1, inside) << "dropper at x = " << x;
    if (inside) {
      ++from_stitch;
      EXPECT_GT(m.nodes[bar.nodes[0]].position.z(), m.nodes[bar.nodes[1]].position.z());
    }
  }
  EXPECT_EQ(from_stitch, 4);
}
// ---------------------------------------------------------------- reader ----

TEST(ParametricDesignFile, ReaderFillsTheParameters) {
  const auto root = pcsim::scene::InputNode::load_file(kMeshes + "en50318-reference.yaml");
  const ParametricDesign d = read_parametric_design(root);
  EXPECT_EQ(d.file, kMeshes + "en50318-reference.yaml");
  EXPECT_EQ(d.name, "en50318-reference");
  EXPECT_EQ(d.span_count, 10);
  EXPECT_EQ(d.span_length, 60.0);
  EXPECT_EQ(d.system_height, 1.2);
  EXPECT_EQ(d.contact_wire_height, 5.3);
  EXPECT_EQ(d.stagger, 0.2);
  EXPECT_EQ(d.messenger_stagger, 0.0);  // default
  EXPECT_EQ(d.contact.EI, 195.0);
  EXPECT_EQ(d.messenger.tension, 16000.0);
  EXPECT_EQ(d.droppers.positions, kDropperPositions);
  EXPECT_EQ(d.droppers.slack, SlackCriterion::force);
  EXPECT_EQ(d.droppers.clamp_mass_contact, 0.165);
  EXPECT_EQ(d.steady_arms.mass, 1.0);
  EXPECT_FALSE(d.stitch_wire.has_value());
  EXPECT_EQ(d.damping.alpha, 0.0125);
  EXPECT_EQ(d.gravity, Eigen::Vector3d(0.0, 0.0, -9.81));
}

TEST(ParametricDesignFile, RangesAreCheckedByTheBuilder) {
  // The reader takes any number; the builder names the key of the bad one.
  const auto root = pcsim::scene::InputNode::load_string(
      replace_once(reference_text(), "tension: 20000.0}", "tension: -20000.0}"), "v.yaml");
  const ParametricDesign d = read_parametric_design(root);
  EXPECT_EQ(d.contact.tension, -20000.0);
  const std::string msg = message_of([&] { build_parametric(d); });
  EXPECT_EQ(msg, "v.yaml: key 'wires.contact.tension': must be positive (got -20000)");
}

// ---------------------------------------------------------------- errors ----

TEST(DesignFileErrors, ParametricValidation) {
  const std::string ref = reference_text();
  struct Case {
    std::string from, to, key, reason;
  };
  const std::vector<Case> cases = {
      {"mass_per_length: 1.35,", "mass_per_length: 0,", "'wires.contact.mass_per_length'",
       "must be positive"},
      {"mass_per_length: 1.07,", "mass_per_length: -1.07,", "'wires.messenger.mass_per_length'",
       "must be positive"},
      {"EA: 1.0e7,", "EA: -1.0e7,", "'wires.messenger.EA'", "must be positive"},
      {"tension: 16000.0}", "tension: 0}", "'wires.messenger.tension'", "must be positive"},
      {"tension: 16000.0}", "tension: lots}", "'wires.messenger.tension'", "must be a number"},
      {"count: 10,", "count: 0,", "'spans.count'", "at least 1"},
      {"count: 10,", "count: 2.5,", "'spans.count'", "must be an integer"},
      {"contact_wire_height: 5.3 ", "contact_wire_height: 0 ", "'contact_wire_height'",
       "must be positive"},
      {"presag: 0.0 ", "presag: 1.5 ", "'system_height'", "must exceed the contact-wire presag"},
      {"system_height: 1.2 ", "system_height: 0.3 ", "'system_height'", "reaches the contact wire"},
      {"positions: [5.0,", "positions: [0.0,", "'droppers.positions[0]'",
       "dropper at 0 m lies outside the span (0, 60) m"},
      {"10.5, 17.0,", "17.0, 10.5,", "'droppers.positions[2]'", "strictly increasing"},
      {"10.5, 17.0,", "10.5, 10.52,", "'droppers.positions[2]'", "minimum spacing"},
      {"slack: force", "slack: sometimes", "'droppers.slack'",
       "must be one of none, length, force"},
      {"model: constraint", "model: pendulum", "'steady_arms.model'",
       "must be one of constraint, hinged, spring"},
      {"EI: 195.0,", "EI: 195.0, tensoin: 3,", "'wires.contact.tensoin'", "unknown key"},
      {"stagger: 0.2 ", "stagger: -0.2 ", "'stagger'", "must not be negative"},
      {"element_length: 0.5 ", "element_length: 100 ", "'element_length'", "must not exceed"},
      {"type: parametric", "type: sketch", "'type'", "must be one of parametric, explicit"},
      {"gravity: 9.81", "gravity: [0, 0]", "'gravity'", "list of 3 numbers"},
  };
  for (const auto& c : cases) {
    const std::string msg =
        message_of([&] { build_text(replace_once(ref, c.from, c.to), "v.yaml"); });
    EXPECT_TRUE(contains(msg, "v.yaml")) << c.to << " -> " << msg;
    EXPECT_TRUE(contains(msg, c.key)) << c.to << " -> " << msg;
    EXPECT_TRUE(contains(msg, c.reason)) << c.to << " -> " << msg;
  }
  // Stitch wire longer than the span, and a clamp almost on a dropper.
  std::string msg = message_of([&] {
    build_text(ref + "stitch_wire: {length: 60, tension: 3500, mass_per_length: 0.6, EA: 5e6}\n",
               "v.yaml");
  });
  EXPECT_TRUE(contains(msg, "'stitch_wire.length'") && contains(msg, "overlap")) << msg;
  msg = message_of([&] {
    build_text(ref + "stitch_wire: {length: 10.02, tension: 3500, mass_per_length: 0.6, EA: 5e6}\n",
               "v.yaml");
  });
  EXPECT_TRUE(contains(msg, "'stitch_wire.length'") && contains(msg, "minimum spacing")) << msg;
  msg = message_of([&] { build_text("name: x\n", "v.yaml"); });
  EXPECT_TRUE(contains(msg, "'type'") && contains(msg, "missing")) << msg;
}

// droppers.diameter and drag_coefficient (the wind's drag, docs/conditions.md)
// reach every dropper bar; without them the bars keep 0 (the kind's default,
// catenary::bar_diameter: 4 mm, Cd 1.2).
TEST(ParametricDesignFile, DropperDragKeysReachTheBars) {
  const std::string text = replace_once(reference_text(), "droppers:\n",
                                        "droppers:\n  diameter: 0.005\n  drag_coefficient: 1.1\n");
  const CatenaryMesh given = build_text(text, "drag.yaml");
  const CatenaryMesh plain = build_text(reference_text(), "plain.yaml");
  int droppers = 0;
  for (std::size_t b = 0; b < given.bars.size(); ++b) {
    if (given.bars[b].kind != BarKind::dropper) continue;
    ++droppers;
    EXPECT_EQ(pcsim::catenary::bar_diameter(given.bars[b]), 0.005);
    EXPECT_EQ(pcsim::catenary::bar_drag_coefficient(given.bars[b]), 1.1);
    EXPECT_EQ(pcsim::catenary::bar_diameter(plain.bars[b]), 0.004);
    EXPECT_EQ(pcsim::catenary::bar_drag_coefficient(plain.bars[b]), 1.2);
  }
  EXPECT_EQ(droppers, 90);
  const std::string bad =
      replace_once(reference_text(), "droppers:\n", "droppers:\n  diameter: -1\n");
  EXPECT_NE(message_of([&] { build_text(bad, "bad.yaml"); }).find("droppers.diameter"),
            std::string::npos);
}
