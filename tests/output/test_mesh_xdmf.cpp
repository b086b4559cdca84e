// Catenary mesh -> HDF5 + XDMF (output/mesh_xdmf.hpp), on meshes built from design
// parameters (design_fixtures.hpp).
#include <gtest/gtest.h>
#include <hdf5.h>
#include <unistd.h>

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "../catenary/design_fixtures.hpp"
#include "pcsim/catenary/geometry.hpp"
#include "pcsim/output/catenary_results.hpp"
#include "pcsim/output/h5_file.hpp"
#include "pcsim/output/mesh_xdmf.hpp"

using namespace pcsim::catenary;
using namespace pcsim::output;
using pcsim::design_fixtures::reference_design;
using pcsim::design_fixtures::taut_string_design;

namespace {

// Minimal well-formedness parser for the XDMF we write: elements with
// quoted attributes, text, comments, <?...?> and <!...> declarations.
struct XmlElement {
  std::string name;
  std::map<std::string, std::string> attributes;
  std::string text;
  std::vector<XmlElement> children;
};

class XmlParser {
 public:
  explicit XmlParser(std::string text) : s_(std::move(text)) {}
  bool parse(XmlElement& root, std::string& error) {
    try {
      skip_misc();
      if (!peek("<")) throw std::runtime_error("no root element");
      root = element();
      skip_misc();
      if (pos_ != s_.size()) throw std::runtime_error("content after the root element");
      return true;
    } catch (const std::exception& e) {
      error = std::string(e.what()) + " at offset " + std::to_string(pos_);
      return false;
    }
  }

 private:
  bool peek(const char* t) const { return s_.compare(pos_, std::strlen(t), t) == 0; }
  void expect(const char* t) {
    if (!peek(t)) throw std::runtime_error(std::string("expected '") + t + "'");
    pos_ += std::strlen(t);
  }
  void skip_space() {
    while (pos_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[pos_]))) ++pos_;
  }
  void skip_until(const char* end) {
    auto p = s_.find(end, pos_);
    if (p == std::string::npos) throw std::runtime_error(std::string("unterminated, no ") + end);
    pos_ = p + std::strlen(end);
  }
  void skip_misc() {
    for (;;) {
      skip_space();
      if (peek("<?"))
        skip_until("?>");
      else if (peek("<!--"))
        skip_until("-->");
      else if (peek("<!"))
        skip_until(">");
      else
        return;
    }
  }
  std::string name() {
    std::size_t start = pos_;
    while (pos_ < s_.size() &&
           (std::isalnum(static_cast<unsigned char>(s_[pos_])) || s_[pos_] == '_' ||
            s_[pos_] == '-' || s_[pos_] == ':' || s_[pos_] == '.'))
      ++pos_;
    if (pos_ == start) throw std::runtime_error("expected a name");
    return s_.substr(start, pos_ - start);
  }
  std::string unescape(const std::string& t) {
    std::string out;
    for (std::size_t i = 0; i < t.size(); ++i) {
      if (t[i] == '<') throw std::runtime_error("'<' in text or attribute");
      if (t[i] != '&') {
        out += t[i];
        continue;
      }
      auto semi = t.find(';', i);
      if (semi == std::string::npos) throw std::runtime_error("bad entity");
      const std::string ent = t.substr(i + 1, semi - i - 1);
      static const std::map<std::string, char> known = {
          {"amp", '&'}, {"lt", '<'}, {"gt", '>'}, {"quot", '"'}, {"apos", '\''}};
      if (!known.count(ent)) throw std::runtime_error("unknown entity &" + ent + ";");
      out += known.at(ent);
      i = semi;
    }
    return out;
  }
  XmlElement element() {
    XmlElement e;
    expect("<");
    e.name = name();
    for (;;) {
      skip_space();
      if (peek("/>")) {
        pos_ += 2;
        return e;
      }
      if (peek(">")) {
        ++pos_;
        break;
      }
      const std::string key = name();
      skip_space();
      expect("=");
      skip_space();
      const char quote = s_[pos_];
      if (quote != '"' && quote != '\'') throw std::runtime_error("unquoted attribute " + key);
      auto end = s_.find(quote, pos_ + 1);
      if (end == std::string::npos) throw std::runtime_error("unterminated attribute");
      if (!e.attributes.emplace(key, unescape(s_.substr(pos_ + 1, end - pos_ - 1))).second)
        throw std::runtime_error("duplicate attribute " + key);
      pos_ = end + 1;
    }
    for (;;) {
      auto lt = s_.find('<', pos_);
      if (lt == std::string::npos) throw std::runtime_error("unclosed element " + e.name);
      e.text += unescape(s_.substr(pos_, lt - pos_));
      pos_ = lt;
      if (peek("</")) {
        pos_ += 2;
        if (name() != e.name) throw std::runtime_error("mismatched closing tag for " + e.name);
        skip_space();
        expect(">");
        return e;
      }
      if (peek("<!--")) {
        skip_until("-->");
        continue;
      }
      e.children.push_back(element());
    }
  }
  std::string s_;
  std::size_t pos_ = 0;
};

