// Catenary design files -> ParametricDesign / ExplicitDesign -> CatenaryMesh
// (see docs/design-format.md). Syntax is checked here, ranges and geometry
// by the builders of pcsim/catenary/geometry.hpp.
#include "pcsim/scene/design_reader.hpp"

#include "design_reader_internal.hpp"
#include "pcsim/scene/composition.hpp"

namespace pcsim::scene {

using namespace pcsim::catenary;

namespace reader {

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
    for (double c : v)
      if (!limit_violation(c, limits::gravity).empty()) g.fail(limit_violation(c, limits::gravity));
    return {v[0], v[1], v[2]};
  }
  return {0.0, 0.0, -root.get_nonnegative("gravity", limits::gravity)};
}

RayleighDamping read_damping(const InputNode& root) {
  RayleighDamping damping;
  if (!root.has("damping")) return damping;
  InputNode d = root["damping"];
  d.allow_only({"rayleigh_alpha", "rayleigh_beta"});
  damping.alpha = d.get_double("rayleigh_alpha", 0.0);
  damping.beta = d.get_double("rayleigh_beta", 0.0);
  return damping;
}

SlackCriterion read_slack(const InputNode& n, const char* fallback) {
  const std::string s = n.get_choice("slack", {"none", "length", "force"}, fallback);
  if (s == "length") return SlackCriterion::length;
  if (s == "force") return SlackCriterion::force;
  return SlackCriterion::none;
}

}  // namespace reader

namespace {

CableDesign read_cable(const InputNode& n) {
  n.allow_only({"mass_per_length", "EA", "EI", "tension", "thermal_expansion", "diameter",
                "drag_coefficient"});
  CableDesign p;
  p.mass_per_length = n.get_double("mass_per_length");
  p.thermal_expansion =
      n.get_nonnegative("thermal_expansion", limits::thermal_expansion, p.thermal_expansion);
  if (n.has("diameter")) p.diameter = n.get_positive("diameter", limits::wire_diameter);
  if (n.has("drag_coefficient"))
    p.drag_coefficient = n.get_positive("drag_coefficient", limits::drag_coefficient);
  p.EA = n.get_double("EA");
  p.EI = n.get_double("EI");
  p.tension = n.get_double("tension");
  return p;
}

DropperDesign read_droppers(const InputNode& drop) {
  drop.allow_only({"positions", "sags", "spans", "stiffness", "EA", "mass_per_length", "slack",
                   "clamp_mass_messenger", "clamp_mass_contact", "diameter", "drag_coefficient"});
  DropperDesign d;
  InputNode pos = drop["positions"];
  if (!pos.is_sequence()) pos.fail("must be a list of distances from the span's first support [m]");
  for (std::size_t i = 0; i < pos.size(); ++i) d.positions.push_back(pos.at(i).as_double());
  if (drop.has("sags")) {
    InputNode sags = drop["sags"];
    if (!sags.is_sequence()) sags.fail("must be a list of contact-wire sags at the droppers [m]");
    for (std::size_t i = 0; i < sags.size(); ++i) d.sags.push_back(sags.at(i).as_double());
  }
  if (drop.has("spans")) d.spans = reader::read_span_droppers(drop["spans"]);
  // Axial stiffness: 'stiffness' [N/m] or 'EA' [N] (one number or one per
  // position); the builder checks the values and the list's length.
  const bool has_stiffness = drop.has("stiffness"), has_EA = drop.has("EA");
  if (has_stiffness && has_EA)
    drop.fail_key("EA",
                  "give the droppers' axial stiffness either as 'stiffness' [N/m] or as "
                  "'EA' [N], not both");
  if (!has_stiffness && !has_EA)
    drop.fail_key("stiffness",
                  "required key is missing: give the droppers' axial stiffness as "
                  "'stiffness' [N/m] or as 'EA' [N]");
  if (has_stiffness) d.stiffness = drop.get_double("stiffness");
  if (has_EA) {
    InputNode ea = drop["EA"];
    if (ea.is_sequence()) {
      if (ea.size() == 0) ea.fail("must be a number or a list of one EA per dropper position [N]");
      for (std::size_t i = 0; i < ea.size(); ++i) d.EA_per_position.push_back(ea.at(i).as_double());
    } else {
      d.EA = ea.as_double();
    }
  }
  d.mass_per_length = drop.get_double("mass_per_length", 0.0);
  d.slack = reader::read_slack(drop, "length");
  d.clamp_mass_messenger = drop.get_double("clamp_mass_messenger", 0.0);
  d.clamp_mass_contact = drop.get_double("clamp_mass_contact", 0.0);
  if (drop.has("diameter")) d.diameter = drop.get_positive("diameter", limits::wire_diameter);
  if (drop.has("drag_coefficient"))
    d.drag_coefficient = drop.get_positive("drag_coefficient", limits::drag_coefficient);
  return d;
}

StitchWireDesign read_stitch_wire(const InputNode& st) {
  st.allow_only({"length", "tension", "mass_per_length", "EA"});
  StitchWireDesign s;
  s.length = st.get_double("length");
  s.tension = st.get_double("tension");
  s.mass_per_length = st.get_double("mass_per_length");
  s.EA = st.get_double("EA");
  return s;
}

}  // namespace

