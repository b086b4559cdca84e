// Catenary designs (meshes/*.yaml) -> CatenaryMesh, and mesh -> HDF5 + XDMF.
#include <gtest/gtest.h>
#include <hdf5.h>
#include <unistd.h>

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <sstream>

#include "pcsim/catenary/design.hpp"
#include "pcsim/catenary/mesh_io.hpp"
#include "pcsim/output/h5_file.hpp"

using namespace pcsim::catenary;
using pcsim::InputError;
using pcsim::InputNode;

namespace {

const std::string kMeshes = std::string(PCSIM_SOURCE_DIR) + "/meshes/";

std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no InputError thrown)";
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// The EN 50318 reference design with one line replaced (for variants).
std::string reference_text() {
  std::ifstream in(kMeshes + "en50318-reference.yaml");
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}
std::string replace_once(std::string text, const std::string& from, const std::string& to) {
  auto pos = text.find(from);
  EXPECT_NE(pos, std::string::npos) << "variant pattern not found: " << from;
  if (pos != std::string::npos) text.replace(pos, from.size(), to);
  return text;
}
CatenaryMesh build_text(const std::string& text, const std::string& name = "variant.yaml") {
  return build_catenary_design(InputNode::load_string(text, name));
}

const std::vector<double> kDropperPositions = {5.0, 10.5, 17.0, 23.5, 30.0, 36.5, 43.0, 49.5, 55.0};

bool is_wire_node(const CatenaryMesh& m, int wire, int node) {
  for (int n : m.wires[wire].nodes)
    if (n == node) return true;
  return false;
}

}  // namespace

// ------------------------------------------------------------ reference ----

