// Parametric lines: the layout of the tension sections over the supports and
// the design geometry of a section's wires (see docs/design-format.md, "What
// the generator builds").
#include <algorithm>
#include <cmath>

#include "geometry_line.hpp"

namespace pcsim::catenary::detail {

namespace {

void set_roles(SectionLayout& sec, int S, int i, const std::vector<int>& q, int m) {
  for (int k = sec.first; k <= sec.last; ++k) sec.role[k] = Role::service;
  if (i > 0) {  // starts in the overlap with section i-1: anchor, raised, in service
    sec.role[sec.first] = Role::anchor;
    sec.role[q[i - 1]] = Role::raised;
  }
  if (i + 1 < S) {  // ends in the overlap with section i+1: in service, raised, anchor
    sec.role[q[i] + m] = Role::raised;
    sec.role[sec.last] = Role::anchor;
  }
}

// At every support the wires there (n of them, in section order) are spread
// across the track 'separation' apart around the stagger position, the
// earlier section to the left: +-1/2 for two, +1, 0, -1 for three (a short
// middle section, whose two overlaps share supports).
void set_lateral_shifts(std::vector<SectionLayout>& sections, int N) {
  for (int k = 0; k <= N; ++k) {
    int n = 0;
    for (const auto& sec : sections) n += sec.role[k] != Role::none;
    int index = 0;
    for (auto& sec : sections)
      if (sec.role[k] != Role::none) sec.lateral_shift[k] = 0.5 * (n - 1) - index++;
  }
}

// Spans a section needs for its overlaps: a first one floor(m/2) + 1 (its
// wires run to the anchor one span beyond the overlap), a last one
// ceil(m/2) + 1, a middle one m + 1 (raised supports of its two overlaps
// apart).
void check_section_lengths(const ParametricDesign& in, const std::vector<SectionDesign>& sections,
                           int m) {
  const std::size_t S = sections.size();
  if (S < 2) return;
  for (std::size_t i = 0; i < S; ++i) {
    const char* which = i == 0 ? "a first" : (i + 1 == S ? "a last" : "a middle");
    const long need = i == 0 ? m / 2 + 1 : (i + 1 == S ? (m + 1) / 2 + 1 : m + 1);
    if (sections[i].spans < need)
      throw InputError(in.file, "sections[" + std::to_string(i) + "].spans",
                       "section " + std::to_string(i + 1) + " of " +
                           std::to_string(sections[i].spans) +
                           " spans is too short for its overlaps of " + std::to_string(m) +
                           " spans: " + which + " section needs at least " + std::to_string(need) +
                           " (its wires run over the overlap and one anchor span beyond it)");
  }
}

}  // namespace

LineLayout make_line_layout(const ParametricDesign& in) {
  LineLayout line;
  line.spans = static_cast<int>(in.span_count);
  line.L = in.span_length;
  const int N = line.spans;
  std::vector<SectionDesign> sections = in.sections;
  if (sections.empty()) sections.push_back({in.span_count, 0.0});
  const int S = static_cast<int>(sections.size()), m = static_cast<int>(in.overlap.spans);
  check_section_lengths(in, sections, m);
  line.overlap_spans = m;
  std::vector<int> boundary = {0};  // B_i: last support each section owns
  for (const auto& sec : sections)
    boundary.push_back(boundary.back() + static_cast<int>(sec.spans));
  for (int j = 0; j + 1 < S; ++j) line.overlap_first.push_back(boundary[j + 1] - m / 2);
  const auto& q = line.overlap_first;
  for (int i = 0; i < S; ++i) {
    SectionLayout sec;
    sec.own_first = boundary[i];
    sec.own_last = boundary[i + 1];
    sec.first = i > 0 ? q[i - 1] - 1 : 0;
    sec.last = i + 1 < S ? q[i] + m + 1 : N;
    sec.role.assign(N + 1, Role::none);
    sec.lateral_shift.assign(N + 1, 0.0);
    set_roles(sec, S, i, q, m);
    line.sections.push_back(sec);
  }
  set_lateral_shifts(line.sections, N);
  bool curved = false;
  std::vector<TrackPiece> pieces;
  for (const auto& sec : sections) {
    pieces.push_back({sec.spans * in.span_length, sec.radius});
    curved = curved || sec.radius != 0;
  }
  if (curved) line.track = TrackAlignment(pieces);
  return line;
}

// ---------------------------------------------------------- geometry ----

SectionGeometry::SectionGeometry(const ParametricDesign& in, const LineLayout& line, int section,
                                 const IrregularProfile& profile)
    : in_(in), line_(line), section_(section), profile_(profile) {
  for (std::size_t i = 0; i < in.droppers.spans.size(); ++i)
    for (long span : in.droppers.spans[i].spans) span_override_[span - 1] = static_cast<int>(i);
  const double g = std::max(0.0, -in.gravity.z()), L = in.span_length;
  contact_anchor_sag_ = g * in.contact.mass_per_length * L * L / (8.0 * in.contact.tension);
  messenger_anchor_sag_ = g * in.messenger.mass_per_length * L * L / (8.0 * in.messenger.tension);
}

bool SectionGeometry::dropper_span(int j) const {
  const Role a = role(j), b = role(j + 1);
  return a != Role::none && b != Role::none && a != Role::anchor && b != Role::anchor;
}

bool SectionGeometry::service_span(int j) const {
  return role(j) == Role::service && role(j + 1) == Role::service;
}

bool SectionGeometry::anchor_span(int j) const {
  return role(j) != Role::none && role(j + 1) != Role::none &&
         (role(j) == Role::anchor || role(j + 1) == Role::anchor);
}

bool SectionGeometry::stitch_at(int k) const {
  const auto& sec = layout();
  return in_.stitch_wire && k > sec.first && k < sec.last && role(k - 1) == Role::service &&
         role(k) == Role::service && role(k + 1) == Role::service;
}

const std::vector<double>& SectionGeometry::positions(int j) const {
  auto it = span_override_.find(j);
  return it == span_override_.end() ? in_.droppers.positions
                                    : in_.droppers.spans[it->second].positions;
}

const std::vector<double>& SectionGeometry::sags(int j) const {
  auto it = span_override_.find(j);
  return it == span_override_.end() ? in_.droppers.sags : in_.droppers.spans[it->second].sags;
}

std::string SectionGeometry::positions_key(int j) const {
  auto it = span_override_.find(j);
  if (it == span_override_.end()) return "droppers.positions";
  return "droppers.spans[" + std::to_string(it->second) + "].positions";
}

double SectionGeometry::support_z(int k) const {
  const double h = in_.contact_wire_height;
  if (role(k) == Role::raised) return h + in_.overlap.raise;
  if (role(k) == Role::anchor) return h + in_.overlap.anchor_raise;
  return h;
}

// The stagger pattern; where several sections' wires meet both wires of a
// section shifted across by its lateral_shift x separation.
double SectionGeometry::lateral(int k, bool messenger) const {
  const double y = (k % 2 == 0 ? 1.0 : -1.0) * (messenger ? in_.messenger_stagger : in_.stagger);
  const double shift = layout().lateral_shift[k];
  return shift == 0 ? y : y + shift * in_.overlap.separation;
}

Eigen::Vector3d SectionGeometry::track_normal(int k) const {
  const Eigen::Vector2d n = line_.track.normal(k * line_.L);
  return {n.x(), n.y(), 0.0};
}

Eigen::Vector3d SectionGeometry::track_tangent(int k) const {
  const Eigen::Vector2d t = line_.track.tangent(k * line_.L);
  return {t.x(), t.y(), 0.0};
}

// Straight in plan between the two support points (offsets y from the track
// centre along its normal); on straight track exactly x = jL + s.
Eigen::Vector3d SectionGeometry::plan_point(int j, double s, double yl, double yr, double z) const {
  const double L = line_.L;
  if (line_.track.straight()) {
    const double y = yr == -yl ? yl * (1.0 - 2.0 * s / L) : yl + (yr - yl) * s / L;
    return {j * L + s, y, z};
  }
  const auto& t = line_.track;
  const Eigen::Vector2d a = t.point(j * L) + yl * t.normal(j * L);
  const Eigen::Vector2d b = t.point((j + 1) * L) + yr * t.normal((j + 1) * L);
  const Eigen::Vector2d p = a + (b - a) * (s / L);
  return {p.x(), p.y(), z};
}

Eigen::Vector2d SectionGeometry::plan_slope(int j, double yl, double yr) const {
  const double L = line_.L;
  if (line_.track.straight()) return {1.0, (yr - yl) / L};
  const auto& t = line_.track;
  const Eigen::Vector2d a = t.point(j * L) + yl * t.normal(j * L);
  const Eigen::Vector2d b = t.point((j + 1) * L) + yr * t.normal((j + 1) * L);
  return (b - a) / L;
}

// Contact-wire sag below the line joining the support heights, and its slope.
double SectionGeometry::presag(int j, double s, double* slope) const {
  const double L = line_.L, p = in_.presag;
  *slope = 0;
  if (anchor_span(j)) {
    const double f = contact_anchor_sag_;
    *slope = 4.0 * f * (L - 2.0 * s) / (L * L);
    return 4.0 * f * s * (L - s) / (L * L);
  }
  if (!service_span(j)) return 0.0;
  if (in_.presag_profile == PresagProfile::parabola) {
    *slope = 4.0 * p * (L - 2.0 * s) / (L * L);
    return 4.0 * p * s * (L - s) / (L * L);
  }
  const auto& pos = positions(j);
  if (in_.presag_profile == PresagProfile::droppers) {
    const double a = pos.front(), b = pos.back();
    if (s <= a || s >= b) return 0.0;
    *slope = 4.0 * p * (a + b - 2.0 * s) / ((b - a) * (b - a));
    return 4.0 * p * (s - a) * (b - s) / ((b - a) * (b - a));
  }
  // Explicit heights: linear between (0, 0), the droppers' sags and (L, 0).
  const auto& sag = sags(j);
  double s0 = 0, f0 = 0;
  for (std::size_t d = 0; d <= pos.size(); ++d) {
    const double s1 = d < pos.size() ? pos[d] : L, f1 = d < pos.size() ? sag[d] : 0.0;
    if (s <= s1) {
      *slope = (f1 - f0) / (s1 - s0);
      return f0 + (f1 - f0) * (s - s0) / (s1 - s0);
    }
    s0 = s1, f0 = f1;
  }
  return 0.0;
}

Eigen::Vector3d SectionGeometry::contact(int j, double s) const {
  const double zl = support_z(j), zr = support_z(j + 1), L = line_.L;
  double slope;
  double z = zl + (zr - zl) * s / L - presag(j, s, &slope);
  if (!profile_.empty()) z += profile_.dz(j * L + s);
  return plan_point(j, s, lateral(j, false), lateral(j + 1, false), z);
}

Eigen::Vector3d SectionGeometry::contact_tangent(int j, double s) const {
  const double zl = support_z(j), zr = support_z(j + 1);
  double slope;
  presag(j, s, &slope);
  const Eigen::Vector2d plan = plan_slope(j, lateral(j, false), lateral(j + 1, false));
  return unit(Eigen::Vector3d(plan.x(), plan.y(), (zr - zl) / line_.L - slope));
}

Eigen::Vector3d SectionGeometry::messenger(int j, double s, double sag) const {
  const double L = line_.L, f = anchor_span(j) ? messenger_anchor_sag_ : sag;
  const double zl = support_z(j) + in_.system_height, zr = support_z(j + 1) + in_.system_height;
  const double z = zl + (zr - zl) * s / L - 4.0 * f * s * (L - s) / (L * L);
  return plan_point(j, s, lateral(j, true), lateral(j + 1, true), z);
}

Eigen::Vector3d SectionGeometry::messenger_tangent(int j, double s) const {
  const double L = line_.L, f = anchor_span(j) ? messenger_anchor_sag_ : messenger_sag;
  const double zl = support_z(j), zr = support_z(j + 1);
  const Eigen::Vector2d plan = plan_slope(j, lateral(j, true), lateral(j + 1, true));
  return unit(
      Eigen::Vector3d(plan.x(), plan.y(), (zr - zl) / L - 4.0 * f * (L - 2.0 * s) / (L * L)));
}

}  // namespace pcsim::catenary::detail
