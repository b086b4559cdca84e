// ExplicitDesign -> CatenaryMesh: arbitrary nodes, cable wires, bars,
// supports, masses, springs and form-finding targets (see
// docs/design-format.md, "type: explicit").
#include <set>

#include "geometry_internal.hpp"
#include "pcsim/core/format.hpp"

namespace pcsim::catenary {

namespace {

using detail::require_nonnegative;
using detail::require_positive;

std::string indexed(const std::string& list, std::size_t i) {
  return list + "[" + std::to_string(i) + "]";
}

class ExplicitBuilder {
 public:
  explicit ExplicitBuilder(const ExplicitDesign& in) : in_(in) {}

  CatenaryMesh build() {
    detail::set_common(mesh_, in_.file, in_.name, in_.gravity, in_.damping);
    mesh_.form_finding_default = in_.form_finding;
    for (const auto& p : in_.nodes) {
      Node n;
      n.position = p;
      mesh_.nodes.push_back(n);
    }
    wire_of_node_.assign(mesh_.nodes.size(), -1);
    for (std::size_t i = 0; i < in_.wires.size(); ++i) add_wire(i);
    set_contact_wire();
    for (std::size_t i = 0; i < in_.bars.size(); ++i) add_bar(i);
    add_supports_masses_and_springs();
    add_targets();
    add_tension_segments();
    for (std::size_t i = 0; i < in_.support_nodes.size(); ++i) {
      const int node = resolve(in_.support_nodes[i], indexed("support_nodes", i));
      mesh_.support_nodes.push_back(node);
      mesh_.support_x.push_back(mesh_.nodes[node].position.x());
    }
    return std::move(mesh_);
  }

 private:
  [[noreturn]] void fail(const std::string& key, const std::string& reason) const {
    throw InputError(in_.file, key, reason);
  }

  // Node index of a reference given at 'key'.
  int resolve(const NodeRef& ref, const std::string& key) const {
    if (ref.wire) {
      const std::string& name = *ref.wire;
      const int w = mesh_.find_wire(name);
      if (w < 0) {
        std::string known;
        for (const auto& wire : mesh_.wires) known += (known.empty() ? "" : ", ") + wire.name;
        fail(key + ".wire", "no wire named '" + name + "' is defined before this point (known: " +
                                (known.empty() ? std::string("none") : known) + ")");
      }
      const long count = static_cast<long>(mesh_.wires[w].nodes.size());
      long k = ref.node;
      if (k < 0) k += count;
      if (k < 0 || k >= count)
        fail(key + ".node", "wire '" + name + "' has nodes 0.." + std::to_string(count - 1) +
                                " (got " + std::to_string(ref.node) + ")");
      return mesh_.wires[w].nodes[k];
    }
    const long count = static_cast<long>(mesh_.nodes.size());
    if (ref.index < 0 || ref.index >= count)
      fail(key, "node index " + std::to_string(ref.index) + " is out of range (the design has " +
                    std::to_string(count) + " nodes, 0.." + std::to_string(count - 1) + ")");
    return static_cast<int>(ref.index);
  }

  // Node list of wire i: its listed nodes, or its run cut into new nodes.
  std::vector<int> wire_nodes(std::size_t i) {
    const ExplicitWire& in = in_.wires[i];
    const std::string key = indexed("wires", i) + ".nodes";
    std::vector<int> nodes;
    if (!in.run) {
      if (in.nodes.size() < 2) fail(key, "a wire needs at least 2 nodes");
      for (std::size_t k = 0; k < in.nodes.size(); ++k)
        nodes.push_back(resolve(in.nodes[k], indexed(key, k)));
      return nodes;
    }
    const int a = resolve(in.run->from, key + ".from");
    const int b = resolve(in.run->to, key + ".to");
    const long n = in.run->elements;
    if (n < 1 || n > 10000000)
      fail(key + ".elements",
           "must be a positive number of elements (got " + std::to_string(n) + ")");
    if (a == b) fail(key, "'from' and 'to' are the same node " + std::to_string(a));
    const Eigen::Vector3d pa = mesh_.nodes[a].position, pb = mesh_.nodes[b].position;
    nodes.push_back(a);
    for (long k = 1; k < n; ++k) {
      Node node;
      node.position = pa + (pb - pa) * (static_cast<double>(k) / n);
      nodes.push_back(static_cast<int>(mesh_.nodes.size()));
      mesh_.nodes.push_back(node);
      wire_of_node_.push_back(-1);
    }
    nodes.push_back(b);
    return nodes;
  }

