// ParametricDesign -> CatenaryMesh: simple catenary on straight track (see
// docs/design-format.md, "What the generator builds").
#include <algorithm>
#include <cmath>
#include <map>

#include "geometry_internal.hpp"

namespace pcsim::catenary {

namespace detail {

// Key points (supports, dropper points, stitch clamps) closer than this are
// rejected: they would make a needlessly tiny, very stiff element.
constexpr double kMinKeyPointGap = 0.05;  // [m]

namespace {

// ----------------------------------------------------------------- checks ----

void check_spans_and_heights(const ParametricDesign& in) {
  const std::string& f = in.file;
  const long count = in.span_count;
  if (count < 1)
    throw InputError(f, "spans.count", "must be at least 1 (got " + std::to_string(count) + ")");
  if (count > 100000)
    throw InputError(f, "spans.count", "is unreasonably large (got " + std::to_string(count) + ")");
  require_positive(f, "spans.length", in.span_length);
  require_positive(f, "system_height", in.system_height);
  require_positive(f, "contact_wire_height", in.contact_wire_height);
  require_nonnegative(f, "presag", in.presag);
  if (!(in.system_height > in.presag))
    throw InputError(f, "system_height",
                     "must exceed the contact-wire presag (" + fmt(in.presag) + " m), got " +
                         fmt(in.system_height) + " m");
  require_nonnegative(f, "stagger", in.stagger);
  require_nonnegative(f, "messenger_stagger", in.messenger_stagger);
  require_positive(f, "element_length", in.element_length);
  if (in.element_length > in.span_length)
    throw InputError(f, "element_length",
                     "must not exceed the span length " + fmt(in.span_length) + " m (got " +
                         fmt(in.element_length) + " m)");
}

void check_cable(const std::string& file, const std::string& key, const CableDesign& p) {
  require_positive(file, key + ".mass_per_length", p.mass_per_length);
  require_positive(file, key + ".EA", p.EA);
  require_nonnegative(file, key + ".EI", p.EI);
  require_positive(file, key + ".tension", p.tension);
}

void check_droppers(const ParametricDesign& in) {
  const std::string& f = in.file;
  const DropperDesign& d = in.droppers;
  const double L = in.span_length;
  if (d.positions.empty())
    throw InputError(f, "droppers.positions", "must list at least one dropper");
  for (std::size_t i = 0; i < d.positions.size(); ++i) {
    const std::string key = "droppers.positions[" + std::to_string(i) + "]";
    const double s = d.positions[i];
    if (!(s > 0 && s < L))
      throw InputError(f, key,
                       "dropper at " + fmt(s) + " m lies outside the span (0, " + fmt(L) + ") m");
    if (i > 0 && !(s > d.positions[i - 1]))
      throw InputError(f, key,
                       "dropper at " + fmt(s) + " m does not follow the previous one (" +
                           fmt(d.positions[i - 1]) + " m): positions must be strictly increasing");
  }
  require_positive(f, "droppers.stiffness", d.stiffness);
  require_nonnegative(f, "droppers.mass_per_length", d.mass_per_length);
  require_nonnegative(f, "droppers.clamp_mass_messenger", d.clamp_mass_messenger);
  require_nonnegative(f, "droppers.clamp_mass_contact", d.clamp_mass_contact);
}

void check_stitch_wire(const std::string& file, const StitchWireDesign& st, double L) {
  require_positive(file, "stitch_wire.length", st.length);
  if (!(st.length < L))
    throw InputError(file, "stitch_wire.length",
                     "must be shorter than the span (" + fmt(L) +
                         " m) so that the stitch wires of neighbouring supports do not "
                         "overlap (got " +
                         fmt(st.length) + " m)");
  require_positive(file, "stitch_wire.tension", st.tension);
  require_positive(file, "stitch_wire.mass_per_length", st.mass_per_length);
  require_positive(file, "stitch_wire.EA", st.EA);
}

}  // namespace

void check_parametric(const ParametricDesign& in) {
  check_spans_and_heights(in);
  check_cable(in.file, "wires.contact", in.contact);
  check_cable(in.file, "wires.messenger", in.messenger);
  check_droppers(in);
  require_nonnegative(in.file, "steady_arms.mass", in.steady_arm_mass);
  if (in.stitch_wire) check_stitch_wire(in.file, *in.stitch_wire, in.span_length);
}

// ------------------------------------------------------------- geometry ----

static std::string describe(const KeyPoint& k) {
  if (k.kind == KeyKind::dropper) return "the dropper at " + fmt(k.s) + " m";
  if (k.kind == KeyKind::stitch_clamp) return "the stitch-wire clamp at " + fmt(k.s) + " m";
  return "the support at " + fmt(k.s) + " m";
}

std::vector<KeyPoint> span_key_points(const ParametricDesign& in, int j) {
  const double L = in.span_length;
  const int N = static_cast<int>(in.span_count);
  const bool stitch = in.stitch_wire.has_value();
  std::vector<KeyPoint> pts;
  pts.push_back({0.0, KeyKind::support, -1});
  for (std::size_t d = 0; d < in.droppers.positions.size(); ++d)
    pts.push_back({in.droppers.positions[d], KeyKind::dropper, static_cast<int>(d)});
  // Stitch wires sit at the intermediate supports only.
  if (stitch && j >= 1) pts.push_back({0.5 * in.stitch_wire->length, KeyKind::stitch_clamp, -1});
  if (stitch && j + 1 <= N - 1)
    pts.push_back({L - 0.5 * in.stitch_wire->length, KeyKind::stitch_clamp, -1});
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
      const std::string reason = describe(p) + " lies only " + fmt(p.s - a.s) + " m from " +
                                 describe(a) + " (minimum spacing " + fmt(kMinKeyPointGap) + " m)";
      if (p.kind == KeyKind::stitch_clamp || a.kind == KeyKind::stitch_clamp)
        throw InputError(in.file, "stitch_wire.length", reason);
      const int d = p.kind == KeyKind::dropper ? p.index : a.index;
      throw InputError(in.file, "droppers.positions[" + std::to_string(d) + "]", reason);
    }
    merged.push_back(p);
  }
  return merged;
}

}  // namespace detail

