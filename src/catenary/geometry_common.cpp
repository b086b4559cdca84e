// Helpers shared by the geometry builders, and the mesh consistency check.
#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

#include "geometry_internal.hpp"
#include "pcsim/core/format.hpp"

namespace pcsim::catenary {

namespace detail {

void require_positive(const std::string& file, const std::string& key, double value) {
  if (!(value > 0))
    throw InputError(file, key, "must be positive (got " + format_number(value) + ")");
}

void require_nonnegative(const std::string& file, const std::string& key, double value) {
  if (!(value >= 0))
    throw InputError(file, key, "must not be negative (got " + format_number(value) + ")");
}

void require_positive(const std::string& file, const std::string& key, double value,
                      const Limit& limit) {
  require_positive(file, key, value);
  require_within(file, key, value, limit);
}

void require_nonnegative(const std::string& file, const std::string& key, double value,
                         const Limit& limit) {
  require_nonnegative(file, key, value);
  require_within(file, key, value, limit);
}

void set_common(CatenaryMesh& mesh, const std::string& file, const std::string& name,
                const Eigen::Vector3d& gravity, const RayleighDamping& damping) {
  require_nonnegative(file, "damping.rayleigh_alpha", damping.alpha, limits::rayleigh_alpha);
  require_nonnegative(file, "damping.rayleigh_beta", damping.beta, limits::rayleigh_beta);
  mesh.name = name;
  mesh.source_file = file;
  mesh.gravity = gravity;
  mesh.rayleigh_alpha = damping.alpha;
  mesh.rayleigh_beta = damping.beta;
}

long element_count(double length, double element_length) {
  const double n = std::ceil(length / element_length - 1e-9);
  if (!(n < 1e12)) return 1000000000000L;  // also NaN
  return std::max(1L, static_cast<long>(n));
}

Eigen::Vector3d unit(const Eigen::Vector3d& a) {
  double n = a.norm();
  return n > 0 ? Eigen::Vector3d(a / n) : Eigen::Vector3d::Zero();
}

void set_polyline_slopes(CatenaryMesh& mesh, const std::vector<int>& nodes) {
  const int n = static_cast<int>(nodes.size());
  for (int i = 0; i < n; ++i) {
    Eigen::Vector3d t = Eigen::Vector3d::Zero();
    if (i > 0) t += unit(mesh.nodes[nodes[i]].position - mesh.nodes[nodes[i - 1]].position);
    if (i + 1 < n) t += unit(mesh.nodes[nodes[i + 1]].position - mesh.nodes[nodes[i]].position);
    mesh.nodes[nodes[i]].slope = unit(t);
  }
}

// Solves lambda^3 - lambda = 2 T / EA by Newton.
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

void require_consistent(const CatenaryMesh& mesh, const std::string& file) {
  const std::string problem = mesh_consistency_error(mesh);
  if (!problem.empty()) throw InputError(file, "", "inconsistent mesh: " + problem);
}

}  // namespace detail

namespace {

std::string cable_and_wire_error(const CatenaryMesh& mesh) {
  const int n_nodes = static_cast<int>(mesh.nodes.size());
  auto bad_node = [&](int i) { return i < 0 || i >= n_nodes; };
  for (std::size_t e = 0; e < mesh.cables.size(); ++e) {
    const auto& c = mesh.cables[e];
    const std::string id = "cable element " + std::to_string(e);
    if (bad_node(c.nodes[0]) || bad_node(c.nodes[1])) return id + " has a node out of range";
    if (c.nodes[0] == c.nodes[1]) return id + " joins a node to itself";
    if (c.wire < 0 || c.wire >= static_cast<int>(mesh.wires.size())) return id + " has no wire";
    if (!(c.ref_length > 0) || !(c.unstressed_length > 0)) return id + " has a non-positive length";
    const double design =
        (mesh.nodes[c.nodes[1]].position - mesh.nodes[c.nodes[0]].position).norm();
    if (std::abs(c.ref_length - design) > 1e-9 * (1.0 + c.ref_length))
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
  return "";
}

std::string bar_mass_and_target_error(const CatenaryMesh& mesh) {
  const int n_nodes = static_cast<int>(mesh.nodes.size());
  auto bad_node = [&](int i) { return i < 0 || i >= n_nodes; };
  for (std::size_t b = 0; b < mesh.bars.size(); ++b) {
    const auto& bar = mesh.bars[b];
    const std::string id = "bar " + std::to_string(b);
    if (bad_node(bar.nodes[0]) || bad_node(bar.nodes[1])) return id + " has a node out of range";
    if (!((mesh.nodes[bar.nodes[1]].position - mesh.nodes[bar.nodes[0]].position).norm() > 0))
      return id + " has zero design length";
    if (!(bar.stiffness > 0) || !(bar.unstressed_length > 0) || bar.mass < 0)
      return id + ": invalid properties";
  }
  for (const auto& pm : mesh.point_masses)
    if (bad_node(pm.node) || !(pm.mass > 0)) return "point mass '" + pm.label + "' is invalid";
  for (const auto& s : mesh.springs)
    if (bad_node(s.node) || s.dof < 0 || s.dof > 2 || !(s.stiffness > 0) ||
        (!s.direction.isZero() && std::abs(s.direction.norm() - 1) > 1e-9))
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
  return "";
}

// Contact wires, node forces, tensioning devices, registrations, gap offsets.
std::string line_error(const CatenaryMesh& mesh) {
  const int n_nodes = static_cast<int>(mesh.nodes.size());
  auto bad_node = [&](int i) { return i < 0 || i >= n_nodes; };
  for (int w : mesh.contact_wires)
    if (w < 0 || w >= static_cast<int>(mesh.wires.size()) ||
        mesh.wires[w].kind != WireKind::contact)
      return "contact_wires lists a wire that is not a contact wire";
  if (!mesh.contact_wires.empty() && mesh.contact_wire != mesh.contact_wires.front())
    return "contact_wire is not the first of contact_wires";
  if (!mesh.contact_gap_offsets.empty() &&
      mesh.contact_gap_offsets.size() != mesh.contact_wire_list().size())
    return "contact_gap_offsets must have one table per contact wire";
  for (const auto& g : mesh.contact_gap_offsets)
    if (g.x.size() != g.offset.size()) return "a contact-gap offset table is ragged";
  for (const auto& nf : mesh.node_forces)
    if (bad_node(nf.node) || !nf.force.allFinite())
      return "node force '" + nf.label + "' is invalid";
  for (const auto& d : mesh.tensioning_devices)
    if (bad_node(d.node) || d.mass < 0 || d.stiffness < 0 ||
        std::abs(d.direction.norm() - 1) > 1e-9)
      return "a tensioning device is invalid";
  for (const auto& r : mesh.registrations)
    if (bad_node(r.node) || r.support < 0 || r.support >= static_cast<int>(mesh.support_x.size()))
      return "a registration is invalid";
  for (const auto& c : mesh.cables)
    if (!(c.section_factor > 0) || c.section_factor > 1)
      return "a cable element has a section factor outside (0, 1]";
  return "";
}

std::string segment_and_support_error(const CatenaryMesh& mesh) {
  for (std::size_t s = 0; s < mesh.tension_segments.size(); ++s) {
    const auto& seg = mesh.tension_segments[s];
    const std::string id = "tension segment " + std::to_string(s);
    if (!(seg.tension > 0)) return id + " is invalid";
    if (!seg.bars.empty()) {
      if (seg.wire != -1 || !seg.elements.empty()) return id + " mixes bars and a wire";
      for (int b : seg.bars)
        if (b < 0 || b >= static_cast<int>(mesh.bars.size()) || mesh.bars[b].form_find_length)
          return id + " lists bar " + std::to_string(b) + " that cannot be its own";
      continue;
    }
    if (seg.wire < 0 || seg.wire >= static_cast<int>(mesh.wires.size()) || seg.elements.empty())
      return id + " is invalid";
    for (int e : seg.elements)
      if (e < 0 || e >= static_cast<int>(mesh.cables.size()) || mesh.cables[e].wire != seg.wire ||
          mesh.cables[e].tension_segment != static_cast<int>(s))
        return id + " lists element " + std::to_string(e) + " that is not its own";
  }
  if (mesh.support_x.size() != mesh.support_nodes.size())
    return "support_x and support_nodes differ";
  for (int n : mesh.support_nodes)
    if (n < 0 || n >= static_cast<int>(mesh.nodes.size())) return "a support node is out of range";
  if (mesh.contact_wire < -1 || mesh.contact_wire >= static_cast<int>(mesh.wires.size()))
    return "contact_wire is out of range";
  return line_error(mesh);
}

}  // namespace

std::string mesh_consistency_error(const CatenaryMesh& mesh) {
  std::string problem = cable_and_wire_error(mesh);
  if (problem.empty()) problem = bar_mass_and_target_error(mesh);
  if (problem.empty()) problem = segment_and_support_error(mesh);
  return problem;
}

}  // namespace pcsim::catenary
