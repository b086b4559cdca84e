// CatenaryMesh -> HDF5 + XDMF (see mesh_xdmf.hpp for the layout).
#include "pcsim/output/mesh_xdmf.hpp"

#include <cctype>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "pcsim/core/error.hpp"
#include "pcsim/output/h5_file.hpp"
#include "pcsim/output/provenance.hpp"

namespace pcsim::output {

using namespace pcsim::catenary;

namespace {

std::string xml_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

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

// One HDF5 data item of the XDMF file (XDMF3 names the format "HDF", not "HDF5").
std::string data_item(const std::string& h5_name, const std::string& dataset, bool is_int,
                      std::size_t rows, std::size_t cols) {
  std::ostringstream s;
  s << "<DataItem Format=\"HDF\" NumberType=\"" << (is_int ? "Int" : "Float")
    << "\" Precision=\"8\" Dimensions=\"" << rows;
  if (cols > 1) s << " " << cols;
  s << "\">" << xml_escape(h5_name) << ":" << dataset << "</DataItem>";
  return s.str();
}

struct XdmfAttribute {
  std::string name, dataset;
  bool is_int;
  bool on_cells;
  std::size_t rows, cols;
  std::string file = "";  // HDF5 file name when not the grid's
};

std::string directory_of(const std::string& path) {
  auto slash = path.find_last_of('/');
  return slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
}

void write_xdmf_file(const std::string& path, const std::string& text) {
  std::ofstream out(path);
  if (!out) throw SolverError("cannot create XDMF file " + path);
  out << text;
  out.close();
  if (!out) throw SolverError("cannot write XDMF file " + path);
}

void write_grid(std::ostream& x, const std::string& h5_name, const std::string& grid_name,
                const std::string& topology, std::size_t cells, const std::string& connectivity,
                std::size_t nodes_per_cell, std::size_t n_nodes,
                const std::vector<XdmfAttribute>& attributes) {
  x << "    <Grid Name=\"" << xml_escape(grid_name) << "\" GridType=\"Uniform\">\n";
  x << "      <Topology TopologyType=\"" << topology << "\" NumberOfElements=\"" << cells
    << "\" NodesPerElement=\"" << nodes_per_cell << "\">\n";
  x << "        " << data_item(h5_name, connectivity, true, cells, nodes_per_cell) << "\n";
  x << "      </Topology>\n";
  x << "      <Geometry GeometryType=\"XYZ\">\n";
  x << "        " << data_item(h5_name, "/nodes/position", false, n_nodes, 3) << "\n";
  x << "      </Geometry>\n";
  for (const auto& a : attributes) {
    x << "      <Attribute Name=\"" << xml_escape(a.name) << "\" AttributeType=\""
      << (a.cols == 3 ? "Vector" : "Scalar") << "\" Center=\"" << (a.on_cells ? "Cell" : "Node")
      << "\">\n";
    x << "        "
      << data_item(a.file.empty() ? h5_name : a.file, a.dataset, a.is_int, a.rows, a.cols) << "\n";
    x << "      </Attribute>\n";
  }
  x << "    </Grid>\n";
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

// XDMF: one grid per kind of cell; empty grids are left out (ParaView
// does not accept zero-cell grids).
std::string mesh_xdmf(const CatenaryMesh& mesh, const std::string& h5_name,
                      const std::vector<NodeField>& node_fields) {
  const std::size_t n = mesh.nodes.size(), ne = mesh.cables.size(), nb = mesh.bars.size(),
                    np = mesh.point_masses.size();
  std::vector<XdmfAttribute> node_attributes = {
      {"displacement", "/nodes/displacement", false, false, n, 3},
      {"node_wire", "/nodes/wire", true, false, n, 1},
      {"fixed_mask", "/nodes/fixed_mask", true, false, n, 1},
      {"point_mass", "/nodes/point_mass", false, false, n, 1},
  };
  for (const auto& f : node_fields)
    node_attributes.push_back(
        {f.name, "/fields/" + f.name, false, false, n, static_cast<std::size_t>(f.components)});
  std::ostringstream x;
  x << "<?xml version=\"1.0\" ?>\n";
  x << "<Xdmf Version=\"3.0\">\n";
  x << "  <Domain Name=\"" << xml_escape(mesh.name) << "\">\n";
  if (ne > 0) {
    auto attrs = node_attributes;
    attrs.push_back({"wire", "/cables/wire", true, true, ne, 1});
    attrs.push_back({"wire_kind", "/cables/wire_kind", true, true, ne, 1});
    attrs.push_back({"tension_segment", "/cables/tension_segment", true, true, ne, 1});
    attrs.push_back({"unstressed_length", "/cables/unstressed_length", false, true, ne, 1});
    write_grid(x, h5_name, "wires", "Polyline", ne, "/cables/connectivity", 2, n, attrs);
  }
  if (nb > 0) {
    auto attrs = node_attributes;
    attrs.push_back({"bar_kind", "/bars/kind", true, true, nb, 1});
    attrs.push_back({"span", "/bars/span", true, true, nb, 1});
    attrs.push_back({"index_in_span", "/bars/index_in_span", true, true, nb, 1});
    attrs.push_back({"unstressed_length", "/bars/unstressed_length", false, true, nb, 1});
    write_grid(x, h5_name, "bars", "Polyline", nb, "/bars/connectivity", 2, n, attrs);
  }
  if (np > 0) {
    std::vector<XdmfAttribute> attrs = {{"mass", "/point_masses/mass", false, true, np, 1}};
    write_grid(x, h5_name, "point_masses", "Polyvertex", np, "/point_masses/node", 1, n, attrs);
  }
  x << "  </Domain>\n";
  x << "</Xdmf>\n";
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
  write_xdmf_file(xdmf_path, mesh_xdmf(mesh, base_name(h5_path), node_fields));
}

void write_modes_xdmf(const CatenaryMesh& mesh, const std::string& modes_h5_name,
                      const std::string& mesh_h5_name, const std::vector<double>& frequencies_hz,
                      const std::string& xdmf_path) {
  if (modes_h5_name.find('/') != std::string::npos || mesh_h5_name.find('/') != std::string::npos)
    throw std::invalid_argument("write_modes_xdmf: give bare file names, not paths");
  const std::size_t n = mesh.nodes.size(), ne = mesh.cables.size(), nb = mesh.bars.size();

  // Modes whose shape is in the modes file.
  const std::string modes_path = directory_of(xdmf_path) + modes_h5_name;
  hid_t file = H5Fopen(modes_path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (file < 0) throw SolverError("cannot open HDF5 file " + modes_path);
  std::vector<std::size_t> modes;
  for (std::size_t m = 0; m < frequencies_hz.size(); ++m) {
    const std::string set = "/shapes/mode_" + std::to_string(m);
    if (H5Lexists(file, "/shapes", H5P_DEFAULT) > 0 &&
        H5Lexists(file, set.c_str(), H5P_DEFAULT) > 0)
      modes.push_back(m);
  }
  H5Fclose(file);

  std::ostringstream x;
  x << "<?xml version=\"1.0\" ?>\n";
  x << "<Xdmf Version=\"3.0\">\n";
  x << "  <Domain Name=\"" << xml_escape(mesh.name) << " modes\">\n";
  x << "    <Grid Name=\"modes\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (std::size_t m : modes) {
    std::ostringstream freq;
    freq.precision(10);
    freq << frequencies_hz[m];
    // Mesh from the mesh file, mode shape from the modes file.
    const std::vector<XdmfAttribute> attrs = {
        {"mode_shape", "/shapes/mode_" + std::to_string(m), false, false, n, 3, modes_h5_name}};
    std::ostringstream grids;
    if (ne > 0)
      write_grid(grids, mesh_h5_name, "wires", "Polyline", ne, "/cables/connectivity", 2, n, attrs);
    if (nb > 0)
      write_grid(grids, mesh_h5_name, "bars", "Polyline", nb, "/bars/connectivity", 2, n, attrs);
    x << "      <Grid Name=\"mode_" << m
      << "\" GridType=\"Collection\" CollectionType=\"Spatial\">\n";
    x << "        <Time Value=\"" << m << "\"/>\n";
    x << "        <Information Name=\"frequency_hz\" Value=\"" << freq.str() << "\"/>\n";
    x << grids.str();
    x << "      </Grid>\n";
  }
  x << "    </Grid>\n";
  x << "  </Domain>\n";
  x << "</Xdmf>\n";
  write_xdmf_file(xdmf_path, x.str());
}

void write_snapshots_xdmf(const CatenaryMesh& mesh, const std::string& mesh_h5_name,
                          const std::string& snapshots_h5_name, const std::vector<double>& times,
                          const std::string& xdmf_path) {
  if (snapshots_h5_name.find('/') != std::string::npos ||
      mesh_h5_name.find('/') != std::string::npos)
    throw std::invalid_argument("write_snapshots_xdmf: give bare file names, not paths");
  const std::size_t n = mesh.nodes.size(), ne = mesh.cables.size(), nb = mesh.bars.size();
  std::ostringstream x;
  x << "<?xml version=\"1.0\" ?>\n";
  x << "<Xdmf Version=\"3.0\">\n";
  x << "  <Domain Name=\"" << xml_escape(mesh.name) << " snapshots\">\n";
  x << "    <Grid Name=\"snapshots\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (std::size_t k = 0; k < times.size(); ++k) {
    const std::vector<XdmfAttribute> attrs = {{"displacement",
                                               "/snapshots/xdmf/displacement_" + std::to_string(k),
                                               false, false, n, 3, snapshots_h5_name}};
    std::ostringstream grids;
    if (ne > 0)
      write_grid(grids, mesh_h5_name, "wires", "Polyline", ne, "/cables/connectivity", 2, n, attrs);
    if (nb > 0)
      write_grid(grids, mesh_h5_name, "bars", "Polyline", nb, "/bars/connectivity", 2, n, attrs);
    std::ostringstream t;
    t.precision(10);
    t << times[k];
    x << "      <Grid Name=\"t_" << k << "\" GridType=\"Collection\" CollectionType=\"Spatial\">\n";
    x << "        <Time Value=\"" << t.str() << "\"/>\n";
    x << grids.str();
    x << "      </Grid>\n";
  }
  x << "    </Grid>\n";
  x << "  </Domain>\n";
  x << "</Xdmf>\n";
  write_xdmf_file(xdmf_path, x.str());
}

}  // namespace pcsim::output