  // Cable wires may neither share nor revisit nodes.
  void claim_wire_nodes(std::size_t i, const std::vector<int>& nodes) {
    const int wire_index = static_cast<int>(mesh_.wires.size());
    for (const int id : nodes) {
      if (wire_of_node_[id] >= 0) {
        const std::string other = wire_of_node_[id] == wire_index
                                      ? std::string("this wire")
                                      : "wire '" + mesh_.wires[wire_of_node_[id]].name + "'";
        fail(indexed("wires", i) + ".nodes",
             "node " + std::to_string(id) + " already belongs to " + other +
                 "; cable wires cannot share or revisit nodes (join wires with a bar)");
      }
      wire_of_node_[id] = wire_index;
    }
  }

  void add_wire(std::size_t i) {
    const ExplicitWire& in = in_.wires[i];
    const std::string key = indexed("wires", i);
    Wire w;
    w.name = in.name;
    if (mesh_.find_wire(w.name) >= 0) fail(key + ".name", "wire '" + w.name + "' is defined twice");
    w.kind = in.kind;
    require_positive(in_.file, key + ".mass_per_length", in.mass_per_length,
                     limits::mass_per_length);
    require_positive(in_.file, key + ".EA", in.EA, limits::axial_stiffness);
    require_nonnegative(in_.file, key + ".EI", in.EI, limits::bending_stiffness);
    require_nonnegative(in_.file, key + ".tension", in.tension, limits::tension);
    w.mass_per_length = in.mass_per_length;
    w.thermal_expansion = in.thermal_expansion;
    w.diameter = in.diameter;
    w.drag_coefficient = in.drag_coefficient;
    w.EA = in.EA;
    w.EI = in.EI;
    w.tension = in.tension;
    w.nodes = wire_nodes(i);
    claim_wire_nodes(i, w.nodes);

    // Unstressed length: a ratio of the design length, or taut (the cable
    // carries 'tension' in its straight design configuration).
    double ratio = 1.0 / detail::taut_stretch(w.tension, w.EA);
    if (in.unstressed_ratio) {
      const double r = *in.unstressed_ratio;
      if (!(r > 0))
        fail(key + ".unstressed",
             "must be 'taut' or a positive ratio L0/L (got " + format_number(r) + ")");
      ratio = r;
    }
    const int wire_index = static_cast<int>(mesh_.wires.size());
    for (std::size_t k = 0; k + 1 < w.nodes.size(); ++k) {
      CableElement e;
      e.nodes = {w.nodes[k], w.nodes[k + 1]};
      e.wire = wire_index;
      e.ref_length = (mesh_.nodes[e.nodes[1]].position - mesh_.nodes[e.nodes[0]].position).norm();
      if (!(e.ref_length > 0))
        fail(key + ".nodes", "element " + std::to_string(k) + " joins nodes " +
                                 std::to_string(e.nodes[0]) + " and " + std::to_string(e.nodes[1]) +
                                 " at the same position: an element needs a positive length");
      e.unstressed_length = ratio * e.ref_length;
      w.elements.push_back(static_cast<int>(mesh_.cables.size()));
      mesh_.cables.push_back(e);
    }
    mesh_.wires.push_back(w);
    detail::set_polyline_slopes(mesh_, mesh_.wires.back().nodes);
  }

  void set_contact_wire() {
    for (std::size_t w = 0; w < mesh_.wires.size(); ++w) {
      if (mesh_.wires[w].kind != WireKind::contact) continue;
      if (mesh_.contact_wire >= 0)
        fail("wires", "at most one wire may be of kind 'contact' ('" +
                          mesh_.wires[mesh_.contact_wire].name + "' and '" + mesh_.wires[w].name +
                          "')");
      mesh_.contact_wire = static_cast<int>(w);
    }
  }

  void add_bar(std::size_t i) {
    const ExplicitBar& in = in_.bars[i];
    const std::string key = indexed("bars", i);
    BarElement b;
    b.nodes = {resolve(in.nodes[0], key + ".nodes[0]"), resolve(in.nodes[1], key + ".nodes[1]")};
    if (b.nodes[0] == b.nodes[1])
      fail(key + ".nodes",
           "the bar joins node " + std::to_string(b.nodes[0]) + " to itself: impossible geometry");
    const double l = (mesh_.nodes[b.nodes[1]].position - mesh_.nodes[b.nodes[0]].position).norm();
    if (!(l > 0))
      fail(key + ".nodes", "nodes " + std::to_string(b.nodes[0]) + " and " +
                               std::to_string(b.nodes[1]) +
                               " are at the same position: a bar needs a positive design length");
    b.kind = in.kind;
    require_positive(in_.file, key + ".stiffness", in.stiffness, limits::stiffness);
    require_nonnegative(in_.file, key + ".mass", in.mass, limits::mass);
    if (in.unstressed_length)
      require_positive(in_.file, key + ".unstressed_length", *in.unstressed_length,
                       limits::distance);
    b.stiffness = in.stiffness;
    b.mass = in.mass;
    b.unstressed_length = in.unstressed_length.value_or(l);
    b.slack = in.slack;
    b.form_find_length = in.form_find;
    if (in.span < -1) fail(key + ".span", "must not be negative");
    if (in.index_in_span < -1) fail(key + ".index_in_span", "must not be negative");
    b.span = static_cast<int>(in.span);
    b.index_in_span = static_cast<int>(in.index_in_span);
    b.diameter = in.diameter;
    b.drag_coefficient = in.drag_coefficient;
    mesh_.bars.push_back(b);
  }

