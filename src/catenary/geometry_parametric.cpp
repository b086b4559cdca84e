// ParametricDesign -> CatenaryMesh: a line of one or several tension
// sections (see docs/design-format.md, "What the generator builds"). The
// checks of every parameter are here; the layout, the sections, their
// supports and the irregularities in geometry_layout.cpp,
// geometry_section.cpp, geometry_supports.cpp and geometry_irregular.cpp.
#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <set>

#include "geometry_line.hpp"
#include "pcsim/core/format.hpp"

namespace pcsim::catenary {

namespace {

using detail::require_nonnegative;
using detail::require_positive;

std::string at(const std::string& list, std::size_t i) {
  return list + "[" + std::to_string(i) + "]";
}

void check_spans_and_heights(const ParametricDesign& in) {
  const std::string& f = in.file;
  const long count = in.span_count;
  if (count < 1)
    throw InputError(f, "spans.count", "must be at least 1 (got " + std::to_string(count) + ")");
  if (count > 100000)
    throw InputError(f, "spans.count", "is unreasonably large (got " + std::to_string(count) + ")");
  require_positive(f, "spans.length", in.span_length, limits::span_length);
  require_positive(f, "system_height", in.system_height, limits::height);
  require_positive(f, "contact_wire_height", in.contact_wire_height, limits::height);
  require_nonnegative(f, in.presag_key, in.presag, limits::height);
  if (!(in.system_height > in.presag))
    throw InputError(f, "system_height",
                     "must exceed the contact-wire presag (" + format_number(in.presag) +
                         " m), got " + format_number(in.system_height) + " m");
  require_nonnegative(f, "stagger", in.stagger, limits::height);
  require_nonnegative(f, "messenger_stagger", in.messenger_stagger, limits::height);
  require_positive(f, "element_length", in.element_length, limits::element_length);
  if (in.element_length > in.span_length)
    throw InputError(f, "element_length",
                     "must not exceed the span length " + format_number(in.span_length) +
                         " m (got " + format_number(in.element_length) + " m)");
}

void check_cable(const std::string& file, const std::string& key, const CableDesign& p) {
  require_positive(file, key + ".mass_per_length", p.mass_per_length, limits::mass_per_length);
  require_positive(file, key + ".EA", p.EA, limits::axial_stiffness);
  require_nonnegative(file, key + ".EI", p.EI, limits::bending_stiffness);
  require_positive(file, key + ".tension", p.tension, limits::tension);
}

// Dropper positions (and sags) of every span or of given spans.
void check_positions(const ParametricDesign& in, const std::string& key,
                     const std::vector<double>& positions, const std::vector<double>& sags) {
  const std::string& f = in.file;
  const double L = in.span_length;
  if (positions.empty()) throw InputError(f, key + ".positions", "must list at least one dropper");
  for (std::size_t i = 0; i < positions.size(); ++i) {
    const double s = positions[i];
    if (!(s > 0 && s < L))
      throw InputError(f, at(key + ".positions", i),
                       "dropper at " + format_number(s) + " m lies outside the span (0, " +
                           format_number(L) + ") m");
    if (i > 0 && !(s > positions[i - 1]))
      throw InputError(f, at(key + ".positions", i),
                       "dropper at " + format_number(s) + " m does not follow the previous one (" +
                           format_number(positions[i - 1]) +
                           " m): positions must be strictly increasing");
  }
  if (in.presag_profile == PresagProfile::droppers && positions.size() < 2)
    throw InputError(f, key + ".positions",
                     "presag profile 'droppers' needs at least two droppers in every span");
  if (in.presag_profile != PresagProfile::heights) {
    if (!sags.empty())
      throw InputError(f, key + ".sags", "sags are given only with the presag profile 'heights'");
    return;
  }
  if (sags.size() != positions.size())
    throw InputError(f, key + ".sags",
                     "presag profile 'heights' needs one sag per dropper (" +
                         std::to_string(positions.size()) + "), got " +
                         std::to_string(sags.size()));
  for (std::size_t i = 0; i < sags.size(); ++i)
    if (!std::isfinite(sags[i]) || std::abs(sags[i]) >= in.system_height)
      throw InputError(
          f, at(key + ".sags", i),
          "must be smaller than system_height in magnitude (got " + format_number(sags[i]) + ")");
}

// Exactly one of 'stiffness' [N/m], 'EA' [N] for every dropper and 'EA' [N]
// per dropper position (as many as the positions of every span).
void check_dropper_stiffness(const ParametricDesign& in) {
  const std::string& f = in.file;
  const DropperDesign& d = in.droppers;
  const bool per_position = !d.EA_per_position.empty();
  const int given = (d.stiffness != 0 ? 1 : 0) + (d.EA ? 1 : 0) + (per_position ? 1 : 0);
  if (given > 1)
    throw InputError(f, "droppers.EA",
                     "give the droppers' axial stiffness either as 'stiffness' [N/m] or as 'EA' "
                     "[N] (one value or one per position), not both");
  if (given == 0 || d.stiffness != 0) {
    require_positive(f, "droppers.stiffness", d.stiffness, limits::stiffness);
    return;
  }
  if (!per_position) {
    require_positive(f, "droppers.EA", *d.EA, limits::axial_stiffness);
    return;
  }
  const std::size_t n = d.EA_per_position.size();
  if (n != d.positions.size())
    throw InputError(f, "droppers.EA",
                     "needs one value per dropper position (" + std::to_string(d.positions.size()) +
                         " in droppers.positions), got " + std::to_string(n) +
                         "; or give one number for every dropper");
  for (std::size_t i = 0; i < d.spans.size(); ++i)
    if (d.spans[i].positions.size() != n)
      throw InputError(f, "droppers.EA",
                       "has one value per dropper position (" + std::to_string(n) + "), but " +
                           at("droppers.spans", i) + " has " +
                           std::to_string(d.spans[i].positions.size()) +
                           " droppers; give one number for every dropper");
  for (std::size_t i = 0; i < n; ++i)
    require_positive(f, at("droppers.EA", i), d.EA_per_position[i], limits::axial_stiffness);
}

void check_droppers(const ParametricDesign& in) {
  const std::string& f = in.file;
  const DropperDesign& d = in.droppers;
  check_positions(in, "droppers", d.positions, d.sags);
  std::set<long> seen;
  for (std::size_t i = 0; i < d.spans.size(); ++i) {
    const std::string key = at("droppers.spans", i);
    if (d.spans[i].spans.empty())
      throw InputError(f, key + ".spans", "must list at least one span");
    for (std::size_t j = 0; j < d.spans[i].spans.size(); ++j) {
      const long span = d.spans[i].spans[j];
      if (span < 1 || span > in.span_count)
        throw InputError(f, at(key + ".spans", j),
                         "span " + std::to_string(span) + " is not on the line (1.." +
                             std::to_string(in.span_count) + ")");
      if (!seen.insert(span).second)
        throw InputError(f, at(key + ".spans", j),
                         "span " + std::to_string(span) + " is listed twice");
    }
    check_positions(in, key, d.spans[i].positions, d.spans[i].sags);
  }
  check_dropper_stiffness(in);
  require_nonnegative(f, "droppers.mass_per_length", d.mass_per_length, limits::mass_per_length);
  require_nonnegative(f, "droppers.clamp_mass_messenger", d.clamp_mass_messenger, limits::mass);
  require_nonnegative(f, "droppers.clamp_mass_contact", d.clamp_mass_contact, limits::mass);
}

void check_stitch_wire(const std::string& file, const StitchWireDesign& st, double L) {
  require_positive(file, "stitch_wire.length", st.length);
  if (!(st.length < L))
    throw InputError(file, "stitch_wire.length",
                     "must be shorter than the span (" + format_number(L) +
                         " m) so that the stitch wires of neighbouring supports do not "
                         "overlap (got " +
                         format_number(st.length) + " m)");
  require_positive(file, "stitch_wire.tension", st.tension, limits::tension);
  require_positive(file, "stitch_wire.mass_per_length", st.mass_per_length,
                   limits::mass_per_length);
  require_positive(file, "stitch_wire.EA", st.EA, limits::axial_stiffness);
}

void check_sections(const ParametricDesign& in) {
  const std::string& f = in.file;
  long total = 0;
  for (std::size_t i = 0; i < in.sections.size(); ++i) {
    const SectionDesign& s = in.sections[i];
    if (s.spans < 1)
      throw InputError(f, at("sections", i) + ".spans",
                       "must be at least 1 (got " + std::to_string(s.spans) + ")");
    total += s.spans;
    if (!std::isfinite(s.radius) || (s.radius != 0 && std::abs(s.radius) < in.span_length))
      throw InputError(f, at("sections", i) + ".radius",
                       "must be 0 (straight) or at least the span length " +
                           format_number(in.span_length) + " m in magnitude (got " +
                           format_number(s.radius) + ")");
  }
  for (std::size_t i = 0; i < in.sections.size(); ++i)
    require_within(f, at("sections", i) + ".radius", in.sections[i].radius, limits::distance);
  if (!in.sections.empty() && total != in.span_count)
    throw InputError(f, "sections",
                     "the sections' spans add up to " + std::to_string(total) +
                         ", but spans.count is " + std::to_string(in.span_count));
  const OverlapDesign& o = in.overlap;
  if (o.spans < 1)
    throw InputError(f, "overlap.spans",
                     "must be at least 1 (got " + std::to_string(o.spans) + ")");
  require_positive(f, "overlap.raise", o.raise, limits::height);
  if (!(o.anchor_raise >= o.raise))
    throw InputError(f, "overlap.anchor_raise",
                     "must be at least overlap.raise (" + format_number(o.raise) + " m), got " +
                         format_number(o.anchor_raise));
  require_within(f, "overlap.anchor_raise", o.anchor_raise, limits::height);
  require_nonnegative(f, "overlap.separation", o.separation, limits::height);
}

void check_tensioning(const ParametricDesign& in) {
  const TensioningDesign& t = in.tensioning;
  if (t.device == TensioningDeviceKind::spring)
    require_positive(in.file, "tensioning.stiffness", t.stiffness, limits::stiffness);
  if (t.device != TensioningDeviceKind::weight) return;
  if (!(t.ratio >= 1))
    throw InputError(
        in.file, "tensioning.ratio",
        "must be at least 1 (wire tension / weight force), got " + format_number(t.ratio));
  require_within(in.file, "tensioning.ratio", t.ratio, Limit{100.0, ""});
  if (t.weight_mass)
    require_positive(in.file, "tensioning.weight_mass", *t.weight_mass, limits::mass);
  if (!t.weight_mass && !(in.gravity.norm() > 0))
    throw InputError(in.file, "tensioning.weight_mass",
                     "is required without gravity (the weight's mass cannot follow from it)");
}

void check_messenger_support(const std::string& f, const std::string& key,
                             const MessengerSupportDesign& s) {
  if (s.model == MessengerSupportModel::fixed) return;
  require_positive(f, key + ".stiffness", s.stiffness, limits::stiffness);
  if (s.model == MessengerSupportModel::spring_mass)
    require_positive(f, key + ".mass", s.mass, limits::mass);
}

void check_steady_arm(const std::string& f, const std::string& key, const SteadyArmDesign& a) {
  require_nonnegative(f, key + ".mass", a.mass, limits::mass);
  if (a.model == SteadyArmModel::hinged) {
    require_positive(f, key + ".length", a.length, limits::height);
    require_positive(f, key + ".axial_stiffness", a.axial_stiffness, limits::stiffness);
  }
  if (a.model == SteadyArmModel::spring)
    require_positive(f, key + ".stiffness", a.stiffness, limits::stiffness);
}

void check_supports(const ParametricDesign& in) {
  check_messenger_support(in.file, "messenger_supports", in.messenger_supports);
  check_steady_arm(in.file, "steady_arms", in.steady_arms);
  std::map<long, std::size_t> listed;  // support -> entry that lists it
  for (std::size_t i = 0; i < in.support_overrides.size(); ++i) {
    const auto& o = in.support_overrides[i];
    const std::string key = at("support_overrides", i);
    if (o.supports.empty()) throw InputError(in.file, key + ".supports", "must list a support");
    for (std::size_t j = 0; j < o.supports.size(); ++j) {
      const long k = o.supports[j];
      if (k < 0 || k > in.span_count)
        throw InputError(in.file, at(key + ".supports", j),
                         "support " + std::to_string(k) + " is not on the line (0.." +
                             std::to_string(in.span_count) + ")");
      const auto [it, first] = listed.emplace(k, i);
      if (!first)
        throw InputError(in.file, at(key + ".supports", j),
                         "support " + std::to_string(k) + " is listed twice (also in " +
                             at("support_overrides", it->second) +
                             "): give each support one entry");
    }
    if (o.messenger) check_messenger_support(in.file, key + ".messenger_supports", *o.messenger);
    if (o.steady_arm) check_steady_arm(in.file, key + ".steady_arms", *o.steady_arm);
  }
}

// Worn stretches: on the line (stations 0 .. N L), from < to, no two
// overlapping (touching ends are allowed).
void check_wear(const ParametricDesign& in) {
  const std::string& f = in.file;
  const auto& wear = in.irregularities.wear;
  const double length = in.span_count * in.span_length;
  for (std::size_t i = 0; i < wear.size(); ++i) {
    const std::string key = at("irregularities.wear", i);
    const WearStretch& w = wear[i];
    if (!(w.from >= 0 && w.from < length))
      throw InputError(f, key + ".from",
                       "must lie on the line, in [0, " + format_number(length) + ") m (got " +
                           format_number(w.from) + ")");
    if (!(w.to > w.from))
      throw InputError(
          f, key + ".to",
          "must exceed 'from' (" + format_number(w.from) + " m), got " + format_number(w.to));
    if (!(w.to <= length))
      throw InputError(f, key + ".to",
                       "must lie on the line, at most its length " + format_number(length) +
                           " m (got " + format_number(w.to) + ")");
    if (!(w.section_loss >= 0 && w.section_loss < 1))
      throw InputError(f, key + ".section_loss",
                       "must lie in [0, 1) (got " + format_number(w.section_loss) + ")");
    for (std::size_t j = 0; j < i; ++j)
      if (w.from < wear[j].to && wear[j].from < w.to)
        throw InputError(f, key,
                         "the stretch " + format_number(w.from) + ".." + format_number(w.to) +
                             " m overlaps irregularities.wear[" + std::to_string(j) + "] (" +
                             format_number(wear[j].from) + ".." + format_number(wear[j].to) +
                             " m): give each part of the wire one section_loss");
  }
}

void check_irregularities(const ParametricDesign& in) {
  const std::string& f = in.file;
  const IrregularityDesign& ir = in.irregularities;
  const auto& x = ir.profile_x;
  if (x.size() != ir.profile_dz.size() || x.size() == 1)
    throw InputError(f, ir.profile_key, "needs at least two (x, dz) points");
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (i > 0 && !(x[i] > x[i - 1]))
      throw InputError(f, ir.profile_key,
                       "x must increase strictly (point " + std::to_string(i + 1) + ": " +
                           format_number(x[i]) + " m after " + format_number(x[i - 1]) + " m)");
    if (!std::isfinite(ir.profile_dz[i]) || std::abs(ir.profile_dz[i]) >= 0.5 * in.system_height)
      throw InputError(f, ir.profile_key,
                       "dz must be smaller than half the system height (point " +
                           std::to_string(i + 1) + ": " + format_number(ir.profile_dz[i]) + " m)");
  }
  if (ir.random) {
    const RandomIrregularity& r = *ir.random;
    require_nonnegative(f, "irregularities.random.rms", r.rms);
    if (!(r.rms < 0.1 * in.system_height))
      throw InputError(
          f, "irregularities.random.rms",
          "must be below a tenth of the system height (got " + format_number(r.rms) + " m)");
    require_positive(f, "irregularities.random.wavelength_min", r.wavelength_min, limits::distance);
    if (!(r.wavelength_max > r.wavelength_min))
      throw InputError(f, "irregularities.random.wavelength_max",
                       "must exceed wavelength_min (" + format_number(r.wavelength_min) +
                           " m), got " + format_number(r.wavelength_max));
    require_within(f, "irregularities.random.wavelength_max", r.wavelength_max, limits::distance);
    if (in.span_count * in.span_length / r.wavelength_min > 1e6)
      throw InputError(f, "irregularities.random.wavelength_min",
                       "too short for the line: more than a million components");
    require_within(f, "irregularities.random.exponent", r.exponent, Limit{100.0, ""});
    if (r.seed < 0) throw InputError(f, "irregularities.random.seed", "must not be negative");
  }
  check_wear(in);
}

}  // namespace

