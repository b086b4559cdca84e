// Catenary design files -> CatenaryMesh (see docs/design-format.md).
#include "pcsim/catenary/design.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <sstream>

namespace pcsim::catenary {

namespace {

// Key points (supports, dropper points, stitch clamps) closer than this are
// rejected: they would make a needlessly tiny, very stiff element.
constexpr double kMinKeyPointGap = 0.05;  // [m]
// Key points closer than this are the same point.
constexpr double kSamePoint = 1e-9;  // [m]

std::string fmt(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

std::string file_stem(const std::string& path) {
  auto slash = path.find_last_of('/');
  std::string base = slash == std::string::npos ? path : path.substr(slash + 1);
  auto dot = base.find_last_of('.');
  return dot == std::string::npos ? base : base.substr(0, dot);
}

Eigen::Vector3d read_gravity(const InputNode& root) {
  if (!root.has("gravity")) return {0.0, 0.0, -9.81};
  InputNode g = root["gravity"];
  if (g.is_sequence()) {
    auto v = g.as_vec3();
    return {v[0], v[1], v[2]};
  }
  return {0.0, 0.0, -root.get_nonnegative("gravity")};
}

void read_damping(const InputNode& root, CatenaryMesh& mesh) {
  if (!root.has("damping")) return;
  InputNode d = root["damping"];
  d.allow_only({"rayleigh_alpha", "rayleigh_beta"});
  mesh.rayleigh_alpha = d.get_nonnegative("rayleigh_alpha", 0.0);
  mesh.rayleigh_beta = d.get_nonnegative("rayleigh_beta", 0.0);
}

SlackCriterion slack_from(const std::string& s) {
  if (s == "length") return SlackCriterion::length;
  if (s == "force") return SlackCriterion::force;
  return SlackCriterion::none;
}

// Unit vector of a, or zero for a zero vector.
Eigen::Vector3d unit(const Eigen::Vector3d& a) {
  double n = a.norm();
  return n > 0 ? Eigen::Vector3d(a / n) : Eigen::Vector3d::Zero();
}

// Gives every node of a wire the unit tangent of the polyline through its
// nodes (mean of the adjacent element directions at interior nodes).
void set_polyline_slopes(CatenaryMesh& mesh, const std::vector<int>& nodes) {
  const int n = static_cast<int>(nodes.size());
  for (int i = 0; i < n; ++i) {
    Eigen::Vector3d t = Eigen::Vector3d::Zero();
    if (i > 0) t += unit(mesh.nodes[nodes[i]].position - mesh.nodes[nodes[i - 1]].position);
    if (i + 1 < n) t += unit(mesh.nodes[nodes[i + 1]].position - mesh.nodes[nodes[i]].position);
    mesh.nodes[nodes[i]].slope = unit(t);
  }
}

// Stretch lambda = Lref/L0 at which a straight cable element of the
// elements.hpp law (T = EA eps lambda, eps = (lambda^2 - 1)/2) carries T:
// solves lambda^3 - lambda = 2 T / EA by Newton.
double taut_stretch(double tension, double EA) {
  double lambda = 1.0 + tension / EA;
  for (int it = 0; it < 50; ++it) {
    double f = lambda * lambda * lambda - lambda - 2.0 * tension / EA;
    double step = f / (3.0 * lambda * lambda - 1.0);
    lambda -= step;
    if (std::abs(step) < 1e-15) break;
  }
  return lambda;
}

// ------------------------------------------------------------ parametric ----

struct CableProps {
  double mass_per_length = 0, EA = 0, EI = 0, tension = 0;
};

CableProps read_cable_props(const InputNode& n) {
  n.allow_only({"mass_per_length", "EA", "EI", "tension"});
  CableProps p;
  p.mass_per_length = n.get_positive("mass_per_length");
  p.EA = n.get_positive("EA");
  p.EI = n.get_nonnegative("EI");
  p.tension = n.get_positive("tension");
  return p;
}

// What a key point of a span is (for messages and for building the mesh).
enum class KeyKind { support, dropper, stitch_clamp };
struct KeyPoint {
  double s = 0;  // distance from the span's first support [m]
  KeyKind kind = KeyKind::support;
  int index = -1;  // dropper index for droppers
};

struct ParametricInput {
  std::string name;
  int span_count = 0;
  double span_length = 0;
  double system_height = 0, contact_height = 0, presag = 0;
  double stagger = 0, messenger_stagger = 0;
  double element_length = 0;
  CableProps contact, messenger;
  std::vector<double> dropper_s;
  double dropper_stiffness = 0, dropper_mass_per_length = 0;
  SlackCriterion dropper_slack = SlackCriterion::length;
  double clamp_mass_messenger = 0, clamp_mass_contact = 0;
  double steady_arm_mass = 0;
  bool stitch = false;
  double stitch_length = 0, stitch_tension = 0, stitch_mass_per_length = 0, stitch_EA = 0;
};

ParametricInput read_parametric(const InputNode& root) {
  root.allow_only({"type", "name", "spans", "system_height", "contact_wire_height", "presag",
                   "stagger", "messenger_stagger", "element_length", "wires", "droppers",
                   "steady_arms", "stitch_wire", "damping", "gravity"});
  ParametricInput in;
  in.name = root.get_string("name", file_stem(root.file()));

  InputNode spans = root["spans"];
  spans.allow_only({"count", "length"});
  long count = spans.get_int("count");
  if (count < 1) spans.fail_key("count", "must be at least 1 (got " + std::to_string(count) + ")");
  if (count > 100000)
    spans.fail_key("count", "is unreasonably large (got " + std::to_string(count) + ")");
  in.span_count = static_cast<int>(count);
  in.span_length = spans.get_positive("length");
  const double L = in.span_length;

  in.system_height = root.get_positive("system_height");
  in.contact_height = root.get_positive("contact_wire_height");
  in.presag = root.get_nonnegative("presag", 0.0);
  if (!(in.system_height > in.presag))
    root.fail_key("system_height", "must exceed the contact-wire presag (" + fmt(in.presag) +
                                       " m), got " + fmt(in.system_height) + " m");
  in.stagger = root.get_nonnegative("stagger", 0.0);
  in.messenger_stagger = root.get_nonnegative("messenger_stagger", 0.0);
  in.element_length = root.get_positive("element_length", 0.5);
  if (in.element_length > L)
    root.fail_key("element_length", "must not exceed the span length " + fmt(L) + " m (got " +
                                        fmt(in.element_length) + " m)");

  InputNode wires = root["wires"];
  wires.allow_only({"contact", "messenger"});
  in.contact = read_cable_props(wires["contact"]);
  in.messenger = read_cable_props(wires["messenger"]);

  InputNode drop = root["droppers"];
  drop.allow_only({"positions", "stiffness", "mass_per_length", "slack", "clamp_mass_messenger",
                   "clamp_mass_contact"});
  InputNode pos = drop["positions"];
  if (!pos.is_sequence()) pos.fail("must be a list of distances from the span's first support [m]");
  if (pos.size() == 0) pos.fail("must list at least one dropper");
  for (std::size_t i = 0; i < pos.size(); ++i) {
    double s = pos.at(i).as_double();
    if (!(s > 0 && s < L))
      pos.at(i).fail("dropper at " + fmt(s) + " m lies outside the span (0, " + fmt(L) + ") m");
    if (i > 0 && !(s > in.dropper_s.back()))
      pos.at(i).fail("dropper at " + fmt(s) + " m does not follow the previous one (" +
                     fmt(in.dropper_s.back()) + " m): positions must be strictly increasing");
    in.dropper_s.push_back(s);
  }
  in.dropper_stiffness = drop.get_positive("stiffness");
  in.dropper_mass_per_length = drop.get_nonnegative("mass_per_length", 0.0);
  in.dropper_slack = slack_from(drop.get_choice("slack", {"none", "length", "force"}, "length"));
  in.clamp_mass_messenger = drop.get_nonnegative("clamp_mass_messenger", 0.0);
  in.clamp_mass_contact = drop.get_nonnegative("clamp_mass_contact", 0.0);

  if (root.has("steady_arms")) {
    InputNode arms = root["steady_arms"];
    arms.allow_only({"mass", "model"});
    in.steady_arm_mass = arms.get_nonnegative("mass", 0.0);
    arms.get_choice("model", {"constraint"}, "constraint");
  }

  if (root.has("stitch_wire")) {
    InputNode st = root["stitch_wire"];
    st.allow_only({"length", "tension", "mass_per_length", "EA"});
    in.stitch = true;
    in.stitch_length = st.get_positive("length");
    if (!(in.stitch_length < L))
      st.fail_key("length", "must be shorter than the span (" + fmt(L) +
                                " m) so that the stitch wires of neighbouring supports do not "
                                "overlap (got " +
                                fmt(in.stitch_length) + " m)");
    in.stitch_tension = st.get_positive("tension");
    in.stitch_mass_per_length = st.get_positive("mass_per_length");
    in.stitch_EA = st.get_positive("EA");
  }
  return in;
}

// Key points of span j (0-based), sorted; coincident points merged (a
// stitch clamp on a dropper point stays a dropper point). Throws if two key
// points are closer than kMinKeyPointGap.
std::vector<KeyPoint> span_key_points(const ParametricInput& in, const InputNode& root, int j) {
  const double L = in.span_length;
  std::vector<KeyPoint> pts;
  pts.push_back({0.0, KeyKind::support, -1});
  for (std::size_t d = 0; d < in.dropper_s.size(); ++d)
    pts.push_back({in.dropper_s[d], KeyKind::dropper, static_cast<int>(d)});
  // Stitch wires sit at the intermediate supports only.
  if (in.stitch && j >= 1) pts.push_back({0.5 * in.stitch_length, KeyKind::stitch_clamp, -1});
  if (in.stitch && j + 1 <= in.span_count - 1)
    pts.push_back({L - 0.5 * in.stitch_length, KeyKind::stitch_clamp, -1});
  pts.push_back({L, KeyKind::support, -1});
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
      auto describe = [&](const KeyPoint& k) {
        if (k.kind == KeyKind::dropper) return "the dropper at " + fmt(k.s) + " m";
        if (k.kind == KeyKind::stitch_clamp) return "the stitch-wire clamp at " + fmt(k.s) + " m";
        return "the support at " + fmt(k.s) + " m";
      };
      std::string reason = describe(p) + " lies only " + fmt(p.s - a.s) + " m from " + describe(a) +
                           " (minimum spacing " + fmt(kMinKeyPointGap) + " m)";
      if (p.kind == KeyKind::stitch_clamp || a.kind == KeyKind::stitch_clamp)
        root["stitch_wire"].fail_key("length", reason);
      int d = p.kind == KeyKind::dropper ? p.index : a.index;
      root["droppers"]["positions"].at(static_cast<std::size_t>(d)).fail(reason);
    }
    merged.push_back(p);
  }
  return merged;
}

// Design geometry of the parametric catenary: s is the distance from the
// first support of span j.
struct ParametricGeometry {
  const ParametricInput* in = nullptr;
  double messenger_sag = 0;  // mid-span sag f = w L^2 / (8 T) [m]

