// The parametric generator's lines (geometry_*.cpp), built from parameter
// structs: tension sections and overlaps (roles, heights, lateral offsets,
// tensioning devices, midpoint anchors, zones), presag profiles and dropper
// positions per span, support and steady-arm models, stitch-wire tension
// segments, irregularities and wear, curved track.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "design_fixtures.hpp"
#include "pcsim/catenary/geometry.hpp"

using namespace pcsim;
using namespace pcsim::catenary;

namespace {

constexpr double kH = 5.3;  // contact_wire_height of the reference design [m]

// Three sections of 3 spans (60 m) joined by two-span overlaps, 1 m elements.
ParametricDesign three_sections() {
  ParametricDesign d = design_fixtures::reference_design(9);
  d.element_length = 1.0;
  d.sections = {{3, 0.0}, {3, 0.0}, {3, 0.0}};
  d.overlap = {2, 0.3, 0.6, 0.2};
  return d;
}

// Node of wire w at station x (design position), -1 if none.
int node_at(const CatenaryMesh& m, int w, double x) {
  for (int n : m.wires[w].nodes)
    if (std::abs(m.nodes[n].position.x() - x) < 1e-9) return n;
  return -1;
}

}  // namespace

TEST(LineGeometry, OverlapRolesHeightsAndLateralOffsets) {
  ParametricDesign d = three_sections();
  const CatenaryMesh m = build_parametric(d);
  ASSERT_EQ(m.wires.size(), 6u);
  EXPECT_EQ(m.contact_wires, (std::vector<int>{0, 2, 4}));
  EXPECT_EQ(m.contact_wire, 0);
  EXPECT_EQ(m.wires[2].name, "contact_2");
  EXPECT_EQ(m.wires[3].name, "messenger_2");
  // Overlap 1-2 over supports 2..4 (q = 3 - 1): section 1 in service at 2
  // and 3, raised at 4, anchored at 5; section 2 anchored at 1, raised at
  // 2, in service from 3.
  const double L = 60.0;
  struct Expect {
    int wire;
    int support;
    double z;
  };
  const std::vector<Expect> expect = {{0, 2, kH},       {0, 3, kH},       {0, 4, kH + 0.3},
                                      {0, 5, kH + 0.6}, {2, 1, kH + 0.6}, {2, 2, kH + 0.3},
                                      {2, 3, kH},       {2, 4, kH}};
  for (const auto& e : expect) {
    const int n = node_at(m, e.wire, e.support * L);
    ASSERT_GE(n, 0) << "wire " << e.wire << " support " << e.support;
    EXPECT_NEAR(m.nodes[n].position.z(), e.z, 1e-12)
        << "wire " << e.wire << " support " << e.support;
    // The messenger at the system height above it.
    const int up = node_at(m, e.wire + 1, e.support * L);
    ASSERT_GE(up, 0);
    EXPECT_NEAR(m.nodes[up].position.z(), e.z + 1.2, 1e-12);
  }
  // Section 1's wires end at support 5, section 2's start at 1.
  EXPECT_NEAR(m.nodes[m.wires[0].nodes.back()].position.x(), 5 * L, 1e-12);
  EXPECT_NEAR(m.nodes[m.wires[2].nodes.front()].position.x(), 1 * L, 1e-12);
  // Where both are in service (support 3) the wires run 0.2 m apart, each
  // shifted by half of it from the stagger (-0.2 at odd supports).
  const int a = node_at(m, 0, 3 * L), b = node_at(m, 2, 3 * L);
  EXPECT_NEAR(m.nodes[a].position.y(), -0.2 + 0.1, 1e-12);
  EXPECT_NEAR(m.nodes[b].position.y(), -0.2 - 0.1, 1e-12);
  // The raised wire is held there (y, z), the in-service one on its steady
  // arm (y only); the anchors fully.
  const int raised = node_at(m, 0, 4 * L), service = node_at(m, 2, 4 * L);
  EXPECT_TRUE(m.nodes[raised].fixed[1] && m.nodes[raised].fixed[2] && !m.nodes[raised].fixed[0]);
  EXPECT_TRUE(m.nodes[service].fixed[1] && !m.nodes[service].fixed[2]);
  EXPECT_EQ(m.support_nodes[4], service);
  EXPECT_EQ(m.support_nodes[3], a);  // both in service: the section that owns the support
  // No droppers in the anchor spans (4-5 for section 1, 1-2 for section 2).
  for (const auto& bar : m.bars) {
    if (bar.kind != BarKind::dropper) continue;
    const double x = m.nodes[bar.nodes[1]].position.x();
    const bool on1 = std::count(m.wires[0].nodes.begin(), m.wires[0].nodes.end(), bar.nodes[1]);
    const bool on2 = std::count(m.wires[2].nodes.begin(), m.wires[2].nodes.end(), bar.nodes[1]);
    if (on1) EXPECT_LT(x, 4 * L) << "section 1 dropper in its anchor span";
    if (on2) EXPECT_GT(x, 2 * L) << "section 2 dropper in its anchor span";
  }
  // Zones: sections' own stretches (without the line's end spans) and the overlaps.
  ASSERT_EQ(m.zones.size(), 5u);
  EXPECT_EQ(m.zones[1].name, "overlap 1-2");
  EXPECT_NEAR(m.zones[0].from_x, L, 1e-12);
  EXPECT_NEAR(m.zones[0].to_x, 2 * L, 1e-12);
  EXPECT_NEAR(m.zones[1].from_x, 2 * L, 1e-12);
  EXPECT_NEAR(m.zones[1].to_x, 4 * L, 1e-12);
  EXPECT_NEAR(m.zones[4].to_x, 8 * L, 1e-12);
  // Multi-section lines: one tension segment per contact wire, one per span
  // of each messenger.
  int contact_segments = 0;
  for (const auto& s : m.tension_segments)
    if (s.wire >= 0 && m.wires[s.wire].kind == WireKind::contact) ++contact_segments;
  EXPECT_EQ(contact_segments, 3);
}

