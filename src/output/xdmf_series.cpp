// The XDMF files of series over the static mesh file: modes.xdmf and
// snapshots.xdmf (see mesh_xdmf.hpp).
#include <hdf5.h>

#include <sstream>
#include <stdexcept>

#include "pcsim/core/error.hpp"
#include "pcsim/output/mesh_xdmf.hpp"
#include "xdmf_xml.hpp"

namespace pcsim::output {

namespace {

std::string directory_of(const std::string& path) {
  auto slash = path.find_last_of('/');
  return slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
}

void check_bare(const char* function, std::initializer_list<std::string> names) {
  for (const auto& name : names)
    if (name.find('/') != std::string::npos)
      throw std::invalid_argument(std::string(function) + ": give bare file names, not paths");
}

// Modes whose shape is in the modes file.
std::vector<std::size_t> stored_modes(const std::string& modes_path, std::size_t count) {
  hid_t file = H5Fopen(modes_path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (file < 0) throw SolverError("cannot open HDF5 file " + modes_path);
  std::vector<std::size_t> modes;
  for (std::size_t m = 0; m < count; ++m) {
    const std::string set = "/shapes/mode_" + std::to_string(m);
    if (H5Lexists(file, "/shapes", H5P_DEFAULT) > 0 &&
        H5Lexists(file, set.c_str(), H5P_DEFAULT) > 0)
      modes.push_back(m);
  }
  H5Fclose(file);
  return modes;
}

// The wires and bars grids of the mesh file, each with 'attributes'.
void write_line_grids(std::ostream& x, const catenary::CatenaryMesh& mesh,
                      const std::string& mesh_h5_name,
                      const std::vector<xdmf::Attribute>& attributes) {
  const std::size_t n = mesh.nodes.size(), ne = mesh.cables.size(), nb = mesh.bars.size();
  if (ne > 0)
    xdmf::write_grid(x, {"wires", "Polyline", ne, 2, n, mesh_h5_name, "/cables/connectivity",
                         "/nodes/position", "", attributes});
  if (nb > 0)
    xdmf::write_grid(x, {"bars", "Polyline", nb, 2, n, mesh_h5_name, "/bars/connectivity",
                         "/nodes/position", "", attributes});
}

}  // namespace

void write_modes_xdmf(const catenary::CatenaryMesh& mesh, const std::string& modes_h5_name,
                      const std::string& mesh_h5_name, const std::vector<double>& frequencies_hz,
                      const std::string& xdmf_path, const std::vector<long>& vertical) {
  check_bare("write_modes_xdmf", {modes_h5_name, mesh_h5_name});
  const std::size_t n = mesh.nodes.size();
  const auto modes = stored_modes(directory_of(xdmf_path) + modes_h5_name, frequencies_hz.size());
  std::ostringstream x;
  x << xdmf::header(mesh.name + " modes");
  x << "    <Grid Name=\"modes\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (std::size_t m : modes) {
    // Mesh from the mesh file, mode shape from the modes file; the frequency
    // (and direction) as field data of every grid.
    std::vector<xdmf::Attribute> attrs = {
        {"mode_shape", "/shapes/mode_" + std::to_string(m), false, "Node", n, 3, modes_h5_name}};
    attrs.push_back({"frequency_hz", "", false, "Grid", 1, 1, "", xdmf::exact(frequencies_hz[m])});
    if (m < vertical.size())
      attrs.push_back({"vertical", "", true, "Grid", 1, 1, "", std::to_string(vertical[m])});
    x << "      <Grid Name=\"mode_" << m
      << "\" GridType=\"Collection\" CollectionType=\"Spatial\">\n";
    x << "        <Time Value=\"" << m << "\"/>\n";
    x << "        <Information Name=\"frequency_hz\" Value=\"" << xdmf::exact(frequencies_hz[m])
      << "\"/>\n";
    write_line_grids(x, mesh, mesh_h5_name, attrs);
    x << "      </Grid>\n";
  }
  x << "    </Grid>\n";
  x << xdmf::footer();
  xdmf::write_file(xdmf_path, x.str());
}

namespace {

// Snapshot k's pantographs: head and contact point of each, one line between.
xdmf::Grid pantograph_grid(const std::string& h5_name, std::size_t k, std::size_t np) {
  const std::string row = std::to_string(k);
  xdmf::Grid g{"pantographs",
               "Polyline",
               np,
               2,
               2 * np,
               h5_name,
               "/snapshots/xdmf/pantograph_cells",
               "/snapshots/xdmf/pantograph_points_" + row,
               "",
               {}};
  g.attributes = {
      {"displacement", "/snapshots/xdmf/pantograph_displacement", false, "Node", 2 * np, 3},
      {"contact_force", "/snapshots/xdmf/contact_force_" + row, false, "Cell", np, 1}};
  return g;
}

}  // namespace

void write_snapshots_xdmf(const catenary::CatenaryMesh& mesh, const std::string& mesh_h5_name,
                          const std::string& snapshots_h5_name, const std::vector<double>& times,
                          const std::string& xdmf_path, std::size_t pantographs) {
  check_bare("write_snapshots_xdmf", {snapshots_h5_name, mesh_h5_name});
  const std::size_t n = mesh.nodes.size();
  std::ostringstream x;
  x << xdmf::header(mesh.name + " snapshots");
  x << "    <Grid Name=\"snapshots\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (std::size_t k = 0; k < times.size(); ++k) {
    const std::vector<xdmf::Attribute> attrs = {
        {"displacement", "/snapshots/xdmf/displacement_" + std::to_string(k), false, "Node", n, 3,
         snapshots_h5_name}};
    std::ostringstream t;
    t.precision(10);
    t << times[k];
    x << "      <Grid Name=\"t_" << k << "\" GridType=\"Collection\" CollectionType=\"Spatial\">\n";
    x << "        <Time Value=\"" << t.str() << "\"/>\n";
    write_line_grids(x, mesh, mesh_h5_name, attrs);
    if (pantographs > 0) xdmf::write_grid(x, pantograph_grid(snapshots_h5_name, k, pantographs));
    x << "      </Grid>\n";
  }
  x << "    </Grid>\n";
  x << xdmf::footer();
  xdmf::write_file(xdmf_path, x.str());
}

}  // namespace pcsim::output
