// One tension section of a parametric line: stations, nodes, the contact
// wire and the messenger, stitch wires and droppers (see
// docs/design-format.md, "What the generator builds"); its supports are in
// geometry_supports.cpp.
#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry_line.hpp"
#include "pcsim/core/format.hpp"

namespace pcsim::catenary::detail {

SectionBuilder::SectionBuilder(const ParametricDesign& in, const LineLayout& line, int section,
                               const IrregularProfile& profile, CatenaryMesh& mesh)
    : in_(in),
      line_(line),
      section_(section),
      L_(in.span_length),
      geo_(in, line, section, profile),
      mesh_(mesh) {}

void SectionBuilder::build() {
  const bool single = line_.sections.size() == 1;
  const std::string suffix = single ? "" : "_" + std::to_string(section_ + 1);
  make_stations();
  find_messenger_sag();
  base_ = static_cast<int>(mesh_.nodes.size());
  place_nodes();
  // One tension segment per span for both wires: the messenger is pinned at
  // every support; the contact wire runs through them with a uniform
  // tension, so imposing it span by span is the same condition, and keeps
  // each form-finding row local (a single segment couples every
  // contact-wire DOF: a dense row that made the sparse factorisation of
  // long lines slow).
  contact_wire_ = static_cast<int>(mesh_.wires.size());
  add_wire("contact" + suffix, WireKind::contact, in_.contact, base_);
  messenger_wire_ = static_cast<int>(mesh_.wires.size());
  add_wire("messenger" + suffix, WireKind::messenger, in_.messenger, base_ + S_);
  add_supports();
  if (in_.stitch_wire) add_stitch_wires();
  add_droppers();
}

int SectionBuilder::contact_node_at(int k) const {
  const auto& sec = geo_.layout();
  if (k < sec.first || k > sec.last) return -1;
  return base_ + support_station_[k - sec.first];
}

std::vector<double> SectionBuilder::held_stations() const {
  std::vector<double> x = {stations_.front().span * L_ + stations_.front().s,
                           stations_.back().span * L_ + stations_.back().s};
  for (const auto& st : stations_)
    if (is_dropper(st)) x.push_back(st.span * L_ + st.s);
  return x;
}

std::string SectionBuilder::describe(const KeyPoint& k) const {
  if (k.kind == KeyKind::dropper) return "the dropper at " + format_number(k.s) + " m";
  if (k.kind == KeyKind::stitch_clamp)
    return "the stitch-wire clamp at " + format_number(k.s) + " m";
  return "the support at " + format_number(k.s) + " m";
}

// Key points of span j, sorted; coincident points merged (a stitch clamp on
// a dropper point stays a dropper point). Throws if two key points are
// closer than kMinKeyPointGap.
std::vector<SectionBuilder::KeyPoint> SectionBuilder::span_key_points(int j) const {
  std::vector<KeyPoint> pts;
  pts.push_back({0.0, KeyKind::support, -1});
  if (geo_.dropper_span(j)) {
    const auto& pos = geo_.positions(j);
    for (std::size_t d = 0; d < pos.size(); ++d)
      pts.push_back({pos[d], KeyKind::dropper, static_cast<int>(d)});
  }
  if (geo_.stitch_at(j)) pts.push_back({0.5 * in_.stitch_wire->length, KeyKind::stitch_clamp, -1});
  if (geo_.stitch_at(j + 1))
    pts.push_back({L_ - 0.5 * in_.stitch_wire->length, KeyKind::stitch_clamp, -1});
  pts.push_back({L_, KeyKind::support, -1});
  std::stable_sort(pts.begin(), pts.end(),
                   [](const KeyPoint& a, const KeyPoint& b) { return a.s < b.s; });
  std::vector<KeyPoint> merged;
  for (const auto& p : pts) {
    if (!merged.empty() && std::abs(p.s - merged.back().s) <= kSamePoint) {
      if (merged.back().kind == KeyKind::stitch_clamp) merged.back() = p;
      continue;
    }
    if (!merged.empty() && p.s - merged.back().s < kMinKeyPointGap) {
      const KeyPoint& a = merged.back();
      const std::string reason = describe(p) + " lies only " + format_number(p.s - a.s) +
                                 " m from " + describe(a) + " (minimum spacing " +
                                 format_number(kMinKeyPointGap) + " m)";
      if (p.kind == KeyKind::stitch_clamp || a.kind == KeyKind::stitch_clamp)
        throw InputError(in_.file, "stitch_wire.length", reason);
      const int d = p.kind == KeyKind::dropper ? p.index : a.index;
      throw InputError(in_.file, geo_.positions_key(j) + "[" + std::to_string(d) + "]", reason);
    }
    merged.push_back(p);
  }
  return merged;
}

void SectionBuilder::make_stations() {
  const auto& sec = geo_.layout();
  for (int j = sec.first; j < sec.last; ++j) {
    auto keys = span_key_points(j);
    for (std::size_t k = 0; k + 1 < keys.size(); ++k) {
      const double a = keys[k].s, b = keys[k + 1].s;
      const int n = static_cast<int>(std::min<long>(
          detail::element_count(b - a, in_.element_length), std::numeric_limits<int>::max()));
      stations_.push_back({j, a, keys[k].kind, keys[k].index});
      for (int i = 1; i < n; ++i)
        stations_.push_back({j, a + (b - a) * i / n, KeyKind::support, -2});
    }
  }
  stations_.push_back({sec.last - 1, L_, KeyKind::support, -1});
  S_ = static_cast<int>(stations_.size());
}

// Dropper attachment: the messenger node, or a stitch-wire node when the
// dropper lies strictly inside a stitch wire's length (returns its support).
int SectionBuilder::stitch_support_of(int j, double s) const {
  if (!in_.stitch_wire) return -1;
  const double half = 0.5 * in_.stitch_wire->length;
  if (geo_.stitch_at(j) && s < half - kSamePoint) return j;
  if (geo_.stitch_at(j + 1) && s > L_ - half + kSamePoint) return j + 1;
  return -1;
}

// Upper end of a dropper for a messenger sag 'sag'.
Eigen::Vector3d SectionBuilder::upper_point(int j, double s, double sag) const {
  int k = stitch_support_of(j, s);
  if (k < 0) return geo_.messenger(j, s, sag);
  // Stitch wire: straight chord between its two messenger clamps.
  const double half = 0.5 * in_.stitch_wire->length;
  Eigen::Vector3d left = geo_.messenger(k - 1, L_ - half, sag),
                  right = geo_.messenger(k, half, sag);
  const Eigen::Vector3d here = geo_.messenger(j, s, sag);
  const double t = (here - left).head<2>().norm() / (right - left).head<2>().norm();
  Eigen::Vector3d p = left + t * (right - left);
  if (line_.track.straight()) {  // exactly at the dropper's x
    const double x = j * L_ + s;
    p = left + ((x - left.x()) / (right.x() - left.x())) * (right - left);
  }
  return p;
}

// Mass hung from the messenger per dropper span at messenger sag 'sag': the
// droppers and their clamps, the steady arms and the stitch wires.
double SectionBuilder::hung_mass(double sag) const {
  const DropperDesign& dr = in_.droppers;
  const auto& sec = geo_.layout();
  double hung = 0;
  int dropper_spans = 0;
  for (int j = sec.first; j < sec.last; ++j) {
    if (!geo_.dropper_span(j)) continue;
    ++dropper_spans;
    for (double s : geo_.positions(j))
      hung += dr.clamp_mass_messenger + dr.clamp_mass_contact +
              dr.mass_per_length * (upper_point(j, s, sag) - geo_.contact(j, s)).norm();
  }
  for (int k = sec.first; k <= sec.last; ++k) {
    if (geo_.role(k) == Role::anchor) continue;
    hung += steady_arm_weight_mass(k);
    if (geo_.stitch_at(k)) hung += in_.stitch_wire->mass_per_length * in_.stitch_wire->length;
  }
  return dropper_spans > 0 ? hung / dropper_spans : 0.0;
}

// Messenger sag from the weight per metre it carries (fixed point: the
// dropper lengths depend on the sag; converges in a few steps).
void SectionBuilder::find_messenger_sag() {
  const double g = -mesh_.gravity.z();
  for (int it = 0; it < 20; ++it) {
    const double hung = hung_mass(geo_.messenger_sag);
    const double w = g * (in_.messenger.mass_per_length + in_.contact.mass_per_length + hung / L_);
    const double sag = w * L_ * L_ / (8.0 * in_.messenger.tension);
    const bool done = std::abs(sag - geo_.messenger_sag) < 1e-13;
    geo_.messenger_sag = sag;
    if (done) break;
  }
}

// Nodes: contact wire base..base+S-1, messenger base+S..base+2S-1 (stitch-wire
// nodes later).
void SectionBuilder::place_nodes() {
  const auto& sec = geo_.layout();
  mesh_.nodes.resize(base_ + 2 * S_);
  for (int i = 0; i < S_; ++i) {
    const Station& st = stations_[i];
    Node& c = mesh_.nodes[base_ + i];
    Node& m = mesh_.nodes[base_ + S_ + i];
    c.position = geo_.contact(st.span, st.s);
    m.position = geo_.messenger(st.span, st.s);
    c.slope = geo_.contact_tangent(st.span, st.s);
    m.slope = geo_.messenger_tangent(st.span, st.s);
    if (is_support(st) && i > 0 && i + 1 < S_) {
      // Support between two spans: the tangent is discontinuous (stagger,
      // messenger sag); use the mean of both sides as the design slope.
      c.slope = unit(c.slope + geo_.contact_tangent(st.span - 1, L_));
      m.slope = unit(m.slope + geo_.messenger_tangent(st.span - 1, L_));
    }
  }
  for (int i = 0; i < S_; ++i)
    if (is_support(stations_[i])) support_station_.push_back(i);
  if (static_cast<int>(support_station_.size()) != sec.last - sec.first + 1)
    throw InputError(in_.file, "", "internal error: support stations do not match spans");
}

// A wire over all stations from node first_node, one tension segment per span.
void SectionBuilder::add_wire(const std::string& name, WireKind kind, const CableDesign& p,
                              int first_node) {
  Wire w;
  w.name = name;
  w.kind = kind;
  w.mass_per_length = p.mass_per_length;
  w.thermal_expansion = p.thermal_expansion;
  w.diameter = p.diameter;
  w.drag_coefficient = p.drag_coefficient;
  w.EA = p.EA;
  w.EI = p.EI;
  w.tension = p.tension;
  const int wire_index = static_cast<int>(mesh_.wires.size());
  for (int i = 0; i < S_; ++i) w.nodes.push_back(first_node + i);
  const int first_segment = static_cast<int>(mesh_.tension_segments.size());
  const auto& sec = geo_.layout();
  const bool per_span = kind == WireKind::messenger || line_.sections.size() == 1;
  for (int k = sec.first; k < (per_span ? sec.last : sec.first + 1); ++k)
    mesh_.tension_segments.push_back({wire_index, {}, {}, p.tension});
  for (int i = 0; i + 1 < S_; ++i) {
    CableElement e;
    e.nodes = {first_node + i, first_node + i + 1};
    e.wire = wire_index;
    e.ref_length = (mesh_.nodes[e.nodes[1]].position - mesh_.nodes[e.nodes[0]].position).norm();
    e.unstressed_length = e.ref_length / (1.0 + p.tension / p.EA);  // first guess
    e.tension_segment = first_segment + (per_span ? stations_[i].span - sec.first : 0);
    const int index = static_cast<int>(mesh_.cables.size());
    mesh_.tension_segments[e.tension_segment].elements.push_back(index);
    w.elements.push_back(index);
    mesh_.cables.push_back(e);
  }
  mesh_.wires.push_back(w);
}

// Stitch wires at the supports inside the section: each a chain of bars
// from the messenger clamp before the support, through the attachment nodes
// of the droppers inside its length, to the messenger clamp after it; its
// bars form a tension segment (form-finding finds their common length scale).
void SectionBuilder::add_stitch_wires() {
  const auto& sec = geo_.layout();
  for (int k = sec.first + 1; k < sec.last; ++k)
    if (geo_.stitch_at(k)) add_stitch_wire(k);
}

void SectionBuilder::add_stitch_wire(int k) {
  const StitchWireDesign& sw = *in_.stitch_wire;
  const double half = 0.5 * sw.length;
  std::vector<int> chain;
  for (int i = 0; i < S_; ++i) {
    const Station& st = stations_[i];
    const double x = st.span * L_ + st.s;
    if (std::abs(x - (k * L_ - half)) <= kSamePoint ||
        std::abs(x - (k * L_ + half)) <= kSamePoint) {
      chain.push_back(base_ + S_ + i);  // messenger clamp
    } else if (x > k * L_ - half && x < k * L_ + half && is_dropper(st)) {
      Node n;
      n.position = upper_point(st.span, st.s, geo_.messenger_sag);
      stitch_node_of_station_[i] = static_cast<int>(mesh_.nodes.size());
      chain.push_back(static_cast<int>(mesh_.nodes.size()));
      mesh_.nodes.push_back(n);
    }
  }
  TensionSegment segment{-1, {}, {}, sw.tension};
  for (std::size_t c = 0; c + 1 < chain.size(); ++c) {
    BarElement b;
    b.nodes = {chain[c], chain[c + 1]};
    b.kind = BarKind::stitch;
    const double l = (mesh_.nodes[b.nodes[1]].position - mesh_.nodes[b.nodes[0]].position).norm();
    b.unstressed_length = l / (1.0 + sw.tension / sw.EA);  // first guess: N = T in design
    b.stiffness = sw.EA / b.unstressed_length;
    b.mass = sw.mass_per_length * l;
    b.slack = SlackCriterion::none;
    segment.bars.push_back(static_cast<int>(mesh_.bars.size()));
    mesh_.bars.push_back(b);
  }
  mesh_.tension_segments.push_back(segment);
}

void SectionBuilder::fail_dropper_below_upper_wire(const Station& st, int i, bool on_stitch) const {
  const std::string where = "dropper " + std::to_string(st.dropper) + " of span " +
                            std::to_string(st.span) +
                            " (x = " + format_number(mesh_.nodes[i].position.x()) + " m)";
  if (on_stitch)
    throw InputError(in_.file, "stitch_wire.length",
                     "the stitch wire passes below the contact wire at " + where +
                         "; increase system_height or shorten it");
  throw InputError(in_.file, "system_height",
                   "the messenger (sag " + format_number(geo_.messenger_sag) +
                       " m) reaches the contact wire at " + where + "; increase system_height");
}

// Droppers, their clamps, and the form-finding height targets.
void SectionBuilder::add_droppers() {
  const DropperDesign& dr = in_.droppers;
  for (int i = 0; i < S_; ++i) {
    const Station& st = stations_[i];
    if (!is_dropper(st)) continue;
    const int lower = base_ + i;
    auto found = stitch_node_of_station_.find(i);
    const bool on_stitch = found != stitch_node_of_station_.end();
    const int upper = on_stitch ? found->second : base_ + S_ + i;
    if (!(mesh_.nodes[upper].position.z() > mesh_.nodes[lower].position.z()))
      fail_dropper_below_upper_wire(st, lower, on_stitch);
    BarElement b;
    b.nodes = {upper, lower};
    b.kind = BarKind::dropper;
    b.stiffness = dr.stiffness;
    b.axial_rigidity =
        dr.EA_per_position.empty() ? dr.EA.value_or(0.0) : dr.EA_per_position[st.dropper];
    const double l = (mesh_.nodes[upper].position - mesh_.nodes[lower].position).norm();
    b.mass = dr.mass_per_length * l;
    set_bar_unstressed_length(b, l);  // with EA: k = EA / l until form-finding sets L0
    b.slack = dr.slack;
    b.form_find_length = true;
    b.span = st.span;
    b.index_in_span = st.dropper;
    b.diameter = dr.diameter;
    b.drag_coefficient = dr.drag_coefficient;
    const int bar = static_cast<int>(mesh_.bars.size());
    mesh_.bars.push_back(b);
    mesh_.height_targets.push_back({lower, mesh_.nodes[lower].position.z(), bar});
    if (dr.clamp_mass_messenger > 0)
      mesh_.point_masses.push_back({upper, dr.clamp_mass_messenger, "dropper_clamp_messenger"});
    if (dr.clamp_mass_contact > 0)
      mesh_.point_masses.push_back({lower, dr.clamp_mass_contact, "dropper_clamp_contact"});
  }
}

}  // namespace pcsim::catenary::detail