// Every support of every overlap: the wires there (contact and messenger) at
// the stagger shifted across by separation steps, in section order from the
// left: +-0.1 m for two wires; +0.2, 0, -0.2 for three, where a middle
// section of fewer than m + 3 spans has both its overlaps at one support.
TEST(LineGeometry, WiresSeparationApartAtEverySupportOfTheOverlaps) {
  struct Case {
    std::vector<long> spans;
    int most_wires;  // at one support
  };
  for (const auto& c : {Case{{3, 3, 3}, 3}, Case{{2, 4, 3}, 3}, Case{{3, 5, 3}, 2}}) {
    ParametricDesign d = three_sections();
    d.span_count = 0;
    d.sections.clear();
    for (long n : c.spans) d.sections.push_back({n, 0.0}), d.span_count += n;
    d.messenger_stagger = 0.05;
    const CatenaryMesh m = build_parametric(d);
    const double L = 60.0;
    int most = 0;
    for (int k = 0; k <= d.span_count; ++k)
      for (bool messenger : {false, true}) {
        std::vector<double> y;  // wires at support k, in section order
        for (int w : m.contact_wires) {
          const int n = node_at(m, w + (messenger ? 1 : 0), k * L);
          if (n >= 0) y.push_back(m.nodes[n].position.y());
        }
        const double stagger = (k % 2 == 0 ? 1.0 : -1.0) * (messenger ? 0.05 : 0.2);
        for (std::size_t i = 0; i < y.size(); ++i)
          EXPECT_NEAR(y[i], stagger + (0.5 * (y.size() - 1.0) - i) * 0.2, 1e-12)
              << "sections " << c.spans[1] << ", support " << k << ", wire " << i
              << (messenger ? " (messenger)" : "");
        most = std::max(most, static_cast<int>(y.size()));
      }
    EXPECT_EQ(most, c.most_wires) << "middle section of " << c.spans[1] << " spans";
  }
  // The short line's support 4: section 1's raised wire, section 2's in
  // service and section 3's anchor, 0.2 m apart (stagger +0.2).
  const CatenaryMesh m = build_parametric(three_sections());
  const double y1 = m.nodes[node_at(m, 0, 240.0)].position.y();
  const double y2 = m.nodes[node_at(m, 2, 240.0)].position.y();
  const double y3 = m.nodes[node_at(m, 4, 240.0)].position.y();
  EXPECT_NEAR(y1, 0.4, 1e-12);
  EXPECT_NEAR(y2, 0.2, 1e-12);
  EXPECT_NEAR(y3, 0.0, 1e-12);
}

