// CatenaryMesh -> HDF5 + XDMF (see mesh_xdmf.hpp for the layout).
#include "pcsim/output/mesh_xdmf.hpp"

#include <cctype>
#include <sstream>
#include <stdexcept>
#include <tuple>

#include "pcsim/core/error.hpp"
#include "pcsim/output/h5_file.hpp"
#include "pcsim/output/provenance.hpp"
#include "xdmf_xml.hpp"

namespace pcsim::output {

using namespace pcsim::catenary;

namespace {

std::string base_name(const std::string& path) {
  auto slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

bool valid_field_name(const std::string& name) {
  if (name.empty()) return false;
  for (char c : name)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_')) return false;
  return true;
}

}  // namespace

std::vector<double> design_positions(const CatenaryMesh& mesh) {
  std::vector<double> out;
  out.reserve(3 * mesh.nodes.size());
  for (const auto& n : mesh.nodes)
    for (int d = 0; d < 3; ++d) out.push_back(n.position[d]);
  return out;
}

namespace {

void check_mesh_output(const CatenaryMesh& mesh, const std::vector<double>& node_positions,
                       const std::vector<NodeField>& node_fields) {
  const std::size_t n = mesh.nodes.size();
  if (node_positions.size() != 3 * n)
    throw std::invalid_argument("write_mesh_h5_xdmf: " + std::to_string(node_positions.size()) +
                                " position values for " + std::to_string(n) + " nodes");
  for (const auto& f : node_fields) {
    if (!valid_field_name(f.name) || (f.components != 1 && f.components != 3) ||
        f.values.size() != n * static_cast<std::size_t>(f.components))
      throw std::invalid_argument("write_mesh_h5_xdmf: bad node field '" + f.name + "'");
  }
}

// /nodes/*: positions, design positions, displacement, wire, fixed DOFs, masses.
void write_nodes_h5(H5File& h5, const CatenaryMesh& mesh,
                    const std::vector<double>& node_positions) {
  const std::size_t n = mesh.nodes.size();
  std::vector<double> design = design_positions(mesh), displacement(3 * n), point_mass(n, 0.0);
  for (std::size_t i = 0; i < 3 * n; ++i) displacement[i] = node_positions[i] - design[i];
  std::vector<long> node_wire(n, -1), fixed(6 * n, 0), fixed_mask(n, 0);
  for (std::size_t w = 0; w < mesh.wires.size(); ++w)
    for (int i : mesh.wires[w].nodes) node_wire[i] = static_cast<long>(w);
  for (std::size_t i = 0; i < n; ++i)
    for (int d = 0; d < kNodeDofs; ++d) {
      fixed[6 * i + d] = mesh.nodes[i].fixed[d] ? 1 : 0;
      if (d < 3 && mesh.nodes[i].fixed[d]) fixed_mask[i] |= 1L << d;
    }
  for (const auto& pm : mesh.point_masses) point_mass[pm.node] += pm.mass;
  h5.write("/nodes/position", node_positions, n, 3, {"m", "node positions (x, y, z)"});
  h5.write("/nodes/design_position", design, n, 3, {"m", "node positions of the design"});
  h5.write("/nodes/displacement", displacement, n, 3, {"m", "position minus design position"});
  h5.write_int("/nodes/wire", node_wire, {"1", "wire of the node (index into /wires), -1: none"});
  h5.write_int("/nodes/fixed", fixed, n, 6, {"1", "1 where a DOF is held (x, y, z, dx, dy, dz)"});
  h5.write_int("/nodes/fixed_mask", fixed_mask, {"1", "positions held: x 1 + y 2 + z 4"});
  h5.write("/nodes/point_mass", point_mass, {"kg", "sum of the point masses at the node"});
}

// /cables/*, /bars/*, /point_masses/*, /wires/*.
void write_elements_h5(H5File& h5, const CatenaryMesh& mesh) {
  std::vector<long> cable_conn, cable_wire, cable_kind, cable_segment;
  std::vector<double> cable_ref, cable_l0;
  for (const auto& c : mesh.cables) {
    cable_conn.insert(cable_conn.end(), {c.nodes[0], c.nodes[1]});
    cable_wire.push_back(c.wire);
    cable_kind.push_back(static_cast<long>(mesh.wires[c.wire].kind));
    cable_segment.push_back(c.tension_segment);
    cable_ref.push_back(c.ref_length);
    cable_l0.push_back(c.unstressed_length);
  }
  std::vector<long> bar_conn, bar_kind, bar_span, bar_index;
  std::vector<double> bar_k, bar_mass, bar_l0;
  for (const auto& b : mesh.bars) {
    bar_conn.insert(bar_conn.end(), {b.nodes[0], b.nodes[1]});
    bar_kind.push_back(static_cast<long>(b.kind));
    bar_span.push_back(b.span);
    bar_index.push_back(b.index_in_span);
    bar_k.push_back(b.stiffness);
    bar_mass.push_back(b.mass);
    bar_l0.push_back(b.unstressed_length);
  }
  h5.write_int("/cables/connectivity", cable_conn, mesh.cables.size(), 2,
               {"1", "node indices of each cable element"});
  h5.write_int("/cables/wire", cable_wire, {"1", "wire of the element (index into /wires)"});
  h5.write_int("/cables/wire_kind", cable_kind,
               {"1", "kind of its wire: messenger 0, contact 1, stitch 2, other 3"});
  h5.write_int("/cables/tension_segment", cable_segment,
               {"1", "tension segment of the element (form-finding)"});
  h5.write("/cables/ref_length", cable_ref, {"m", "reference (design) length of the element"});
  h5.write("/cables/unstressed_length", cable_l0, {"m", "unstressed length of the element"});
  h5.write_int("/bars/connectivity", bar_conn, mesh.bars.size(), 2,
               {"1", "node indices of each bar"});
  h5.write_int("/bars/kind", bar_kind, {"1", "dropper 0, steady arm 1, stitch 2, other 3"});
  h5.write_int("/bars/span", bar_span, {"1", "span of the bar (0-based), -1: none"});
  h5.write_int("/bars/index_in_span", bar_index, {"1", "index of the bar in its span"});
  h5.write("/bars/stiffness", bar_k, {"N/m", "axial stiffness"});
  h5.write("/bars/mass", bar_mass, {"kg", "mass of the bar"});
  h5.write("/bars/unstressed_length", bar_l0, {"m", "unstressed length"});
  std::vector<long> pm_node, wire_kind;
  std::vector<double> pm_mass;
  std::vector<std::string> pm_label, wire_name;
  for (const auto& pm : mesh.point_masses) {
    pm_node.push_back(pm.node);
    pm_mass.push_back(pm.mass);
    pm_label.push_back(pm.label);
  }
  for (const auto& w : mesh.wires) {
    wire_name.push_back(w.name);
    wire_kind.push_back(static_cast<long>(w.kind));
  }
  h5.write_int("/point_masses/node", pm_node, {"1", "node of the point mass"});
  h5.write("/point_masses/mass", pm_mass, {"kg", "point mass"});
  h5.write_strings("/point_masses/label", pm_label, {"none", "what the point mass is"});
  h5.write_strings("/wires/name", wire_name, {"none", "wire names"});
  h5.write_int("/wires/kind", wire_kind, {"1", "messenger 0, contact 1, stitch 2, other 3"});
}

// XDMF: one grid per kind of cell, each with the same node attributes (a
// block without them would leave ParaView's colouring partial); empty grids
// are left out (ParaView does not accept zero-cell grids).
std::string mesh_xdmf(const CatenaryMesh& mesh, const std::string& h5_name,
                      const std::vector<NodeField>& node_fields) {
  const std::size_t n = mesh.nodes.size(), ne = mesh.cables.size(), nb = mesh.bars.size(),
                    np = mesh.point_masses.size();
  std::vector<xdmf::Attribute> node_attributes = {
      {"displacement", "/nodes/displacement", false, "Node", n, 3},
      {"node_wire", "/nodes/wire", true, "Node", n, 1},
      {"fixed_mask", "/nodes/fixed_mask", true, "Node", n, 1},
      {"point_mass", "/nodes/point_mass", false, "Node", n, 1},
  };
  for (const auto& f : node_fields)
    node_attributes.push_back(
        {f.name, "/fields/" + f.name, false, "Node", n, static_cast<std::size_t>(f.components)});
  auto cell = [](const char* name, const char* dataset, bool is_int, std::size_t rows) {
    return xdmf::Attribute{name, dataset, is_int, "Cell", rows, 1};
  };
  std::ostringstream x;
  x << xdmf::header(mesh.name);
  if (ne > 0) {
    xdmf::Grid g{
        "wires", "Polyline",     ne, 2, n, h5_name, "/cables/connectivity", "/nodes/position",
        "",      node_attributes};
    for (auto [name, dataset, is_int] : {std::tuple{"wire", "/cables/wire", true},
                                         {"wire_kind", "/cables/wire_kind", true},
                                         {"tension_segment", "/cables/tension_segment", true},
                                         {"unstressed_length", "/cables/unstressed_length", false}})
      g.attributes.push_back(cell(name, dataset, is_int, ne));
    xdmf::write_grid(x, g);
  }
  if (nb > 0) {
    xdmf::Grid g{"bars", "Polyline",     nb, 2, n, h5_name, "/bars/connectivity", "/nodes/position",
                 "",     node_attributes};
    for (auto [name, dataset, is_int] : {std::tuple{"bar_kind", "/bars/kind", true},
                                         {"span", "/bars/span", true},
                                         {"index_in_span", "/bars/index_in_span", true},
                                         {"unstressed_length", "/bars/unstressed_length", false}})
      g.attributes.push_back(cell(name, dataset, is_int, nb));
    xdmf::write_grid(x, g);
  }
  if (np > 0) {
    xdmf::Grid g{"point_masses",
                 "Polyvertex",
                 np,
                 1,
                 n,
                 h5_name,
                 "/point_masses/node",
                 "/nodes/position",
                 "",
                 node_attributes};
    g.attributes.push_back(cell("mass", "/point_masses/mass", false, np));
    xdmf::write_grid(x, g);
  }
  x << xdmf::footer();
  return x.str();
}

}  // namespace

void write_mesh_h5_xdmf(const CatenaryMesh& mesh, const std::vector<double>& node_positions,
                        const std::string& h5_path, const std::string& xdmf_path,
                        const std::vector<NodeField>& node_fields,
                        const nlohmann::json& provenance) {
  check_mesh_output(mesh, node_positions, node_fields);
  {
    H5File h5(h5_path);
    write_nodes_h5(h5, mesh, node_positions);
    write_elements_h5(h5, mesh);
    for (const auto& f : node_fields)
      h5.write("/fields/" + f.name, f.values, mesh.nodes.size(),
               static_cast<std::size_t>(f.components), {f.unit, "node field " + f.name});
    h5.attribute("/", "name", mesh.name);
    stamp_provenance(h5, provenance);
    h5.attribute("/", "source_file", mesh.source_file);
  }
  xdmf::write_file(xdmf_path, mesh_xdmf(mesh, base_name(h5_path), node_fields));
}

}  // namespace pcsim::output