  double side(int support) const { return support % 2 == 0 ? 1.0 : -1.0; }
  // Contact wire: stagger alternating +-a, linear in between; parabolic presag.
  Eigen::Vector3d contact(int j, double s) const {
    const double L = in->span_length;
    return {j * L + s, side(j) * in->stagger * (1.0 - 2.0 * s / L),
            in->contact_height - 4.0 * in->presag * s * (L - s) / (L * L)};
  }
  Eigen::Vector3d contact_tangent(int j, double s) const {
    const double L = in->span_length;
    return unit(Eigen::Vector3d(1.0, -2.0 * side(j) * in->stagger / L,
                                -4.0 * in->presag * (L - 2.0 * s) / (L * L)));
  }
  // Messenger: parabola of sag f between supports at system height.
  Eigen::Vector3d messenger(int j, double s) const {
    const double L = in->span_length;
    return {j * L + s, side(j) * in->messenger_stagger * (1.0 - 2.0 * s / L),
            in->contact_height + in->system_height - 4.0 * messenger_sag * s * (L - s) / (L * L)};
  }
  Eigen::Vector3d messenger_tangent(int j, double s) const {
    const double L = in->span_length;
    return unit(Eigen::Vector3d(1.0, -2.0 * side(j) * in->messenger_stagger / L,
                                -4.0 * messenger_sag * (L - 2.0 * s) / (L * L)));
  }
};

CatenaryMesh build_parametric(const InputNode& root) {
  const ParametricInput in = read_parametric(root);
  CatenaryMesh mesh;
  mesh.name = in.name;
  mesh.source_file = root.file();
  mesh.gravity = read_gravity(root);
  read_damping(root, mesh);
  mesh.form_finding_default = true;

  const int N = in.span_count;
  const double L = in.span_length;
  const int D = static_cast<int>(in.dropper_s.size());

  // Stations along the track shared by both wires: (span, s) of every node.
  struct Station {
    int span;
    double s;
    KeyKind kind;
    int dropper;  // dropper index at dropper stations
  };
  std::vector<Station> stations;
  for (int j = 0; j < N; ++j) {
    auto keys = span_key_points(in, root, j);
    for (std::size_t k = 0; k + 1 < keys.size(); ++k) {
      const double a = keys[k].s, b = keys[k + 1].s;
      int n = std::max(1, static_cast<int>(std::ceil((b - a) / in.element_length - 1e-9)));
      stations.push_back({j, a, keys[k].kind, keys[k].index});
      for (int i = 1; i < n; ++i)
        stations.push_back({j, a + (b - a) * i / n, KeyKind::support, -2});  // -2: plain node
    }
  }
  stations.push_back({N - 1, L, KeyKind::support, -1});
  const int S = static_cast<int>(stations.size());
  auto is_plain = [](const Station& st) { return st.dropper == -2; };
  auto is_support = [&](const Station& st) { return !is_plain(st) && st.kind == KeyKind::support; };

  // Dropper attachment: the messenger node, or a stitch-wire node when the
  // dropper lies strictly inside a stitch wire's length.
  auto stitch_support_of = [&](int j, double s) -> int {
    if (!in.stitch) return -1;
    const double half = 0.5 * in.stitch_length;
    if (j >= 1 && s < half - kSamePoint) return j;
    if (j + 1 <= N - 1 && s > L - half + kSamePoint) return j + 1;
    return -1;
  };

  // Messenger sag from the weight per metre it carries (fixed point: the
  // dropper lengths depend on the sag; converges in a few steps).
  ParametricGeometry geo{&in, 0.0};
  const double g = -mesh.gravity.z();
  auto upper_point = [&](int j, double s, double sag) {
    ParametricGeometry gg{&in, sag};
    int k = stitch_support_of(j, s);
    if (k < 0) return gg.messenger(j, s);
    // Stitch wire: straight chord between its two messenger clamps.
    const double half = 0.5 * in.stitch_length;
    Eigen::Vector3d left = gg.messenger(k - 1, L - half), right = gg.messenger(k, half);
    const double x = j * L + s;
    const double t = (x - left.x()) / (right.x() - left.x());
    return Eigen::Vector3d(left + t * (right - left));
  };
  for (int it = 0; it < 20; ++it) {
    double hung = D * (in.clamp_mass_messenger + in.clamp_mass_contact);
    for (int d = 0; d < D; ++d) {
      // Average over the spans (the stitch wire changes the end spans only).
      double len = 0;
      for (int j = 0; j < N; ++j)
        len +=
            (upper_point(j, in.dropper_s[d], geo.messenger_sag) - geo.contact(j, in.dropper_s[d]))
                .norm();
      hung += in.dropper_mass_per_length * len / N;
    }
    hung += in.steady_arm_mass * (N + 1.0) / N;
    if (in.stitch) hung += in.stitch_mass_per_length * in.stitch_length * (N - 1.0) / N;
    const double w = g * (in.messenger.mass_per_length + in.contact.mass_per_length + hung / L);
    const double sag = w * L * L / (8.0 * in.messenger.tension);
    const bool done = std::abs(sag - geo.messenger_sag) < 1e-13;
    geo.messenger_sag = sag;
    if (done) break;
  }

  // Nodes: contact wire 0..S-1, messenger S..2S-1, then stitch-wire nodes.
  mesh.nodes.resize(2 * S);
  for (int i = 0; i < S; ++i) {
    const Station& st = stations[i];
    Node& c = mesh.nodes[i];
    Node& m = mesh.nodes[S + i];
    c.position = geo.contact(st.span, st.s);
    m.position = geo.messenger(st.span, st.s);
    c.slope = geo.contact_tangent(st.span, st.s);
    m.slope = geo.messenger_tangent(st.span, st.s);
    if (is_support(st) && i > 0 && i + 1 < S) {
      // Support between two spans: the tangent is discontinuous (stagger,
      // messenger sag); use the mean of both sides as the design slope.
      c.slope = unit(c.slope + geo.contact_tangent(st.span - 1, L));
      m.slope = unit(m.slope + geo.messenger_tangent(st.span - 1, L));
    }
  }
  // The station list stores a support at s = 0 of span j; map x to support.
  std::vector<int> support_station;
  for (int i = 0; i < S; ++i)
    if (is_support(stations[i])) support_station.push_back(i);
  if (static_cast<int>(support_station.size()) != N + 1)
    throw InputError(root.file(), "", "internal error: support stations do not match spans");

  // Wires and cable elements.
  auto add_wire = [&](const std::string& name, WireKind kind, const CableProps& p, int first_node,
                      bool per_span_segments) {
    Wire w;
    w.name = name;
    w.kind = kind;
    w.mass_per_length = p.mass_per_length;
    w.EA = p.EA;
    w.EI = p.EI;
    w.tension = p.tension;
    const int wire_index = static_cast<int>(mesh.wires.size());
    for (int i = 0; i < S; ++i) w.nodes.push_back(first_node + i);
    const int first_segment = static_cast<int>(mesh.tension_segments.size());
    const int segments = per_span_segments ? N : 1;
    for (int k = 0; k < segments; ++k) mesh.tension_segments.push_back({wire_index, {}, p.tension});
    for (int i = 0; i + 1 < S; ++i) {
      CableElement e;
      e.nodes = {first_node + i, first_node + i + 1};
      e.wire = wire_index;
      e.ref_length = (mesh.nodes[e.nodes[1]].position - mesh.nodes[e.nodes[0]].position).norm();
      e.unstressed_length = e.ref_length / (1.0 + p.tension / p.EA);  // first guess
      e.tension_segment = first_segment + (per_span_segments ? stations[i].span : 0);
      const int index = static_cast<int>(mesh.cables.size());
      mesh.tension_segments[e.tension_segment].elements.push_back(index);
      w.elements.push_back(index);
      mesh.cables.push_back(e);
    }
    mesh.wires.push_back(w);
  };
  // One tension segment per span for both wires: the messenger is pinned at
  // every support; the contact wire runs through them with a uniform tension,
  // so imposing it span by span is the same condition, and keeps each
  // form-finding row local (a single segment couples every contact-wire DOF:
  // a dense row that made the sparse factorisation of long lines slow).
  add_wire("contact", WireKind::contact, in.contact, 0, true);
  add_wire("messenger", WireKind::messenger, in.messenger, S, true);
  mesh.contact_wire = 0;

  // Supports: messenger pinned everywhere; contact wire anchored at the ends,
  // held laterally by the steady arms elsewhere (vertical motion free).
  for (int k = 0; k <= N; ++k) {
    const int i = support_station[k];
    mesh.support_x.push_back(k * L);
    mesh.support_nodes.push_back(i);
    for (int dof = 0; dof < 3; ++dof) mesh.nodes[S + i].fixed[dof] = true;
    if (k == 0 || k == N) {
      for (int dof = 0; dof < 3; ++dof) mesh.nodes[i].fixed[dof] = true;
    } else {
      mesh.nodes[i].fixed[1] = true;  // steady arm holds y at the stagger
    }
    if (in.steady_arm_mass > 0) mesh.point_masses.push_back({i, in.steady_arm_mass, "steady_arm"});
  }

  // Stitch wires at the intermediate supports: a chain of bars from the
  // messenger clamp before the support, through the attachment nodes of the
  // droppers inside its length, to the messenger clamp after it.
  std::map<int, int> stitch_node_of_station;  // contact station -> stitch node
  if (in.stitch) {
    const double half = 0.5 * in.stitch_length;
    for (int k = 1; k <= N - 1; ++k) {
      std::vector<int> chain;
      for (int i = 0; i < S; ++i) {
        const Station& st = stations[i];
        const double x = st.span * L + st.s;
        if (std::abs(x - (k * L - half)) <= kSamePoint ||
            std::abs(x - (k * L + half)) <= kSamePoint) {
          chain.push_back(S + i);  // messenger clamp
        } else if (x > k * L - half && x < k * L + half && !is_plain(st) &&
                   st.kind == KeyKind::dropper) {
          Node n;
          n.position = upper_point(st.span, st.s, geo.messenger_sag);
          stitch_node_of_station[i] = static_cast<int>(mesh.nodes.size());
          chain.push_back(static_cast<int>(mesh.nodes.size()));
          mesh.nodes.push_back(n);
        }
      }
      for (std::size_t c = 0; c + 1 < chain.size(); ++c) {
        BarElement b;
        b.nodes = {chain[c], chain[c + 1]};
        b.kind = BarKind::stitch;
        const double l = (mesh.nodes[b.nodes[1]].position - mesh.nodes[b.nodes[0]].position).norm();
        b.unstressed_length = l / (1.0 + in.stitch_tension / in.stitch_EA);  // N = T in design
        b.stiffness = in.stitch_EA / b.unstressed_length;
        b.mass = in.stitch_mass_per_length * l;
        b.slack = SlackCriterion::none;
        mesh.bars.push_back(b);
      }
    }
  }

  // Droppers, their clamps, and the form-finding height targets.
  for (int i = 0; i < S; ++i) {
    const Station& st = stations[i];
    if (is_plain(st) || st.kind != KeyKind::dropper) continue;
    auto found = stitch_node_of_station.find(i);
    const int upper = found == stitch_node_of_station.end() ? S + i : found->second;
    BarElement b;
    b.nodes = {upper, i};
    b.kind = BarKind::dropper;
    b.stiffness = in.dropper_stiffness;
    const double l = (mesh.nodes[upper].position - mesh.nodes[i].position).norm();
    if (!(mesh.nodes[upper].position.z() > mesh.nodes[i].position.z())) {
      const std::string where = "dropper " + std::to_string(st.dropper) + " of span " +
                                std::to_string(st.span) +
                                " (x = " + fmt(mesh.nodes[i].position.x()) + " m)";
      if (found != stitch_node_of_station.end())
        root["stitch_wire"].fail_key("length", "the stitch wire passes below the contact wire at " +
                                                   where +
                                                   "; increase system_height or shorten it");
      root.fail_key("system_height", "the messenger (sag " + fmt(geo.messenger_sag) +
                                         " m) reaches the contact wire at " + where +
                                         "; increase system_height");
    }
    b.mass = in.dropper_mass_per_length * l;
    b.unstressed_length = l;
    b.slack = in.dropper_slack;
    b.form_find_length = true;
    b.span = st.span;
    b.index_in_span = st.dropper;
    const int bar = static_cast<int>(mesh.bars.size());
    mesh.bars.push_back(b);
    mesh.height_targets.push_back({i, mesh.nodes[i].position.z(), bar});
    if (in.clamp_mass_messenger > 0)
      mesh.point_masses.push_back({upper, in.clamp_mass_messenger, "dropper_clamp_messenger"});
    if (in.clamp_mass_contact > 0)
      mesh.point_masses.push_back({i, in.clamp_mass_contact, "dropper_clamp_contact"});
  }
  return mesh;
}

// -------------------------------------------------------------- explicit ----

// A node given as an index, or as {wire: name, node: k} (k-th node along a
// wire defined earlier; negative k counts from the wire's end).
int read_node_ref(const InputNode& n, const CatenaryMesh& mesh) {
  if (n.is_map()) {
    n.allow_only({"wire", "node"});
    const std::string name = n.get_string("wire");
    const int w = mesh.find_wire(name);
    if (w < 0) {
      std::string known;
      for (const auto& wire : mesh.wires) known += (known.empty() ? "" : ", ") + wire.name;
      n.fail_key("wire", "no wire named '" + name + "' is defined before this point (known: " +
                             (known.empty() ? std::string("none") : known) + ")");
    }
    const long count = static_cast<long>(mesh.wires[w].nodes.size());
    long k = n.get_int("node");
    const long given = k;
    if (k < 0) k += count;
    if (k < 0 || k >= count)
      n.fail_key("node", "wire '" + name + "' has nodes 0.." + std::to_string(count - 1) +
                             " (got " + std::to_string(given) + ")");
    return mesh.wires[w].nodes[k];
  }
  const long i = n.as_int();
  const long count = static_cast<long>(mesh.nodes.size());
  if (i < 0 || i >= count)
    n.fail("node index " + std::to_string(i) + " is out of range (the design has " +
           std::to_string(count) + " nodes, 0.." + std::to_string(count - 1) + ")");
  return static_cast<int>(i);
}

int read_dof(const InputNode& n) {
  const std::string s = n.as_string();
  static const char* names[] = {"x", "y", "z", "dx", "dy", "dz"};
  for (int d = 0; d < kNodeDofs; ++d)
    if (s == names[d]) return d;
  n.fail("unknown degree of freedom '" + s + "' (use x, y, z for position, dx, dy, dz for slope)");
}

void read_explicit_wire(const InputNode& wn, CatenaryMesh& mesh, std::vector<int>& wire_of_node) {
  wn.allow_only({"name", "kind", "nodes", "mass_per_length", "EA", "EI", "tension", "unstressed"});
  Wire w;
  w.name = wn.get_string("name", "wire" + std::to_string(mesh.wires.size()));
  if (mesh.find_wire(w.name) >= 0) wn.fail_key("name", "wire '" + w.name + "' is defined twice");
  const std::string kind =
      wn.get_choice("kind", {"messenger", "contact", "stitch", "other"}, "other");
  w.kind = kind == "messenger" ? WireKind::messenger
           : kind == "contact" ? WireKind::contact
           : kind == "stitch"  ? WireKind::stitch
                               : WireKind::other;
  w.mass_per_length = wn.get_positive("mass_per_length");
  w.EA = wn.get_positive("EA");
  w.EI = wn.get_nonnegative("EI");
  w.tension = wn.get_nonnegative("tension", 0.0);

  InputNode nodes = wn["nodes"];
  if (nodes.is_map()) {
    nodes.allow_only({"from", "to", "elements"});
    const int a = read_node_ref(nodes["from"], mesh);
    const int b = read_node_ref(nodes["to"], mesh);
    const long n = nodes.get_int("elements");
    if (n < 1 || n > 10000000)
      nodes.fail_key("elements",
                     "must be a positive number of elements (got " + std::to_string(n) + ")");
    if (a == b) nodes.fail("'from' and 'to' are the same node " + std::to_string(a));
    const Eigen::Vector3d pa = mesh.nodes[a].position, pb = mesh.nodes[b].position;
    w.nodes.push_back(a);
    for (long i = 1; i < n; ++i) {
      Node node;
      node.position = pa + (pb - pa) * (static_cast<double>(i) / n);
      w.nodes.push_back(static_cast<int>(mesh.nodes.size()));
      mesh.nodes.push_back(node);
      wire_of_node.push_back(-1);
    }
    w.nodes.push_back(b);
  } else if (nodes.is_sequence()) {
    if (nodes.size() < 2) nodes.fail("a wire needs at least 2 nodes");
    for (std::size_t i = 0; i < nodes.size(); ++i)
      w.nodes.push_back(read_node_ref(nodes.at(i), mesh));
  } else {
    nodes.fail("must be a list of nodes or a map {from, to, elements}");
  }

  const int wire_index = static_cast<int>(mesh.wires.size());
  for (std::size_t i = 0; i < w.nodes.size(); ++i) {
    const int id = w.nodes[i];
    if (wire_of_node[id] >= 0) {
      const std::string other = wire_of_node[id] == wire_index
                                    ? std::string("this wire")
                                    : "wire '" + mesh.wires[wire_of_node[id]].name + "'";
      nodes.fail("node " + std::to_string(id) + " already belongs to " + other +
                 "; cable wires cannot share or revisit nodes (join wires with a bar)");
    }
    wire_of_node[id] = wire_index;
  }

  // Unstressed length: a ratio of the design length, or 'taut' (the cable
  // carries 'tension' in its straight design configuration).
  double ratio = 1.0 / taut_stretch(w.tension, w.EA);
  if (wn.has("unstressed")) {
    InputNode u = wn["unstressed"];
    if (!u.is_scalar()) u.fail("must be 'taut' or a positive ratio L0/L");
    if (u.as_string() != "taut") {
      double r = 0;
      try {
        r = u.as_double();
      } catch (const InputError&) {
        u.fail("must be 'taut' or a positive ratio L0/L, got '" + u.as_string() + "'");
      }
      if (!(r > 0)) u.fail("must be 'taut' or a positive ratio L0/L (got " + fmt(r) + ")");
      ratio = r;
    }
  }

  for (std::size_t i = 0; i + 1 < w.nodes.size(); ++i) {
    CableElement e;
    e.nodes = {w.nodes[i], w.nodes[i + 1]};
    e.wire = wire_index;
    e.ref_length = (mesh.nodes[e.nodes[1]].position - mesh.nodes[e.nodes[0]].position).norm();
    if (!(e.ref_length > 0))
      nodes.fail("element " + std::to_string(i) + " joins nodes " + std::to_string(e.nodes[0]) +
                 " and " + std::to_string(e.nodes[1]) +
                 " at the same position: an element needs a positive length");
    e.unstressed_length = ratio * e.ref_length;
    w.elements.push_back(static_cast<int>(mesh.cables.size()));
    mesh.cables.push_back(e);
  }
  mesh.wires.push_back(w);
  set_polyline_slopes(mesh, mesh.wires.back().nodes);
}

CatenaryMesh build_explicit(const InputNode& root) {
  root.allow_only({"type", "name", "gravity", "nodes", "wires", "bars", "supports", "point_masses",
                   "springs", "targets", "tension_segments", "form_finding", "damping",
                   "support_nodes"});
  CatenaryMesh mesh;
  mesh.name = root.get_string("name", file_stem(root.file()));
  mesh.source_file = root.file();
  mesh.gravity = read_gravity(root);
  read_damping(root, mesh);
  mesh.form_finding_default = root.get_bool("form_finding", false);

  if (root.has("nodes")) {
    InputNode nodes = root["nodes"];
    if (!nodes.is_sequence()) nodes.fail("must be a list of [x, y, z] positions");
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      auto p = nodes.at(i).as_vec3();
      Node n;
      n.position = Eigen::Vector3d(p[0], p[1], p[2]);
      mesh.nodes.push_back(n);
    }
  }
  std::vector<int> wire_of_node(mesh.nodes.size(), -1);