ParametricDesign read_parametric_design(const InputNode& root) {
  root.allow_only({"type",
                   "name",
                   "spans",
                   "system_height",
                   "contact_wire_height",
                   "presag",
                   "stagger",
                   "messenger_stagger",
                   "element_length",
                   "wires",
                   "droppers",
                   "steady_arms",
                   "messenger_supports",
                   "support_overrides",
                   "stitch_wire",
                   "sections",
                   "overlap",
                   "tensioning",
                   "irregularities",
                   "damping",
                   "gravity"});
  ParametricDesign d;
  d.file = root.file();
  d.name = root.get_string("name", reader::file_stem(root.file()));
  InputNode spans = root["spans"];
  spans.allow_only({"count", "length"});
  d.span_count = spans.get_int("count");
  d.span_length = spans.get_double("length");
  d.system_height = root.get_double("system_height");
  d.contact_wire_height = root.get_double("contact_wire_height");
  reader::read_presag(root, d);
  d.stagger = root.get_double("stagger", 0.0);
  d.messenger_stagger = root.get_double("messenger_stagger", 0.0);
  d.element_length = root.get_double("element_length", 0.5);
  InputNode wires = root["wires"];
  wires.allow_only({"contact", "messenger"});
  d.contact = read_cable(wires["contact"]);
  d.messenger = read_cable(wires["messenger"]);
  d.droppers = read_droppers(root["droppers"]);
  reader::read_supports(root, d);
  if (root.has("stitch_wire")) d.stitch_wire = read_stitch_wire(root["stitch_wire"]);
  reader::read_line(root, d);
  reader::read_irregularities(root, d);
  d.gravity = reader::read_gravity(root);
  d.damping = reader::read_damping(root);
  return d;
}

CatenaryMesh build_catenary_design(const InputNode& root, const MeshSizeCheck& check) {
  if (!root.is_map()) root.fail("a design must be a map of keys");
  const std::string type = root.get_choice("type", {"parametric", "explicit"}, "");
  if (type.empty()) root.fail_key("type", "required key is missing (parametric or explicit)");
  if (type == "parametric") {
    const ParametricDesign design = read_parametric_design(root);
    if (check) check(mesh_size(design));
    return build_parametric(design);
  }
  const ExplicitDesign design = read_explicit_design(root);
  if (check) check(mesh_size(design));
  return build_explicit(design);
}

CatenaryMesh load_catenary_design(const std::string& path, const MeshSizeCheck& check) {
  CatenaryMesh mesh = build_catenary_design(load_composed(path), check);
  mesh.source_file = path;
  return mesh;
}

}  // namespace pcsim::scene
