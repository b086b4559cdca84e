// The XML of pcsim's XDMF files (mesh_xdmf.cpp, xdmf_series.cpp): grids whose
// data are HDF5 datasets beside the XDMF file (XDMF3 names the format "HDF").
#pragma once

#include <ostream>
#include <string>
#include <vector>

namespace pcsim::output::xdmf {

std::string xml_escape(const std::string& s);

// One attribute of a grid: a dataset (file: the grid's HDF5 file when empty),
// or, with 'value' given, one number written in the XDMF file itself.
struct Attribute {
  std::string name, dataset;
  bool is_int = false;
  std::string center = "Node";  // "Node", "Cell" or "Grid" (field data in VTK)
  std::size_t rows = 1, cols = 1;
  std::string file = "";
  std::string value = "";  // inline value (Grid attributes)
};

// A Uniform grid: cells of 'topology' ("Polyline", "Polyvertex") from the
// integer dataset 'connectivity', points from 'geometry' (points x 3).
struct Grid {
  std::string name, topology;
  std::size_t cells = 0, nodes_per_cell = 1, points = 0;
  std::string h5_file, connectivity, geometry = "/nodes/position";
  std::string geometry_file = "";  // h5_file when empty
  std::vector<Attribute> attributes;
};

void write_grid(std::ostream& x, const Grid& grid);

// The file head up to the Domain's opening tag, and its tail.
std::string header(const std::string& domain_name);
std::string footer();

// Writes 'text' to 'path'; throws pcsim::SolverError if it cannot.
void write_file(const std::string& path, const std::string& text);

// The number as text that reads back to the same double.
std::string exact(double value);

}  // namespace pcsim::output::xdmf