void detail::check_parametric(const ParametricDesign& in) {
  check_spans_and_heights(in);
  check_cable(in.file, "wires.contact", in.contact);
  check_cable(in.file, "wires.messenger", in.messenger);
  check_droppers(in);
  if (in.stitch_wire) check_stitch_wire(in.file, *in.stitch_wire, in.span_length);
  check_sections(in);
  check_tensioning(in);
  check_supports(in);
  check_irregularities(in);
}

namespace {

// Supports, sections' and overlaps' zones, from the layout.
void add_track_description(CatenaryMesh& mesh, const detail::LineLayout& line,
                           const std::vector<std::unique_ptr<detail::SectionBuilder>>& sections) {
  const int N = line.spans, m = line.overlap_spans;
  for (int k = 0; k <= N; ++k) {
    std::size_t owner = 0;
    while (owner + 1 < sections.size() && k > line.sections[owner].own_last) ++owner;
    mesh.support_x.push_back(k * line.L);
    mesh.support_nodes.push_back(sections[owner]->contact_node_at(k));
  }
  const auto& q = line.overlap_first;
  for (std::size_t i = 0; i < sections.size(); ++i) {
    // The line's end spans (fixed wire ends, the pantograph's start) are left out.
    const int from = i > 0 ? q[i - 1] + m : std::min(1, N - 1);
    const int to = i + 1 < sections.size() ? q[i] : std::max(N - 1, from + 1);
    mesh.zones.push_back({"section " + std::to_string(i + 1), false, from * line.L, to * line.L});
    if (i + 1 < sections.size())
      mesh.zones.push_back({"overlap " + std::to_string(i + 1) + "-" + std::to_string(i + 2), true,
                            q[i] * line.L, (q[i] + m) * line.L});
  }
}

// An override must act on some wire: the messenger model at a support
// inner to a section, a steady-arm model other than 'constraint' where a
// steady arm holds a wire in service (at the line's first and last supports
// only the arm's mass is used).
void check_overrides_have_effect(const ParametricDesign& in, const detail::LineLayout& line) {
  for (std::size_t i = 0; i < in.support_overrides.size(); ++i) {
    const auto& o = in.support_overrides[i];
    for (std::size_t j = 0; j < o.supports.size(); ++j) {
      const int k = static_cast<int>(o.supports[j]);
      bool inner = false, arm = false;
      for (const auto& sec : line.sections) {
        if (sec.role[k] == detail::Role::none || k == sec.first || k == sec.last) continue;
        inner = true;
        arm = arm || sec.role[k] == detail::Role::service;
      }
      const std::string key = at(at("support_overrides", i) + ".supports", j);
      const std::string where = "support " + std::to_string(k) + " is a wire end";
      if (o.messenger && !inner)
        throw InputError(in.file, key,
                         where +
                             ": the messenger is anchored there whatever its model, so "
                             "messenger_supports would have no effect");
      if (o.steady_arm && !arm && o.steady_arm->model != SteadyArmModel::constraint)
        throw InputError(in.file, key,
                         where +
                             ": it has no steady arm, only the steady_arms 'mass' is used "
                             "there (a point mass); give model 'constraint'");
    }
  }
}

}  // namespace