  auto list = [&](const char* key) -> std::vector<InputNode> {
    std::vector<InputNode> out;
    if (!root.has(key)) return out;
    InputNode l = root[key];
    if (!l.is_sequence()) l.fail("must be a list");
    for (std::size_t i = 0; i < l.size(); ++i) out.push_back(l.at(i));
    return out;
  };

  for (const auto& wn : list("wires")) read_explicit_wire(wn, mesh, wire_of_node);
  for (std::size_t w = 0; w < mesh.wires.size(); ++w) {
    if (mesh.wires[w].kind != WireKind::contact) continue;
    if (mesh.contact_wire >= 0)
      root["wires"].fail("at most one wire may be of kind 'contact' ('" +
                         mesh.wires[mesh.contact_wire].name + "' and '" + mesh.wires[w].name +
                         "')");
    mesh.contact_wire = static_cast<int>(w);
  }

  for (const auto& bn : list("bars")) {
    bn.allow_only({"nodes", "kind", "stiffness", "mass", "unstressed_length", "slack", "form_find",
                   "span", "index_in_span"});
    InputNode nodes = bn["nodes"];
    if (!nodes.is_sequence() || nodes.size() != 2) nodes.fail("must be a list of 2 nodes [a, b]");
    BarElement b;
    b.nodes = {read_node_ref(nodes.at(0), mesh), read_node_ref(nodes.at(1), mesh)};
    if (b.nodes[0] == b.nodes[1])
      nodes.fail("the bar joins node " + std::to_string(b.nodes[0]) +
                 " to itself: impossible geometry");
    const double l = (mesh.nodes[b.nodes[1]].position - mesh.nodes[b.nodes[0]].position).norm();
    if (!(l > 0))
      nodes.fail("nodes " + std::to_string(b.nodes[0]) + " and " + std::to_string(b.nodes[1]) +
                 " are at the same position: a bar needs a positive design length");
    const std::string kind =
        bn.get_choice("kind", {"dropper", "steady_arm", "stitch", "other"}, "other");
    b.kind = kind == "dropper"      ? BarKind::dropper
             : kind == "steady_arm" ? BarKind::steady_arm
             : kind == "stitch"     ? BarKind::stitch
                                    : BarKind::other;
    b.stiffness = bn.get_positive("stiffness");
    b.mass = bn.get_nonnegative("mass", 0.0);
    b.unstressed_length = bn.get_positive("unstressed_length", l);
    b.slack = slack_from(bn.get_choice("slack", {"none", "length", "force"}, "none"));
    b.form_find_length = bn.get_bool("form_find", false);
    b.span = static_cast<int>(bn.get_int("span", -1));
    b.index_in_span = static_cast<int>(bn.get_int("index_in_span", -1));
    if (b.span < -1) bn.fail_key("span", "must not be negative");
    if (b.index_in_span < -1) bn.fail_key("index_in_span", "must not be negative");
    mesh.bars.push_back(b);
  }