namespace {

using detail::fmt;
using detail::KeyKind;
using detail::KeyPoint;
using detail::kSamePoint;
using detail::unit;

// Design geometry of the parametric catenary: s is the distance from the
// first support of span j.
struct ParametricGeometry {
  const ParametricDesign* in = nullptr;
  double messenger_sag = 0;  // mid-span sag f = w L^2 / (8 T) [m]

  double side(int support) const { return support % 2 == 0 ? 1.0 : -1.0; }
  // Contact wire: stagger alternating +-a, linear in between; parabolic presag.
  Eigen::Vector3d contact(int j, double s) const {
    const double L = in->span_length;
    return {j * L + s, side(j) * in->stagger * (1.0 - 2.0 * s / L),
            in->contact_wire_height - 4.0 * in->presag * s * (L - s) / (L * L)};
  }
  Eigen::Vector3d contact_tangent(int j, double s) const {
    const double L = in->span_length;
    return unit(Eigen::Vector3d(1.0, -2.0 * side(j) * in->stagger / L,
                                -4.0 * in->presag * (L - 2.0 * s) / (L * L)));
  }
  // Messenger: parabola of sag f between supports at system height.
  Eigen::Vector3d messenger(int j, double s) const {
    const double L = in->span_length;
    return {
        j * L + s, side(j) * in->messenger_stagger * (1.0 - 2.0 * s / L),
        in->contact_wire_height + in->system_height - 4.0 * messenger_sag * s * (L - s) / (L * L)};
  }
  Eigen::Vector3d messenger_tangent(int j, double s) const {
    const double L = in->span_length;
    return unit(Eigen::Vector3d(1.0, -2.0 * side(j) * in->messenger_stagger / L,
                                -4.0 * messenger_sag * (L - 2.0 * s) / (L * L)));
  }
};

// ------------------------------------------------------------- builder ----

class ParametricBuilder {
 public:
  explicit ParametricBuilder(const ParametricDesign& in)
      : in_(in), N_(static_cast<int>(in.span_count)), L_(in.span_length), geo_{&in, 0.0} {}