void collect(const XmlElement& e, const std::string& name, std::vector<const XmlElement*>& out) {
  if (e.name == name) out.push_back(&e);
  for (const auto& c : e.children) collect(c, name, out);
}

std::string trim(const std::string& s) {
  auto a = s.find_first_not_of(" \t\n\r");
  auto b = s.find_last_not_of(" \t\n\r");
  return a == std::string::npos ? "" : s.substr(a, b - a + 1);
}

std::vector<hsize_t> dataset_dims(const std::string& h5_path, const std::string& dataset) {
  std::vector<hsize_t> dims;
  hid_t file = H5Fopen(h5_path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (file < 0) return dims;
  if (H5Lexists(file, dataset.c_str(), H5P_DEFAULT) > 0) {
    hid_t set = H5Dopen2(file, dataset.c_str(), H5P_DEFAULT);
    hid_t space = H5Dget_space(set);
    dims.resize(H5Sget_simple_extent_ndims(space));
    H5Sget_simple_extent_dims(space, dims.data(), nullptr);
    H5Sclose(space);
    H5Dclose(set);
  }
  H5Fclose(file);
  return dims;
}

std::vector<double> read_doubles(const std::string& h5_path, const std::string& dataset) {
  hid_t file = H5Fopen(h5_path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  hid_t set = H5Dopen2(file, dataset.c_str(), H5P_DEFAULT);
  hid_t space = H5Dget_space(set);
  std::vector<double> out(H5Sget_simple_extent_npoints(space));
  H5Dread(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data());
  H5Sclose(space);
  H5Dclose(set);
  H5Fclose(file);
  return out;
}

std::filesystem::path make_temp_dir() {
  std::string templ = (std::filesystem::temp_directory_path() / "pcsim-design-XXXXXX").string();
  char* made = mkdtemp(templ.data());
  if (!made) throw std::runtime_error("mkdtemp failed");
  return std::filesystem::path(made);
}

// Parses folder/xdmf_name and checks that every DataItem names one of
// 'h5_names' (bare file names) and a dataset there with the stated dimensions.
void check_xdmf_references(const std::string& folder, const std::string& xdmf_name,
                           const std::set<std::string>& h5_names, XmlElement& root) {
  std::ifstream in(folder + "/" + xdmf_name);
  std::stringstream text;
  text << in.rdbuf();
  std::string error;
  ASSERT_TRUE(XmlParser(text.str()).parse(root, error)) << error;
  std::vector<const XmlElement*> items;
  collect(root, "DataItem", items);
  ASSERT_FALSE(items.empty());
  for (const XmlElement* item : items) {
    if (item->attributes.at("Format") == "XML") {  // a Grid attribute's one number
      EXPECT_EQ(item->attributes.at("Dimensions"), "1");
      continue;
    }
    EXPECT_EQ(item->attributes.at("Format"), "HDF");
    const std::string ref = trim(item->text);
    const auto colon = ref.find(':');
    ASSERT_NE(colon, std::string::npos) << ref;
    const std::string file = ref.substr(0, colon);
    EXPECT_EQ(h5_names.count(file), 1u) << "must be a bare file name: " << ref;
    const std::string dataset = ref.substr(colon + 1);
    const auto dims = dataset_dims(folder + "/" + file, dataset);
    ASSERT_FALSE(dims.empty()) << "dataset " << dataset << " missing from " << file;
    std::istringstream want(item->attributes.at("Dimensions"));
    std::vector<hsize_t> wanted;
    for (hsize_t d; want >> d;) wanted.push_back(d);
    EXPECT_EQ(dims, wanted) << dataset;
  }
}

// Names of the attributes of 'grid' with the given Center.
std::vector<std::string> attribute_names(const XmlElement& grid, const std::string& center) {
  std::vector<std::string> names;
  for (const auto& c : grid.children)
    if (c.name == "Attribute" && c.attributes.at("Center") == center)
      names.push_back(c.attributes.at("Name"));
  return names;
}

// Writes 'mesh', moves the folder, and checks every HDF5 reference of the XDMF.
void check_written_mesh(const CatenaryMesh& mesh, std::size_t expected_grids) {
  const auto dir = make_temp_dir();
  std::vector<double> positions = design_positions(mesh);
  for (std::size_t i = 0; i < positions.size(); i += 3) positions[i + 2] -= 0.01;  // a "solution"
  NodeField speed{"speed", 1, std::vector<double>(mesh.nodes.size(), 2.0)};
  write_mesh_h5_xdmf(mesh, positions, (dir / "mesh.h5").string(), (dir / "mesh.xdmf").string(),
                     {speed});
  // The folder can be moved: nothing refers to its old name.
  const auto moved = dir.string() + "-moved";
  std::filesystem::rename(dir, moved);
  const std::string h5 = moved + "/mesh.h5";
  XmlElement root;
  check_xdmf_references(moved, "mesh.xdmf", {"mesh.h5"}, root);
  if (::testing::Test::HasFatalFailure()) return;
  EXPECT_EQ(root.name, "Xdmf");
  std::vector<const XmlElement*> grids;
  collect(root, "Grid", grids);
  EXPECT_EQ(grids.size(), expected_grids);
  // Every grid has the same node attributes (ParaView colours every block).
  const std::vector<std::string> node_attributes = {"displacement", "node_wire", "fixed_mask",
                                                    "point_mass", "speed"};
  for (const XmlElement* grid : grids) {
    EXPECT_EQ(attribute_names(*grid, "Node"), node_attributes) << grid->attributes.at("Name");
    const XmlElement* topology = nullptr;
    for (const auto& c : grid->children)
      if (c.name == "Topology") topology = &c;
    ASSERT_NE(topology, nullptr);
    const std::string name = grid->attributes.at("Name");
    const std::string cells = topology->attributes.at("NumberOfElements");
    if (name == "wires") {
      EXPECT_EQ(topology->attributes.at("TopologyType"), "Polyline");
      EXPECT_EQ(topology->attributes.at("NodesPerElement"), "2");
      EXPECT_EQ(cells, std::to_string(mesh.cables.size()));
    } else if (name == "bars") {
      EXPECT_EQ(topology->attributes.at("TopologyType"), "Polyline");
      EXPECT_EQ(cells, std::to_string(mesh.bars.size()));
    } else {
      EXPECT_EQ(name, "point_masses");
      EXPECT_EQ(cells, std::to_string(mesh.point_masses.size()));
    }
  }
  // Values round-trip.
  EXPECT_EQ(read_doubles(h5, "/nodes/position"), positions);
  const auto disp = read_doubles(h5, "/nodes/displacement");
  ASSERT_EQ(disp.size(), positions.size());
  for (std::size_t i = 0; i < disp.size(); ++i)
    EXPECT_NEAR(disp[i], i % 3 == 2 ? -0.01 : 0.0, 1e-12);
  EXPECT_EQ(read_doubles(h5, "/fields/speed"), speed.values);
  std::filesystem::remove_all(moved);
}

}  // namespace

TEST(MeshOutput, ReferenceXdmfIsWellFormedAndMatchesH5) {
  const CatenaryMesh m = build_parametric(reference_design(10));
  check_written_mesh(m, 3);  // wires, bars, point masses
}

TEST(MeshOutput, GridsWithoutCellsAreLeftOut) {
  const CatenaryMesh m = build_explicit(taut_string_design());
  check_written_mesh(m, 1);  // wires only
}

TEST(MeshOutput, RejectsWrongPositionCount) {
  const CatenaryMesh m = build_explicit(taut_string_design());
  const auto dir = make_temp_dir();
  EXPECT_THROW(write_mesh_h5_xdmf(m, std::vector<double>(5, 0.0), (dir / "m.h5").string(),
                                  (dir / "m.xdmf").string()),
               std::invalid_argument);
  std::filesystem::remove_all(dir);
}

TEST(MeshOutput, ModesXdmfReferencesMeshAndModeFiles) {
  const CatenaryMesh m = build_parametric(reference_design(2));
  const auto dir = make_temp_dir();
  const auto positions = design_positions(m);
  write_mesh_h5_xdmf(m, positions, (dir / "mesh.h5").string(), (dir / "mesh.xdmf").string());
  const std::vector<double> frequencies = {1.5, 2.5, 3.5};
  {
    pcsim::output::H5File h5((dir / "modes.h5").string());
    h5.write("/frequencies_hz", frequencies);
    for (int mode = 0; mode < 2; ++mode)  // no shape for the third mode
      h5.write("/shapes/mode_" + std::to_string(mode), std::vector<double>(positions.size(), 0.1),
               m.nodes.size(), 3);
  }
  write_modes_xdmf(m, "modes.h5", "mesh.h5", frequencies, (dir / "modes.xdmf").string(), {1, 0, 1});
  XmlElement root;
  check_xdmf_references(dir.string(), "modes.xdmf", {"mesh.h5", "modes.h5"}, root);
  if (HasFatalFailure()) return;
  std::vector<const XmlElement*> grids, times, infos;
  collect(root, "Grid", grids);
  collect(root, "Time", times);
  collect(root, "Information", infos);
  // Temporal collection + 2 modes x (spatial collection + wires + bars).
  EXPECT_EQ(grids.size(), 1u + 2u * 3u);
  ASSERT_EQ(times.size(), 2u);
  EXPECT_EQ(times[1]->attributes.at("Value"), "1");
  ASSERT_EQ(infos.size(), 2u);
  EXPECT_EQ(infos[1]->attributes.at("Value"), "2.5");
  // The frequency and the direction as Grid attributes (field data) of every
  // grid of a mode, written exactly.
  for (const XmlElement* grid : grids) {
    if (grid->attributes.at("GridType") != "Uniform") continue;
    EXPECT_EQ(attribute_names(*grid, "Grid"),
              (std::vector<std::string>{"frequency_hz", "vertical"}));
    EXPECT_EQ(attribute_names(*grid, "Node"), std::vector<std::string>{"mode_shape"});
  }
  std::vector<const XmlElement*> attributes;
  collect(root, "Attribute", attributes);
  std::vector<std::string> values;
  for (const XmlElement* a : attributes)
    if (a->attributes.at("Center") == "Grid") values.push_back(trim(a->children.at(0).text));
  // mode 0 (wires, bars), mode 1 (wires, bars): frequency, vertical.
  EXPECT_EQ(values, (std::vector<std::string>{"1.5", "1", "1.5", "1", "2.5", "0", "2.5", "0"}));
  EXPECT_THROW(
      write_modes_xdmf(m, "sub/modes.h5", "mesh.h5", frequencies, (dir / "modes.xdmf").string()),
      std::invalid_argument);
  std::filesystem::remove_all(dir);
}

// A mode is vertical when z dominates the contact wire's motion, lateral
// when y does; the messenger's motion does not count.
TEST(MeshOutput, ModeDirectionFromTheContactWire) {
  const CatenaryMesh m = build_parametric(reference_design(2));
  const std::size_t n = m.nodes.size();
  std::vector<bool> on_contact(n, false);
  for (const auto& w : m.wires)
    if (w.kind == pcsim::catenary::WireKind::contact)
      for (int i : w.nodes) on_contact[i] = true;
  std::vector<double> vertical(3 * n, 0.0), lateral(3 * n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    // Contact wire: z 1 and y 0.5 (vertical), or the reverse; elsewhere the
    // other direction, ten times larger.
    vertical[3 * i + 2] = on_contact[i] ? 1.0 : 0.0;
    vertical[3 * i + 1] = on_contact[i] ? 0.5 : 10.0;
    lateral[3 * i + 1] = on_contact[i] ? 1.0 : 0.0;
    lateral[3 * i + 2] = on_contact[i] ? 0.5 : 10.0;
  }
  EXPECT_EQ(pcsim::output::modes_vertical(m, {vertical, lateral, vertical}),
            (std::vector<long>{1, 0, 1}));
}
