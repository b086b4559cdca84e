// Design files of type explicit -> ExplicitDesign (docs/design-format.md,
// "type: explicit"). Node references are resolved by build_explicit.
#include <vector>

#include "design_reader_internal.hpp"

namespace pcsim::scene {

using namespace pcsim::catenary;

namespace {

// A node given as an index, or as {wire: name, node: k}.
NodeRef read_node_ref(const InputNode& n) {
  if (n.is_map()) {
    n.allow_only({"wire", "node"});
    const std::string wire = n.get_string("wire");
    return NodeRef::on_wire(wire, n.get_int("node"));
  }
  return NodeRef::at(n.as_int());
}

int read_dof(const InputNode& n) {
  const std::string s = n.as_string();
  static const char* names[] = {"x", "y", "z", "dx", "dy", "dz"};
  for (int d = 0; d < kNodeDofs; ++d)
    if (s == names[d]) return d;
  n.fail("unknown degree of freedom '" + s + "' (use x, y, z for position, dx, dy, dz for slope)");
}

// Entries of the list 'key' of root (none when absent).
std::vector<InputNode> list(const InputNode& root, const char* key) {
  std::vector<InputNode> out;
  if (!root.has(key)) return out;
  InputNode l = root[key];
  if (!l.is_sequence()) l.fail("must be a list");
  for (std::size_t i = 0; i < l.size(); ++i) out.push_back(l.at(i));
  return out;
}

// Unstressed length: 'taut' (empty) or a ratio L0/L.
std::optional<double> read_unstressed(const InputNode& wn) {
  if (!wn.has("unstressed")) return std::nullopt;
  InputNode u = wn["unstressed"];
  if (!u.is_scalar()) u.fail("must be 'taut' or a positive ratio L0/L");
  if (u.as_string() == "taut") return std::nullopt;
  try {
    return u.as_double();
  } catch (const InputError&) {
    u.fail("must be 'taut' or a positive ratio L0/L, got '" + u.as_string() + "'");
  }
}

ExplicitWire read_wire(const InputNode& wn, std::size_t index) {
  wn.allow_only({"name", "kind", "nodes", "mass_per_length", "EA", "EI", "tension", "unstressed",
                 "thermal_expansion", "diameter", "drag_coefficient"});
  ExplicitWire w;
  w.name = wn.get_string("name", "wire" + std::to_string(index));
  const std::string kind =
      wn.get_choice("kind", {"messenger", "contact", "stitch", "other"}, "other");
  w.kind = kind == "messenger" ? WireKind::messenger
           : kind == "contact" ? WireKind::contact
           : kind == "stitch"  ? WireKind::stitch
                               : WireKind::other;
  w.mass_per_length = wn.get_double("mass_per_length");
  w.thermal_expansion =
      wn.get_nonnegative("thermal_expansion", limits::thermal_expansion, w.thermal_expansion);
  if (wn.has("diameter")) w.diameter = wn.get_positive("diameter", limits::wire_diameter);
  if (wn.has("drag_coefficient"))
    w.drag_coefficient = wn.get_positive("drag_coefficient", limits::drag_coefficient);
  w.EA = wn.get_double("EA");
  w.EI = wn.get_double("EI");
  w.tension = wn.get_double("tension", 0.0);
  InputNode nodes = wn["nodes"];
  if (nodes.is_map()) {
    nodes.allow_only({"from", "to", "elements"});
    w.run = WireRun{read_node_ref(nodes["from"]), read_node_ref(nodes["to"]), 0};
    w.run->elements = nodes.get_int("elements");
  } else if (nodes.is_sequence()) {
    for (std::size_t i = 0; i < nodes.size(); ++i) w.nodes.push_back(read_node_ref(nodes.at(i)));
  } else {
    nodes.fail("must be a list of nodes or a map {from, to, elements}");
  }
  w.unstressed_ratio = read_unstressed(wn);
  return w;
}

ExplicitBar read_bar(const InputNode& bn) {
  bn.allow_only({"nodes", "kind", "stiffness", "mass", "unstressed_length", "slack", "form_find",
                 "span", "index_in_span", "diameter", "drag_coefficient"});
  InputNode nodes = bn["nodes"];
  if (!nodes.is_sequence() || nodes.size() != 2) nodes.fail("must be a list of 2 nodes [a, b]");
  ExplicitBar b;
  b.nodes = {read_node_ref(nodes.at(0)), read_node_ref(nodes.at(1))};
  const std::string kind =
      bn.get_choice("kind", {"dropper", "steady_arm", "stitch", "other"}, "other");
  b.kind = kind == "dropper"      ? BarKind::dropper
           : kind == "steady_arm" ? BarKind::steady_arm
           : kind == "stitch"     ? BarKind::stitch
                                  : BarKind::other;
  b.stiffness = bn.get_double("stiffness");
  b.mass = bn.get_double("mass", 0.0);
  if (bn.has("unstressed_length")) b.unstressed_length = bn.get_double("unstressed_length");
  b.slack = reader::read_slack(bn, "none");
  b.form_find = bn.get_bool("form_find", false);
  b.span = bn.get_int("span", -1);
  b.index_in_span = bn.get_int("index_in_span", -1);
  if (bn.has("diameter")) b.diameter = bn.get_positive("diameter", limits::wire_diameter);
  if (bn.has("drag_coefficient"))
    b.drag_coefficient = bn.get_positive("drag_coefficient", limits::drag_coefficient);
  return b;
}

ExplicitSupport read_support(const InputNode& sn) {
  sn.allow_only({"node", "fix"});
  ExplicitSupport s;
  s.node = read_node_ref(sn["node"]);
  if (!sn.has("fix")) return s;  // x, y, z
  InputNode fix = sn["fix"];
  if (!fix.is_sequence() || fix.size() == 0)
    fix.fail("must be a non-empty list of x, y, z, dx, dy, dz");
  s.dofs.clear();
  for (std::size_t i = 0; i < fix.size(); ++i) s.dofs.push_back(read_dof(fix.at(i)));
  return s;
}

// Point masses, springs, targets, tension segments and support nodes.
void read_attachments(const InputNode& root, ExplicitDesign& d) {
  for (const auto& pn : list(root, "point_masses")) {
    pn.allow_only({"node", "mass", "label"});
    d.point_masses.push_back(
        {read_node_ref(pn["node"]), pn.get_double("mass"), pn.get_string("label", "point_mass")});
  }
  for (const auto& sn : list(root, "springs")) {
    sn.allow_only({"node", "dof", "stiffness"});
    d.springs.push_back(
        {read_node_ref(sn["node"]), read_dof(sn["dof"]), sn.get_double("stiffness")});
  }
  for (const auto& tn : list(root, "targets")) {
    tn.allow_only({"node", "z", "bar"});
    ExplicitTarget t;
    t.node = read_node_ref(tn["node"]);
    if (tn.has("z")) t.z = tn.get_double("z");
    t.bar = tn.get_int("bar");
    d.targets.push_back(t);
  }
  for (const auto& sn : list(root, "tension_segments")) {
    sn.allow_only({"wire", "tension"});
    ExplicitTensionSegment s;
    s.wire = sn.get_string("wire");
    if (sn.has("tension")) s.tension = sn.get_double("tension");
    d.tension_segments.push_back(s);
  }
  if (root.has("support_nodes")) {
    InputNode sn = root["support_nodes"];
    if (!sn.is_sequence()) sn.fail("must be a list of nodes");
    for (std::size_t i = 0; i < sn.size(); ++i) d.support_nodes.push_back(read_node_ref(sn.at(i)));
  }
}

}  // namespace

ExplicitDesign read_explicit_design(const InputNode& root) {
  root.allow_only({"type", "name", "gravity", "nodes", "wires", "bars", "supports", "point_masses",
                   "springs", "targets", "tension_segments", "form_finding", "damping",
                   "support_nodes"});
  ExplicitDesign d;
  d.file = root.file();
  d.name = root.get_string("name", reader::file_stem(root.file()));
  d.gravity = reader::read_gravity(root);
  d.damping = reader::read_damping(root);
  d.form_finding = root.get_bool("form_finding", false);
  if (root.has("nodes")) {
    InputNode nodes = root["nodes"];
    if (!nodes.is_sequence()) nodes.fail("must be a list of [x, y, z] positions");
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      const auto p = nodes.at(i).as_vec3();
      for (double c : p)
        if (!limit_violation(c, limits::distance).empty())
          nodes.at(i).fail(limit_violation(c, limits::distance));
      d.nodes.emplace_back(p[0], p[1], p[2]);
    }
  }
  const auto wires = list(root, "wires");
  for (std::size_t i = 0; i < wires.size(); ++i) d.wires.push_back(read_wire(wires[i], i));
  for (const auto& bn : list(root, "bars")) d.bars.push_back(read_bar(bn));
  for (const auto& sn : list(root, "supports")) d.supports.push_back(read_support(sn));
  read_attachments(root, d);
  return d;
}

}  // namespace pcsim::scene