  CatenaryMesh build() {
    detail::set_common(mesh_, in_.file, in_.name, in_.gravity, in_.damping);
    mesh_.form_finding_default = true;
    make_stations();
    find_messenger_sag();
    place_nodes();
    // One tension segment per span for both wires: the messenger is pinned at
    // every support; the contact wire runs through them with a uniform
    // tension, so imposing it span by span is the same condition, and keeps
    // each form-finding row local (a single segment couples every
    // contact-wire DOF: a dense row that made the sparse factorisation of
    // long lines slow).
    add_wire("contact", WireKind::contact, in_.contact, 0);
    add_wire("messenger", WireKind::messenger, in_.messenger, S_);
    mesh_.contact_wire = 0;
    add_supports();
    if (in_.stitch_wire) add_stitch_wires();
    add_droppers();
    return std::move(mesh_);
  }

 private:
  // Stations along the track shared by both wires: (span, s) of every node.
  struct Station {
    int span;
    double s;
    KeyKind kind;
    int dropper;  // dropper index at dropper stations, -2 at plain nodes
  };
  static bool is_plain(const Station& st) { return st.dropper == -2; }
  static bool is_support(const Station& st) { return !is_plain(st) && st.kind == KeyKind::support; }
  static bool is_dropper(const Station& st) { return !is_plain(st) && st.kind == KeyKind::dropper; }

  void make_stations() {
    for (int j = 0; j < N_; ++j) {
      auto keys = detail::span_key_points(in_, j);
      for (std::size_t k = 0; k + 1 < keys.size(); ++k) {
        const double a = keys[k].s, b = keys[k + 1].s;
        int n = std::max(1, static_cast<int>(std::ceil((b - a) / in_.element_length - 1e-9)));
        stations_.push_back({j, a, keys[k].kind, keys[k].index});
        for (int i = 1; i < n; ++i)
          stations_.push_back({j, a + (b - a) * i / n, KeyKind::support, -2});
      }
    }
    stations_.push_back({N_ - 1, L_, KeyKind::support, -1});
    S_ = static_cast<int>(stations_.size());
  }

  // Dropper attachment: the messenger node, or a stitch-wire node when the
  // dropper lies strictly inside a stitch wire's length (returns its support).
  int stitch_support_of(int j, double s) const {
    if (!in_.stitch_wire) return -1;
    const double half = 0.5 * in_.stitch_wire->length;
    if (j >= 1 && s < half - kSamePoint) return j;
    if (j + 1 <= N_ - 1 && s > L_ - half + kSamePoint) return j + 1;
    return -1;
  }

  // Upper end of a dropper for a messenger sag 'sag'.
  Eigen::Vector3d upper_point(int j, double s, double sag) const {
    ParametricGeometry gg{&in_, sag};
    int k = stitch_support_of(j, s);
    if (k < 0) return gg.messenger(j, s);
    // Stitch wire: straight chord between its two messenger clamps.
    const double half = 0.5 * in_.stitch_wire->length;
    Eigen::Vector3d left = gg.messenger(k - 1, L_ - half), right = gg.messenger(k, half);
    const double x = j * L_ + s;
    const double t = (x - left.x()) / (right.x() - left.x());
    return Eigen::Vector3d(left + t * (right - left));
  }

  // Messenger sag from the weight per metre it carries (fixed point: the
  // dropper lengths depend on the sag; converges in a few steps).
  void find_messenger_sag() {
    const DropperDesign& dr = in_.droppers;
    const int D = static_cast<int>(dr.positions.size());
    const double g = -mesh_.gravity.z();
    for (int it = 0; it < 20; ++it) {
      double hung = D * (dr.clamp_mass_messenger + dr.clamp_mass_contact);
      for (int d = 0; d < D; ++d) {
        // Average over the spans (the stitch wire changes the end spans only).
        double len = 0;
        for (int j = 0; j < N_; ++j)
          len += (upper_point(j, dr.positions[d], geo_.messenger_sag) -
                  geo_.contact(j, dr.positions[d]))
                     .norm();
        hung += dr.mass_per_length * len / N_;
      }
      hung += in_.steady_arm_mass * (N_ + 1.0) / N_;
      if (in_.stitch_wire)
        hung += in_.stitch_wire->mass_per_length * in_.stitch_wire->length * (N_ - 1.0) / N_;
      const double w =
          g * (in_.messenger.mass_per_length + in_.contact.mass_per_length + hung / L_);
      const double sag = w * L_ * L_ / (8.0 * in_.messenger.tension);
      const bool done = std::abs(sag - geo_.messenger_sag) < 1e-13;
      geo_.messenger_sag = sag;
      if (done) break;
    }
  }