TEST(LineGeometry, BalanceWeightsAndMidpointAnchors) {
  ParametricDesign d = three_sections();
  d.tensioning.device = TensioningDeviceKind::weight;
  d.tensioning.ratio = 3.0;
  const CatenaryMesh m = build_parametric(d);
  // Every end of every wire: 3 sections x 2 ends x 2 wires.
  ASSERT_EQ(m.tensioning_devices.size(), 12u);
  for (const auto& dev : m.tensioning_devices) {
    const double T = m.wires[dev.wire].tension;
    // The weight T / (g ratio) moving ratio times the wire end: mass ratio^2 x weight.
    EXPECT_NEAR(dev.mass, T * 3.0 / 9.81, 1e-9 * T);
    EXPECT_EQ(dev.kind, TensioningKind::weight);
    const bool at_start = dev.node == m.wires[dev.wire].nodes.front();
    EXPECT_NEAR(dev.direction.x(), at_start ? -1.0 : 1.0, 1e-15);
    EXPECT_TRUE(m.nodes[dev.node].fixed[0]);  // held during form-finding
  }
  // Midpoint anchor: each contact wire's x held at exactly one inner support.
  for (int w : m.contact_wires) {
    int held = 0;
    for (std::size_t i = 1; i + 1 < m.wires[w].nodes.size(); ++i)
      held += m.nodes[m.wires[w].nodes[i]].fixed[0];
    EXPECT_EQ(held, 1) << m.wires[w].name;
  }
  // A section of one span between two weights has no inner support for it.
  ParametricDesign bad = design_fixtures::reference_design(1);
  bad.tensioning.device = TensioningDeviceKind::weight;
  EXPECT_THROW(build_parametric(bad), InputError);
}

TEST(LineGeometry, PresagProfilesAndDroppersPerSpan) {
  ParametricDesign d = design_fixtures::reference_design(3);
  d.presag_profile = PresagProfile::droppers;
  d.presag = 0.04;
  d.droppers.spans = {{{2}, {4.0, 20.0, 30.0, 40.0, 56.0}, {}}};
  CatenaryMesh m = build_parametric(d);
  // Targets: the first and last droppers at support height, 40 mm lower
  // midway between them (spans 1, 3: (5 + 55) / 2 = 30 m; span 2: 30 m).
  int in_span2 = 0;
  for (const auto& t : m.height_targets) {
    const double x = m.nodes[t.node].position.x(), s = std::fmod(x, 60.0);
    const int span = static_cast<int>(x / 60.0);
    const double a = span == 1 ? 4.0 : 5.0, b = span == 1 ? 56.0 : 55.0;
    EXPECT_NEAR(t.z, kH - 4 * 0.04 * (s - a) * (b - s) / ((b - a) * (b - a)), 1e-12) << x;
    in_span2 += span == 1;
    if (std::abs(s - 30.0) < 1e-9) EXPECT_NEAR(t.z, kH - 0.04, 1e-12);
  }
  EXPECT_EQ(in_span2, 5);
  EXPECT_EQ(m.height_targets.size(), 9u + 5u + 9u);
  // Explicit sags per dropper.
  d.presag_profile = PresagProfile::heights;
  d.droppers.sags = {0.0, 0.01, 0.02, 0.03, 0.035, 0.03, 0.02, 0.01, 0.0};
  d.droppers.spans[0].sags = {0.0, 0.02, 0.03, 0.02, 0.0};
  m = build_parametric(d);
  for (const auto& t : m.height_targets) {
    const double x = m.nodes[t.node].position.x();
    const int span = static_cast<int>(x / 60.0);
    const auto& pos = span == 1 ? d.droppers.spans[0].positions : d.droppers.positions;
    const auto& sag = span == 1 ? d.droppers.spans[0].sags : d.droppers.sags;
    const auto it = std::find_if(pos.begin(), pos.end(),
                                 [&](double p) { return std::abs(p - std::fmod(x, 60.0)) < 1e-9; });
    ASSERT_NE(it, pos.end());
    EXPECT_NEAR(t.z, kH - sag[it - pos.begin()], 1e-12) << x;
  }
}