  for (const auto& sn : list("supports")) {
    sn.allow_only({"node", "fix"});
    const int node = read_node_ref(sn["node"], mesh);
    if (!sn.has("fix")) {
      for (int d = 0; d < 3; ++d) mesh.nodes[node].fixed[d] = true;
      continue;
    }
    InputNode fix = sn["fix"];
    if (!fix.is_sequence() || fix.size() == 0)
      fix.fail("must be a non-empty list of x, y, z, dx, dy, dz");
    for (std::size_t i = 0; i < fix.size(); ++i) mesh.nodes[node].fixed[read_dof(fix.at(i))] = true;
  }

  for (const auto& pn : list("point_masses")) {
    pn.allow_only({"node", "mass", "label"});
    mesh.point_masses.push_back({read_node_ref(pn["node"], mesh), pn.get_positive("mass"),
                                 pn.get_string("label", "point_mass")});
  }

  for (const auto& sn : list("springs")) {
    sn.allow_only({"node", "dof", "stiffness"});
    SupportSpring s;
    s.node = read_node_ref(sn["node"], mesh);
    s.dof = read_dof(sn["dof"]);
    if (s.dof > 2) sn.fail_key("dof", "springs act on a position DOF: x, y or z");
    s.stiffness = sn.get_positive("stiffness");
    mesh.springs.push_back(s);
  }