  // Nodes: contact wire 0..S-1, messenger S..2S-1 (stitch-wire nodes later).
  void place_nodes() {
    mesh_.nodes.resize(2 * S_);
    for (int i = 0; i < S_; ++i) {
      const Station& st = stations_[i];
      Node& c = mesh_.nodes[i];
      Node& m = mesh_.nodes[S_ + i];
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
    // The station list stores a support at s = 0 of span j; map x to support.
    for (int i = 0; i < S_; ++i)
      if (is_support(stations_[i])) support_station_.push_back(i);
    if (static_cast<int>(support_station_.size()) != N_ + 1)
      throw InputError(in_.file, "", "internal error: support stations do not match spans");
  }

  // A wire over all stations from node first_node, one tension segment per span.
  void add_wire(const std::string& name, WireKind kind, const CableDesign& p, int first_node) {
    Wire w;
    w.name = name;
    w.kind = kind;
    w.mass_per_length = p.mass_per_length;
    w.EA = p.EA;
    w.EI = p.EI;
    w.tension = p.tension;
    const int wire_index = static_cast<int>(mesh_.wires.size());
    for (int i = 0; i < S_; ++i) w.nodes.push_back(first_node + i);
    const int first_segment = static_cast<int>(mesh_.tension_segments.size());
    for (int k = 0; k < N_; ++k) mesh_.tension_segments.push_back({wire_index, {}, p.tension});
    for (int i = 0; i + 1 < S_; ++i) {
      CableElement e;
      e.nodes = {first_node + i, first_node + i + 1};
      e.wire = wire_index;
      e.ref_length = (mesh_.nodes[e.nodes[1]].position - mesh_.nodes[e.nodes[0]].position).norm();
      e.unstressed_length = e.ref_length / (1.0 + p.tension / p.EA);  // first guess
      e.tension_segment = first_segment + stations_[i].span;
      const int index = static_cast<int>(mesh_.cables.size());
      mesh_.tension_segments[e.tension_segment].elements.push_back(index);
      w.elements.push_back(index);
      mesh_.cables.push_back(e);
    }
    mesh_.wires.push_back(w);
  }

  // Supports: messenger pinned everywhere; contact wire anchored at the ends,
  // held laterally by the steady arms elsewhere (vertical motion free).
  void add_supports() {
    for (int k = 0; k <= N_; ++k) {
      const int i = support_station_[k];
      mesh_.support_x.push_back(k * L_);
      mesh_.support_nodes.push_back(i);
      for (int dof = 0; dof < 3; ++dof) mesh_.nodes[S_ + i].fixed[dof] = true;
      if (k == 0 || k == N_) {
        for (int dof = 0; dof < 3; ++dof) mesh_.nodes[i].fixed[dof] = true;
      } else {
        mesh_.nodes[i].fixed[1] = true;  // steady arm holds y at the stagger
      }
      if (in_.steady_arm_mass > 0)
        mesh_.point_masses.push_back({i, in_.steady_arm_mass, "steady_arm"});
    }
  }

  // Stitch wires at the intermediate supports: a chain of bars from the
  // messenger clamp before the support, through the attachment nodes of the
  // droppers inside its length, to the messenger clamp after it.
  void add_stitch_wires() {
    const StitchWireDesign& sw = *in_.stitch_wire;
    const double half = 0.5 * sw.length;
    for (int k = 1; k <= N_ - 1; ++k) {
      std::vector<int> chain;
      for (int i = 0; i < S_; ++i) {
        const Station& st = stations_[i];
        const double x = st.span * L_ + st.s;
        if (std::abs(x - (k * L_ - half)) <= kSamePoint ||
            std::abs(x - (k * L_ + half)) <= kSamePoint) {
          chain.push_back(S_ + i);  // messenger clamp
        } else if (x > k * L_ - half && x < k * L_ + half && is_dropper(st)) {
          Node n;
          n.position = upper_point(st.span, st.s, geo_.messenger_sag);
          stitch_node_of_station_[i] = static_cast<int>(mesh_.nodes.size());
          chain.push_back(static_cast<int>(mesh_.nodes.size()));
          mesh_.nodes.push_back(n);
        }
      }
      for (std::size_t c = 0; c + 1 < chain.size(); ++c) {
        BarElement b;
        b.nodes = {chain[c], chain[c + 1]};
        b.kind = BarKind::stitch;
        const double l =
            (mesh_.nodes[b.nodes[1]].position - mesh_.nodes[b.nodes[0]].position).norm();
        b.unstressed_length = l / (1.0 + sw.tension / sw.EA);  // N = T in design
        b.stiffness = sw.EA / b.unstressed_length;
        b.mass = sw.mass_per_length * l;
        b.slack = SlackCriterion::none;
        mesh_.bars.push_back(b);
      }
    }
  }

  [[noreturn]] void fail_dropper_below_upper_wire(const Station& st, int i, bool on_stitch) const {
    const std::string where = "dropper " + std::to_string(st.dropper) + " of span " +
                              std::to_string(st.span) +
                              " (x = " + fmt(mesh_.nodes[i].position.x()) + " m)";
    if (on_stitch)
      throw InputError(in_.file, "stitch_wire.length",
                       "the stitch wire passes below the contact wire at " + where +
                           "; increase system_height or shorten it");
    throw InputError(in_.file, "system_height",
                     "the messenger (sag " + fmt(geo_.messenger_sag) +
                         " m) reaches the contact wire at " + where + "; increase system_height");
  }

  // Droppers, their clamps, and the form-finding height targets.
  void add_droppers() {
    const DropperDesign& dr = in_.droppers;
    for (int i = 0; i < S_; ++i) {
      const Station& st = stations_[i];
      if (!is_dropper(st)) continue;
      auto found = stitch_node_of_station_.find(i);
      const bool on_stitch = found != stitch_node_of_station_.end();
      const int upper = on_stitch ? found->second : S_ + i;
      if (!(mesh_.nodes[upper].position.z() > mesh_.nodes[i].position.z()))
        fail_dropper_below_upper_wire(st, i, on_stitch);
      BarElement b;
      b.nodes = {upper, i};
      b.kind = BarKind::dropper;
      b.stiffness = dr.stiffness;
      const double l = (mesh_.nodes[upper].position - mesh_.nodes[i].position).norm();
      b.mass = dr.mass_per_length * l;
      b.unstressed_length = l;
      b.slack = dr.slack;
      b.form_find_length = true;
      b.span = st.span;
      b.index_in_span = st.dropper;
      const int bar = static_cast<int>(mesh_.bars.size());
      mesh_.bars.push_back(b);
      mesh_.height_targets.push_back({i, mesh_.nodes[i].position.z(), bar});
      if (dr.clamp_mass_messenger > 0)
        mesh_.point_masses.push_back({upper, dr.clamp_mass_messenger, "dropper_clamp_messenger"});
      if (dr.clamp_mass_contact > 0)
        mesh_.point_masses.push_back({i, dr.clamp_mass_contact, "dropper_clamp_contact"});
    }
  }

  const ParametricDesign& in_;
  const int N_;     // spans
  const double L_;  // span length [m]
  ParametricGeometry geo_;
  CatenaryMesh mesh_;
  std::vector<Station> stations_;
  int S_ = 0;  // stations = nodes per wire
  std::vector<int> support_station_;
  std::map<int, int> stitch_node_of_station_;  // contact station -> stitch node
};

}  // namespace

CatenaryMesh build_parametric(const ParametricDesign& design) {
  detail::check_parametric(design);
  CatenaryMesh mesh = ParametricBuilder(design).build();
  detail::require_consistent(mesh, design.file);
  return mesh;
}

}  // namespace pcsim::catenary