TEST(ParametricDesign, ReferenceCounts) {
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

TEST(ParametricDesign, ReferenceWireProperties) {
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

TEST(ParametricDesign, StaggerAndSupports) {
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

TEST(ParametricDesign, DroppersAtListedPositionsOnBothWires) {
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

TEST(ParametricDesign, MessengerParabolaCarriesTheHungWeight) {
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

TEST(ParametricDesign, MessengerStaggerAndNoSteadyArmBlock) {
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

TEST(ParametricDesign, PresagSetsDesignHeights) {
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

TEST(ParametricDesign, StitchWireCarriesDroppersNearSupports) {
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

// ---------------------------------------------------------------- errors ----

struct BadFileCase {
  const char* file;
  const char* key;
  const char* reason;
};

TEST(DesignErrors, BadFilesNameFileKeyAndReason) {
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

TEST(DesignErrors, ParametricValidation) {
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
      {"model: constraint", "model: spring", "'steady_arms.model'", "must be one of constraint"},
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

TEST(DesignErrors, ExplicitValidation) {
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

TEST(ExplicitDesign, SingleWire) {
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

TEST(ExplicitDesign, TautStringHasNoGravity) {
  const CatenaryMesh m = load_catenary_design(kMeshes + "taut-string.yaml");
  EXPECT_EQ(mesh_consistency_error(m), "");
  EXPECT_EQ(m.gravity.norm(), 0.0);
  EXPECT_EQ(m.nodes.size(), 41u);
  EXPECT_EQ(m.cables.size(), 40u);
  EXPECT_DOUBLE_EQ(m.wires[0].EI, 195.0);
  EXPECT_TRUE(m.bars.empty());
  EXPECT_TRUE(m.tension_segments.empty());
}

TEST(ExplicitDesign, TwoWiresWithDroppers) {
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

TEST(ExplicitDesign, UnstressedRatioAndSlopeFixes) {
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

// ----------------------------------------------------------- HDF5 + XDMF ----

namespace {

// Minimal well-formedness parser for the XDMF we write: elements with
// quoted attributes, text, comments, <?...?> and <!...> declarations.
struct XmlElement {
  std::string name;
  std::map<std::string, std::string> attributes;
  std::string text;
  std::vector<XmlElement> children;
};

class XmlParser {
 public:
  explicit XmlParser(std::string text) : s_(std::move(text)) {}
  bool parse(XmlElement& root, std::string& error) {
    try {
      skip_misc();
      if (!peek("<")) throw std::runtime_error("no root element");
      root = element();
      skip_misc();
      if (pos_ != s_.size()) throw std::runtime_error("content after the root element");
      return true;
    } catch (const std::exception& e) {
      error = std::string(e.what()) + " at offset " + std::to_string(pos_);
      return false;
    }
  }

 private:
  bool peek(const char* t) const { return s_.compare(pos_, std::strlen(t), t) == 0; }
  void expect(const char* t) {
    if (!peek(t)) throw std::runtime_error(std::string("expected '") + t + "'");
    pos_ += std::strlen(t);
  }
  void skip_space() {
    while (pos_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[pos_]))) ++pos_;
  }
  void skip_until(const char* end) {
    auto p = s_.find(end, pos_);
    if (p == std::string::npos) throw std::runtime_error(std::string("unterminated, no ") + end);
    pos_ = p + std::strlen(end);
  }
  void skip_misc() {
    for (;;) {
      skip_space();
      if (peek("<?"))
        skip_until("?>");
      else if (peek("<!--"))
        skip_until("-->");
      else if (peek("<!"))
        skip_until(">");
      else
        return;
    }
  }
  std::string name() {
    std::size_t start = pos_;
    while (pos_ < s_.size() &&
           (std::isalnum(static_cast<unsigned char>(s_[pos_])) || s_[pos_] == '_' ||
            s_[pos_] == '-' || s_[pos_] == ':' || s_[pos_] == '.'))
      ++pos_;
    if (pos_ == start) throw std::runtime_error("expected a name");
    return s_.substr(start, pos_ - start);
  }
  std::string unescape(const std::string& t) {
    std::string out;
    for (std::size_t i = 0; i < t.size(); ++i) {
      if (t[i] == '<') throw std::runtime_error("'<' in text or attribute");
      if (t[i] != '&') {
        out += t[i];
        continue;
      }
      auto semi = t.find(';', i);
      if (semi == std::string::npos) throw std::runtime_error("bad entity");
      const std::string ent = t.substr(i + 1, semi - i - 1);
      static const std::map<std::string, char> known = {
          {"amp", '&'}, {"lt", '<'}, {"gt", '>'}, {"quot", '"'}, {"apos", '\''}};
      if (!known.count(ent)) throw std::runtime_error("unknown entity &" + ent + ";");
      out += known.at(ent);
      i = semi;
    }
    return out;
  }
  XmlElement element() {
    XmlElement e;
    expect("<");
    e.name = name();
    for (;;) {
      skip_space();
      if (peek("/>")) {
        pos_ += 2;
        return e;
      }
      if (peek(">")) {
        ++pos_;
        break;
      }
      const std::string key = name();
      skip_space();
      expect("=");
      skip_space();
      const char quote = s_[pos_];
      if (quote != '"' && quote != '\'') throw std::runtime_error("unquoted attribute " + key);
      auto end = s_.find(quote, pos_ + 1);
      if (end == std::string::npos) throw std::runtime_error("unterminated attribute");
      if (!e.attributes.emplace(key, unescape(s_.substr(pos_ + 1, end - pos_ - 1))).second)
        throw std::runtime_error("duplicate attribute " + key);
      pos_ = end + 1;
    }
    for (;;) {
      auto lt = s_.find('<', pos_);
      if (lt == std::string::npos) throw std::runtime_error("unclosed element " + e.name);
      e.text += unescape(s_.substr(pos_, lt - pos_));
      pos_ = lt;
      if (peek("</")) {
        pos_ += 2;
        if (name() != e.name) throw std::runtime_error("mismatched closing tag for " + e.name);
        skip_space();
        expect(">");
        return e;
      }
      if (peek("<!--")) {
        skip_until("-->");
        continue;
      }
      e.children.push_back(element());
    }
  }
  std::string s_;
  std::size_t pos_ = 0;
};

void collect(const XmlElement& e, const std::string& name, std::vector<const XmlElement*>& out) {
  if (e.name == name) out.push_back(&e);
  for (const auto& c : e.children) collect(c, name, out);
}

std::string trim(const std::string& s) {
  auto a = s.find_first_not_of(" \t\n\r");
  auto b = s.find_last_not_of(" \t\n\r");
  return a == std::string::npos ? "" : s.substr(a, b - a + 1);
}

std::vector<hsize_t> dataset_dims(const std::string& h5_path, const std::string& dataset) {
  std::vector<hsize_t> dims;
  hid_t file = H5Fopen(h5_path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (file < 0) return dims;
  if (H5Lexists(file, dataset.c_str(), H5P_DEFAULT) > 0) {
    hid_t set = H5Dopen2(file, dataset.c_str(), H5P_DEFAULT);
    hid_t space = H5Dget_space(set);
    dims.resize(H5Sget_simple_extent_ndims(space));
    H5Sget_simple_extent_dims(space, dims.data(), nullptr);
    H5Sclose(space);
    H5Dclose(set);
  }
  H5Fclose(file);
  return dims;
}

std::vector<double> read_doubles(const std::string& h5_path, const std::string& dataset) {
  hid_t file = H5Fopen(h5_path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  hid_t set = H5Dopen2(file, dataset.c_str(), H5P_DEFAULT);
  hid_t space = H5Dget_space(set);
  std::vector<double> out(H5Sget_simple_extent_npoints(space));
  H5Dread(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data());
  H5Sclose(space);
  H5Dclose(set);
  H5Fclose(file);
  return out;
}

std::filesystem::path make_temp_dir() {
  std::string templ = (std::filesystem::temp_directory_path() / "pcsim-design-XXXXXX").string();
  char* made = mkdtemp(templ.data());
  if (!made) throw std::runtime_error("mkdtemp failed");
  return std::filesystem::path(made);
}

// Parses folder/xdmf_name and checks that every DataItem names one of
// 'h5_names' (bare file names) and a dataset there with the stated dimensions.
void check_xdmf_references(const std::string& folder, const std::string& xdmf_name,
                           const std::set<std::string>& h5_names, XmlElement& root) {
  std::ifstream in(folder + "/" + xdmf_name);
  std::stringstream text;
  text << in.rdbuf();
  std::string error;
  ASSERT_TRUE(XmlParser(text.str()).parse(root, error)) << error;
  std::vector<const XmlElement*> items;
  collect(root, "DataItem", items);
  ASSERT_FALSE(items.empty());
  for (const XmlElement* item : items) {
    EXPECT_EQ(item->attributes.at("Format"), "HDF");  // the XDMF3 name (not "HDF5")
    const std::string ref = trim(item->text);
    const auto colon = ref.find(':');
    ASSERT_NE(colon, std::string::npos) << ref;
    const std::string file = ref.substr(0, colon);
    EXPECT_EQ(h5_names.count(file), 1u) << "must be a bare file name: " << ref;
    const std::string dataset = ref.substr(colon + 1);
    const auto dims = dataset_dims(folder + "/" + file, dataset);
    ASSERT_FALSE(dims.empty()) << "dataset " << dataset << " missing from " << file;
    std::istringstream want(item->attributes.at("Dimensions"));
    std::vector<hsize_t> wanted;
    for (hsize_t d; want >> d;) wanted.push_back(d);
    EXPECT_EQ(dims, wanted) << dataset;
  }
}

// Writes 'mesh', moves the folder, and checks every HDF5 reference of the XDMF.
void check_written_mesh(const CatenaryMesh& mesh, std::size_t expected_grids) {
  const auto dir = make_temp_dir();
  std::vector<double> positions = design_positions(mesh);
  for (std::size_t i = 0; i < positions.size(); i += 3) positions[i + 2] -= 0.01;  // a "solution"
  NodeField speed{"speed", 1, std::vector<double>(mesh.nodes.size(), 2.0)};
  write_mesh_h5_xdmf(mesh, positions, (dir / "mesh.h5").string(), (dir / "mesh.xdmf").string(),
                     {speed});
  // The folder can be moved: nothing refers to its old name.
  const auto moved = dir.string() + "-moved";
  std::filesystem::rename(dir, moved);
  const std::string h5 = moved + "/mesh.h5";
  XmlElement root;
  check_xdmf_references(moved, "mesh.xdmf", {"mesh.h5"}, root);
  if (::testing::Test::HasFatalFailure()) return;
  EXPECT_EQ(root.name, "Xdmf");
  std::vector<const XmlElement*> grids;
  collect(root, "Grid", grids);
  EXPECT_EQ(grids.size(), expected_grids);
  for (const XmlElement* grid : grids) {
    const XmlElement* topology = nullptr;
    for (const auto& c : grid->children)
      if (c.name == "Topology") topology = &c;
    ASSERT_NE(topology, nullptr);
    const std::string name = grid->attributes.at("Name");
    const std::string cells = topology->attributes.at("NumberOfElements");
    if (name == "wires") {
      EXPECT_EQ(topology->attributes.at("TopologyType"), "Polyline");
      EXPECT_EQ(topology->attributes.at("NodesPerElement"), "2");
      EXPECT_EQ(cells, std::to_string(mesh.cables.size()));
    } else if (name == "bars") {
      EXPECT_EQ(topology->attributes.at("TopologyType"), "Polyline");
      EXPECT_EQ(cells, std::to_string(mesh.bars.size()));
    } else {
      EXPECT_EQ(name, "point_masses");
      EXPECT_EQ(cells, std::to_string(mesh.point_masses.size()));
    }
  }
  // Values round-trip.
  EXPECT_EQ(read_doubles(h5, "/nodes/position"), positions);
  const auto disp = read_doubles(h5, "/nodes/displacement");
  ASSERT_EQ(disp.size(), positions.size());
  for (std::size_t i = 0; i < disp.size(); ++i)
    EXPECT_NEAR(disp[i], i % 3 == 2 ? -0.01 : 0.0, 1e-12);
  EXPECT_EQ(read_doubles(h5, "/fields/speed"), speed.values);
  std::filesystem::remove_all(moved);
}

}  // namespace

TEST(MeshOutput, ReferenceXdmfIsWellFormedAndMatchesH5) {
  const CatenaryMesh m = load_catenary_design(kMeshes + "en50318-reference.yaml");
  check_written_mesh(m, 3);  // wires, bars, point masses
}

TEST(MeshOutput, GridsWithoutCellsAreLeftOut) {
  const CatenaryMesh m = load_catenary_design(kMeshes + "taut-string.yaml");
  check_written_mesh(m, 1);  // wires only
}

TEST(MeshOutput, RejectsWrongPositionCount) {
  const CatenaryMesh m = load_catenary_design(kMeshes + "taut-string.yaml");
  const auto dir = make_temp_dir();
  EXPECT_THROW(write_mesh_h5_xdmf(m, std::vector<double>(5, 0.0), (dir / "m.h5").string(),
                                  (dir / "m.xdmf").string()),
               std::invalid_argument);
  std::filesystem::remove_all(dir);
}

TEST(MeshOutput, AllCommittedDesignsAreConsistent) {
  for (const char* f : {"en50318-reference.yaml", "single-wire.yaml", "taut-string.yaml",
                        "two-wires-droppers.yaml"}) {
    const CatenaryMesh m = load_catenary_design(kMeshes + f);
    EXPECT_EQ(mesh_consistency_error(m), "") << f;
    EXPECT_EQ(m.source_file, kMeshes + f);
  }
}

TEST(MeshOutput, ModesXdmfReferencesMeshAndModeFiles) {
  const CatenaryMesh m = load_catenary_design(kMeshes + "two-wires-droppers.yaml");
  const auto dir = make_temp_dir();
  const auto positions = design_positions(m);
  write_mesh_h5_xdmf(m, positions, (dir / "mesh.h5").string(), (dir / "mesh.xdmf").string());
  const std::vector<double> frequencies = {1.5, 2.5, 3.5};
  {
    pcsim::H5File h5((dir / "modes.h5").string());
    h5.write("/frequencies_hz", frequencies);
    for (int mode = 0; mode < 2; ++mode)  // no shape for the third mode
      h5.write("/shapes/mode_" + std::to_string(mode), std::vector<double>(positions.size(), 0.1),
               m.nodes.size(), 3);
  }
  write_modes_xdmf(m, "modes.h5", "mesh.h5", frequencies, (dir / "modes.xdmf").string());
  XmlElement root;
  check_xdmf_references(dir.string(), "modes.xdmf", {"mesh.h5", "modes.h5"}, root);
  if (HasFatalFailure()) return;
  std::vector<const XmlElement*> grids, times, infos;
  collect(root, "Grid", grids);
  collect(root, "Time", times);
  collect(root, "Information", infos);
  // Temporal collection + 2 modes x (spatial collection + wires + bars).
  EXPECT_EQ(grids.size(), 1u + 2u * 3u);
  ASSERT_EQ(times.size(), 2u);
  EXPECT_EQ(times[1]->attributes.at("Value"), "1");
  ASSERT_EQ(infos.size(), 2u);
  EXPECT_EQ(infos[1]->attributes.at("Value"), "2.5");
  EXPECT_THROW(
      write_modes_xdmf(m, "sub/modes.h5", "mesh.h5", frequencies, (dir / "modes.xdmf").string()),
      std::invalid_argument);
  std::filesystem::remove_all(dir);
}
