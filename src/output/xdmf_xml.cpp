#include "xdmf_xml.hpp"

#include <cerrno>
#include <fstream>
#include <limits>
#include <sstream>

#include "pcsim/core/error.hpp"

namespace pcsim::output::xdmf {

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

namespace {

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

std::string inline_item(const std::string& value, bool is_int) {
  return std::string("<DataItem Format=\"XML\" NumberType=\"") + (is_int ? "Int" : "Float") +
         "\" Precision=\"8\" Dimensions=\"1\">" + value + "</DataItem>";
}

}  // namespace

void write_grid(std::ostream& x, const Grid& g) {
  x << "    <Grid Name=\"" << xml_escape(g.name) << "\" GridType=\"Uniform\">\n";
  x << "      <Topology TopologyType=\"" << g.topology << "\" NumberOfElements=\"" << g.cells
    << "\" NodesPerElement=\"" << g.nodes_per_cell << "\">\n";
  x << "        " << data_item(g.h5_file, g.connectivity, true, g.cells, g.nodes_per_cell) << "\n";
  x << "      </Topology>\n";
  x << "      <Geometry GeometryType=\"XYZ\">\n";
  x << "        "
    << data_item(g.geometry_file.empty() ? g.h5_file : g.geometry_file, g.geometry, false, g.points,
                 3)
    << "\n";
  x << "      </Geometry>\n";
  for (const auto& a : g.attributes) {
    x << "      <Attribute Name=\"" << xml_escape(a.name) << "\" AttributeType=\""
      << (a.cols == 3 ? "Vector" : "Scalar") << "\" Center=\"" << a.center << "\">\n";
    x << "        "
      << (a.value.empty()
              ? data_item(a.file.empty() ? g.h5_file : a.file, a.dataset, a.is_int, a.rows, a.cols)
              : inline_item(a.value, a.is_int))
      << "\n";
    x << "      </Attribute>\n";
  }
  x << "    </Grid>\n";
}

std::string header(const std::string& domain_name) {
  return "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n  <Domain Name=\"" +
         xml_escape(domain_name) + "\">\n";
}

std::string footer() {
  return "  </Domain>\n</Xdmf>\n";
}

void write_file(const std::string& path, const std::string& text) {
  errno = 0;
  std::ofstream out(path);
  if (out) out << text;
  if (out) out.close();
  if (!out) throw OutputError(path, write_failure_reason(path, errno));
}

std::string exact(double value) {
  std::ostringstream s;
  s.precision(std::numeric_limits<double>::max_digits10);
  s << value;
  return s.str();
}

}  // namespace pcsim::output::xdmf