TEST(LineGeometry, SupportAndSteadyArmModels) {
  ParametricDesign d = design_fixtures::reference_design(4);
  d.messenger_supports = {MessengerSupportModel::spring_mass, 2.0e6, 8.0};
  d.steady_arms = {SteadyArmModel::hinged, 1.5, 1.2, 1.0e7, 0.0};
  SupportOverride o;
  o.supports = {2};
  o.steady_arm = SteadyArmDesign{SteadyArmModel::spring, 1.0, 1.0, 1.0e7, 3000.0};
  d.support_overrides = {o};
  const CatenaryMesh m = build_parametric(d);
  // Messenger at the inner supports 1..3: x, y held, z on a spring, 8 kg.
  int springs_z = 0, support_masses = 0;
  for (const auto& s : m.springs)
    if (s.dof == 2 && s.stiffness == 2.0e6) ++springs_z;
  for (const auto& pm : m.point_masses) support_masses += pm.label == "messenger_support";
  EXPECT_EQ(springs_z, 3);
  EXPECT_EQ(support_masses, 3);
  // Hinged arms at supports 1 and 3, a spring arm at 2.
  std::vector<int> arms;
  for (std::size_t b = 0; b < m.bars.size(); ++b)
    if (m.bars[b].kind == BarKind::steady_arm) arms.push_back(static_cast<int>(b));
  ASSERT_EQ(arms.size(), 2u);
  for (int b : arms) {
    const auto& bar = m.bars[b];
    const Node& pivot = m.nodes[bar.nodes[0]];
    const Node& wire = m.nodes[bar.nodes[1]];
    EXPECT_TRUE(pivot.fixed[0] && pivot.fixed[1] && pivot.fixed[2]);
    EXPECT_FALSE(wire.fixed[1]);  // the arm holds the wire laterally
    EXPECT_NEAR((pivot.position - wire.position).norm(), 1.2, 1e-12);
    EXPECT_NEAR(bar.unstressed_length, 1.2, 1e-12);
    // On the side away from the wire's pull: outward of the stagger (+-0.2).
    EXPECT_GT(pivot.position.y() * wire.position.y(), 0.0);
    EXPECT_NEAR(std::abs(pivot.position.y()), 0.2 + 1.2, 1e-12);
    // Inertia m/3 and weight m/2 at the wire.
    double mass = 0, weight = 0;
    for (const auto& pm : m.point_masses)
      if (pm.node == bar.nodes[1] && pm.label == "steady_arm") mass += pm.mass, weight += pm.mass;
    for (const auto& nf : m.node_forces)
      if (nf.node == bar.nodes[1]) weight += -nf.force.z() / 9.81;
    EXPECT_NEAR(mass, 0.5, 1e-12);
    EXPECT_NEAR(weight, 0.75, 1e-12);
  }
  int arm_springs = 0;
  for (const auto& s : m.springs) arm_springs += s.dof == 2 && s.stiffness == 3000.0;
  EXPECT_EQ(arm_springs, 1);
  EXPECT_EQ(m.registrations.size(), 3u);
}

TEST(LineGeometry, StitchWiresAreTensionSegmentsOfBars) {
  ParametricDesign d = design_fixtures::reference_design(4);
  d.stitch_wire = StitchWireDesign{18.0, 3500.0, 0.31, 4.2e6};
  const CatenaryMesh m = build_parametric(d);
  int stitch_segments = 0;
  for (const auto& s : m.tension_segments) {
    if (s.bars.empty()) continue;
    ++stitch_segments;
    EXPECT_EQ(s.wire, -1);
    EXPECT_EQ(s.tension, 3500.0);
    EXPECT_EQ(s.bars.size(), 3u);  // clamp, droppers at 5 m on both sides, clamp
    for (int b : s.bars) EXPECT_EQ(m.bars[b].kind, BarKind::stitch);
  }
  EXPECT_EQ(stitch_segments, 3);  // inner supports 1..3
}