std::string spans_differ(const ParametricDesign& design) {
  if (!design.sections.empty()) return "sections (tension sections, overlaps, curves)";
  if (!design.support_overrides.empty()) return "support overrides";
  if (!design.irregularities.empty()) return "irregularities";
  if (!design.droppers.spans.empty()) return "spans with droppers of their own (droppers.spans)";
  return "";
}

CatenaryMesh build_parametric(const ParametricDesign& design) {
  detail::check_parametric(design);
  const detail::LineLayout line = detail::make_line_layout(design);
  check_overrides_have_effect(design, line);
  CatenaryMesh mesh;
  detail::set_common(mesh, design.file, design.name, design.gravity, design.damping);
  mesh.form_finding_default = true;
  mesh.identical_spans = spans_differ(design).empty();
  mesh.track = line.track;
  const detail::IrregularProfile profile(design.irregularities, line.spans * line.L);
  std::vector<std::unique_ptr<detail::SectionBuilder>> sections;
  std::vector<std::vector<double>> held;
  for (std::size_t i = 0; i < line.sections.size(); ++i) {
    sections.push_back(
        std::make_unique<detail::SectionBuilder>(design, line, static_cast<int>(i), profile, mesh));
    sections.back()->build();
    mesh.contact_wires.push_back(sections.back()->contact_wire());
    held.push_back(sections.back()->held_stations());
  }
  mesh.contact_wire = mesh.contact_wires.front();
  add_track_description(mesh, line, sections);
  detail::add_contact_gap_offsets(mesh, profile, held);
  detail::apply_wear(mesh, design.irregularities);
  detail::require_consistent(mesh, design.file);
  return mesh;
}

}  // namespace pcsim::catenary