  std::set<int> targeted_bars;
  for (const auto& tn : list("targets")) {
    tn.allow_only({"node", "z", "bar"});
    HeightTarget t;
    t.node = read_node_ref(tn["node"], mesh);
    t.z = tn.get_double("z", mesh.nodes[t.node].position.z());
    const long bar = tn.get_int("bar");
    if (bar < 0 || bar >= static_cast<long>(mesh.bars.size()))
      tn.fail_key("bar", "bar index " + std::to_string(bar) + " is out of range (the design has " +
                             std::to_string(mesh.bars.size()) + " bars)");
    if (!mesh.bars[bar].form_find_length)
      tn.fail_key("bar", "bar " + std::to_string(bar) +
                             " is not a form-finding bar (give it form_find: true)");
    if (!targeted_bars.insert(static_cast<int>(bar)).second)
      tn.fail_key("bar", "bar " + std::to_string(bar) + " already matches another target");
    t.bar = static_cast<int>(bar);
    mesh.height_targets.push_back(t);
  }

  for (const auto& sn : list("tension_segments")) {
    sn.allow_only({"wire", "tension"});
    const std::string name = sn.get_string("wire");
    const int w = mesh.find_wire(name);
    if (w < 0) sn.fail_key("wire", "no wire named '" + name + "'");
    for (const auto& seg : mesh.tension_segments)
      if (seg.wire == w) sn.fail_key("wire", "wire '" + name + "' already has a tension segment");
    TensionSegment seg;
    seg.wire = w;
    seg.tension = sn.has("tension") ? sn.get_positive("tension") : mesh.wires[w].tension;
    if (!(seg.tension > 0))
      sn.fail("needs a positive tension (the wire '" + name + "' has none; give 'tension')");
    seg.elements = mesh.wires[w].elements;
    const int index = static_cast<int>(mesh.tension_segments.size());
    for (int e : seg.elements) mesh.cables[e].tension_segment = index;
    mesh.tension_segments.push_back(seg);
  }