TEST(LineGeometry, RandomIrregularityHasItsRmsAndZeroGapAtTheDroppers) {
  ParametricDesign d = design_fixtures::reference_design(5);
  const CatenaryMesh plain = build_parametric(d);
  RandomIrregularity r;
  r.rms = 0.002;
  r.wavelength_min = 2.0;
  r.wavelength_max = 50.0;
  r.seed = 7;
  d.irregularities.random = r;
  // Two touching stretches: each element in the one holding its midpoint
  // ([from, to)).
  d.irregularities.wear = {{100.0, 115.0, 0.25}, {115.0, 130.0, 0.5}};
  const CatenaryMesh m = build_parametric(d);
  // The profile on the contact wire's design heights. The line (300 m) is
  // one period of every component, so the RMS over a uniform sample is
  // exact; the contact nodes are uniform to the dropper stations (0.5 m
  // elements, a few shorter ones): 3 % covers that.
  double sum2 = 0;
  const auto& nodes = m.wires[0].nodes;
  for (std::size_t i = 0; i + 1 < nodes.size(); ++i) {
    const double dz = m.nodes[nodes[i]].position.z() - plain.nodes[nodes[i]].position.z();
    const double dx = m.nodes[nodes[i + 1]].position.x() - m.nodes[nodes[i]].position.x();
    sum2 += dz * dz * dx;
  }
  EXPECT_NEAR(std::sqrt(sum2 / 300.0), 0.002, 0.03 * 0.002);
  // The targets carry it; the contact-gap offset vanishes at the droppers.
  ASSERT_EQ(m.contact_gap_offsets.size(), 1u);
  const auto& g = m.contact_gap_offsets[0];
  for (const auto& t : m.height_targets) {
    const double x = m.nodes[t.node].position.x();
    EXPECT_NEAR(t.z, m.nodes[t.node].position.z(), 0.0);
    const auto it = std::lower_bound(g.x.begin(), g.x.end(), x - 1e-9);
    if (it != g.x.end() && std::abs(*it - x) < 1e-9)
      EXPECT_NEAR(g.offset[it - g.x.begin()], 0.0, 1e-15);
  }
  // Wear: the elements of 100..115 m keep 75 % of the section, those of
  // 115..130 m half of it.
  int worn = 0;
  for (int e : m.wires[0].elements) {
    const auto& el = m.cables[e];
    const double mid =
        0.5 * (m.nodes[el.nodes[0]].position.x() + m.nodes[el.nodes[1]].position.x());
    const double f = mid < 100.0 || mid >= 130.0 ? 1.0 : (mid < 115.0 ? 0.75 : 0.5);
    EXPECT_EQ(el.section_factor, f) << mid;
    worn += el.section_factor < 1;
  }
  EXPECT_EQ(worn, 60);
}

TEST(LineGeometry, CurvedSectionFollowsTheTrackWithChords) {
  ParametricDesign d = design_fixtures::reference_design(6);
  d.element_length = 1.0;
  d.sections = {{2, 0.0}, {4, 800.0}};
  d.overlap.spans = 1;
  const CatenaryMesh m = build_parametric(d);
  ASSERT_FALSE(m.track.straight());
  // Supports on the track, the wire at the stagger along the track normal.
  for (std::size_t k = 0; k < m.support_nodes.size(); ++k) {
    const int n = m.support_nodes[k];
    const double s = m.support_x[k];
    const Eigen::Vector2d p = m.track.point(s), nrm = m.track.normal(s);
    const Eigen::Vector2d y = m.nodes[n].position.head<2>() - p;
    EXPECT_NEAR(y.dot(m.track.tangent(s)), 0.0, 1e-9) << k;
    // Stagger +-0.2; in the one-span overlap (supports 1..4 around q = 2)
    // section 1 (owning 0..2) shifted by +0.1, section 2 by -0.1.
    const double shift = k >= 1 && k <= 2 ? 0.1 : (k >= 3 && k <= 4 ? -0.1 : 0.0);
    EXPECT_NEAR(y.dot(nrm), (k % 2 == 0 ? 0.2 : -0.2) + shift, 1e-9) << k;
    EXPECT_NEAR(m.track.station(m.nodes[n].position.head<2>()), s, 1e-9) << k;
  }
  // On the curve the steady arms hold the wire along the normal (stiff
  // spring), not by the y DOF.
  int normal_springs = 0;
  for (const auto& reg : m.registrations) {
    const double s = m.support_x[reg.support];
    if (s <= 120.0 + 1e-9) continue;
    bool found = false;
    for (const auto& sp : m.springs)
      found = found || (sp.node == reg.node && (sp.direction - reg.lateral).norm() < 1e-12);
    EXPECT_TRUE(found) << "support at " << s;
    EXPECT_FALSE(m.nodes[reg.node].fixed[1]);
    normal_springs += found;
  }
  EXPECT_GT(normal_springs, 0);
  // Between two supports a wire is straight in plan: the nodes of the span
  // 3 (180..240 m) on the chord of its support points.
  const int a = m.support_nodes[3], b = m.support_nodes[4];
  const Eigen::Vector2d pa = m.nodes[a].position.head<2>(), pb = m.nodes[b].position.head<2>();
  for (int n : m.wires[m.contact_wires.back()].nodes) {
    const Eigen::Vector2d p = m.nodes[n].position.head<2>();
    const double t = (p - pa).dot(pb - pa) / (pb - pa).squaredNorm();
    if (t <= 0 || t >= 1) continue;
    EXPECT_NEAR((pa + t * (pb - pa) - p).norm(), 0.0, 1e-9);
  }
}