  void add_supports_masses_and_springs() {
    for (std::size_t i = 0; i < in_.supports.size(); ++i) {
      const ExplicitSupport& s = in_.supports[i];
      const std::string key = indexed("supports", i);
      const int node = resolve(s.node, key + ".node");
      if (s.dofs.empty()) fail(key + ".fix", "must be a non-empty list of x, y, z, dx, dy, dz");
      for (std::size_t k = 0; k < s.dofs.size(); ++k) {
        if (s.dofs[k] < 0 || s.dofs[k] >= kNodeDofs)
          fail(indexed(key + ".fix", k), "DOF index " + std::to_string(s.dofs[k]) +
                                             " is out of range (0..5: x, y, z, dx, dy, dz)");
        mesh_.nodes[node].fixed[s.dofs[k]] = true;
      }
    }
    for (std::size_t i = 0; i < in_.point_masses.size(); ++i) {
      const ExplicitPointMass& p = in_.point_masses[i];
      const std::string key = indexed("point_masses", i);
      const int node = resolve(p.node, key + ".node");
      require_positive(in_.file, key + ".mass", p.mass, limits::mass);
      mesh_.point_masses.push_back({node, p.mass, p.label});
    }
    for (std::size_t i = 0; i < in_.springs.size(); ++i) {
      const ExplicitSpring& sp = in_.springs[i];
      const std::string key = indexed("springs", i);
      SupportSpring s;
      s.node = resolve(sp.node, key + ".node");
      if (sp.dof < 0 || sp.dof > 2) fail(key + ".dof", "springs act on a position DOF: x, y or z");
      require_positive(in_.file, key + ".stiffness", sp.stiffness, limits::stiffness);
      s.dof = sp.dof;
      s.stiffness = sp.stiffness;
      mesh_.springs.push_back(s);
    }
  }

  void add_targets() {
    std::set<int> targeted_bars;
    for (std::size_t i = 0; i < in_.targets.size(); ++i) {
      const ExplicitTarget& in = in_.targets[i];
      const std::string key = indexed("targets", i);
      HeightTarget t;
      t.node = resolve(in.node, key + ".node");
      t.z = in.z.value_or(mesh_.nodes[t.node].position.z());
      const long bar = in.bar;
      if (bar < 0 || bar >= static_cast<long>(mesh_.bars.size()))
        fail(key + ".bar", "bar index " + std::to_string(bar) +
                               " is out of range (the design has " +
                               std::to_string(mesh_.bars.size()) + " bars)");
      if (!mesh_.bars[bar].form_find_length)
        fail(key + ".bar",
             "bar " + std::to_string(bar) + " is not a form-finding bar (give it form_find: true)");
      if (!targeted_bars.insert(static_cast<int>(bar)).second)
        fail(key + ".bar", "bar " + std::to_string(bar) + " already matches another target");
      t.bar = static_cast<int>(bar);
      mesh_.height_targets.push_back(t);
    }
  }

  void add_tension_segments() {
    for (std::size_t i = 0; i < in_.tension_segments.size(); ++i) {
      const ExplicitTensionSegment& in = in_.tension_segments[i];
      const std::string key = indexed("tension_segments", i);
      const int w = mesh_.find_wire(in.wire);
      if (w < 0) fail(key + ".wire", "no wire named '" + in.wire + "'");
      for (const auto& seg : mesh_.tension_segments)
        if (seg.wire == w)
          fail(key + ".wire", "wire '" + in.wire + "' already has a tension segment");
      if (in.tension) require_positive(in_.file, key + ".tension", *in.tension, limits::tension);
      TensionSegment seg;
      seg.wire = w;
      seg.tension = in.tension.value_or(mesh_.wires[w].tension);
      if (!(seg.tension > 0))
        fail(key, "needs a positive tension (the wire '" + in.wire + "' has none; give 'tension')");
      seg.elements = mesh_.wires[w].elements;
      const int index = static_cast<int>(mesh_.tension_segments.size());
      for (int e : seg.elements) mesh_.cables[e].tension_segment = index;
      mesh_.tension_segments.push_back(seg);
    }
  }

  const ExplicitDesign& in_;
  CatenaryMesh mesh_;
  std::vector<int> wire_of_node_;  // wire of every node, -1: none yet
};

}  // namespace

CatenaryMesh build_explicit(const ExplicitDesign& design) {
  CatenaryMesh mesh = ExplicitBuilder(design).build();
  detail::require_consistent(mesh, design.file);
  return mesh;
}

}  // namespace pcsim::catenary