  if (root.has("support_nodes")) {
    InputNode sn = root["support_nodes"];
    if (!sn.is_sequence()) sn.fail("must be a list of nodes");
    for (std::size_t i = 0; i < sn.size(); ++i) {
      const int node = read_node_ref(sn.at(i), mesh);
      mesh.support_nodes.push_back(node);
      mesh.support_x.push_back(mesh.nodes[node].position.x());
    }
  }
  return mesh;
}

}  // namespace

CatenaryMesh build_catenary_design(const InputNode& root) {
  if (!root.is_map()) root.fail("a design must be a map of keys");
  const std::string type = root.get_choice("type", {"parametric", "explicit"}, "");
  if (type.empty()) root.fail_key("type", "required key is missing (parametric or explicit)");
  CatenaryMesh mesh = type == "parametric" ? build_parametric(root) : build_explicit(root);
  const std::string problem = mesh_consistency_error(mesh);
  if (!problem.empty()) throw InputError(root.file(), "", "inconsistent mesh: " + problem);
  return mesh;
}

CatenaryMesh load_catenary_design(const std::string& path) {
  CatenaryMesh mesh = build_catenary_design(InputNode::load_file(path));
  mesh.source_file = path;
  return mesh;
}

std::string mesh_consistency_error(const CatenaryMesh& mesh) {
  const int n_nodes = static_cast<int>(mesh.nodes.size());
  auto bad_node = [&](int i) { return i < 0 || i >= n_nodes; };
  auto length = [&](int a, int b) {
    return (mesh.nodes[b].position - mesh.nodes[a].position).norm();
  };
  for (std::size_t e = 0; e < mesh.cables.size(); ++e) {
    const auto& c = mesh.cables[e];
    const std::string id = "cable element " + std::to_string(e);
    if (bad_node(c.nodes[0]) || bad_node(c.nodes[1])) return id + " has a node out of range";
    if (c.nodes[0] == c.nodes[1]) return id + " joins a node to itself";
    if (c.wire < 0 || c.wire >= static_cast<int>(mesh.wires.size())) return id + " has no wire";
    if (!(c.ref_length > 0) || !(c.unstressed_length > 0)) return id + " has a non-positive length";
    if (std::abs(c.ref_length - length(c.nodes[0], c.nodes[1])) > 1e-9 * (1.0 + c.ref_length))
      return id + ": ref_length differs from its design length";
    if (c.tension_segment < -1 ||
        c.tension_segment >= static_cast<int>(mesh.tension_segments.size()))
      return id + " has a tension segment out of range";
  }
  for (std::size_t w = 0; w < mesh.wires.size(); ++w) {
    const auto& wire = mesh.wires[w];
    const std::string id = "wire '" + wire.name + "'";
    if (wire.nodes.size() != wire.elements.size() + 1) return id + ": nodes and elements disagree";
    for (std::size_t k = 0; k < wire.elements.size(); ++k) {
      const int e = wire.elements[k];
      if (e < 0 || e >= static_cast<int>(mesh.cables.size())) return id + ": element out of range";
      const auto& c = mesh.cables[e];
      if (c.wire != static_cast<int>(w) || c.nodes[0] != wire.nodes[k] ||
          c.nodes[1] != wire.nodes[k + 1])
        return id + ": element " + std::to_string(e) + " is not in order along the wire";
    }
    if (!(wire.mass_per_length > 0) || !(wire.EA > 0) || wire.EI < 0 || wire.tension < 0)
      return id + ": invalid properties";
  }
  for (std::size_t b = 0; b < mesh.bars.size(); ++b) {
    const auto& bar = mesh.bars[b];
    const std::string id = "bar " + std::to_string(b);
    if (bad_node(bar.nodes[0]) || bad_node(bar.nodes[1])) return id + " has a node out of range";
    if (!(length(bar.nodes[0], bar.nodes[1]) > 0)) return id + " has zero design length";
    if (!(bar.stiffness > 0) || !(bar.unstressed_length > 0) || bar.mass < 0)
      return id + ": invalid properties";
  }
  for (const auto& pm : mesh.point_masses)
    if (bad_node(pm.node) || !(pm.mass > 0)) return "point mass '" + pm.label + "' is invalid";
  for (const auto& s : mesh.springs)
    if (bad_node(s.node) || s.dof < 0 || s.dof > 2 || !(s.stiffness > 0))
      return "a spring is invalid";
  std::set<int> bars_used;
  for (const auto& t : mesh.height_targets) {
    if (bad_node(t.node)) return "a height target has a node out of range";
    if (t.bar < 0 || t.bar >= static_cast<int>(mesh.bars.size()) ||
        !mesh.bars[t.bar].form_find_length)
      return "a height target does not point at a form-finding bar";
    if (!bars_used.insert(t.bar).second)
      return "two height targets share bar " + std::to_string(t.bar);
  }
  for (std::size_t s = 0; s < mesh.tension_segments.size(); ++s) {
    const auto& seg = mesh.tension_segments[s];
    if (seg.wire < 0 || seg.wire >= static_cast<int>(mesh.wires.size()) || seg.elements.empty() ||
        !(seg.tension > 0))
      return "tension segment " + std::to_string(s) + " is invalid";
    for (int e : seg.elements)
      if (e < 0 || e >= static_cast<int>(mesh.cables.size()) || mesh.cables[e].wire != seg.wire ||
          mesh.cables[e].tension_segment != static_cast<int>(s))
        return "tension segment " + std::to_string(s) + " lists element " + std::to_string(e) +
               " that is not its own";
  }
  if (mesh.support_x.size() != mesh.support_nodes.size())
    return "support_x and support_nodes differ";
  for (int n : mesh.support_nodes)
    if (bad_node(n)) return "a support node is out of range";
  if (mesh.contact_wire < -1 || mesh.contact_wire >= static_cast<int>(mesh.wires.size()))
    return "contact_wire is out of range";
  return "";
}

}  // namespace pcsim::catenary
