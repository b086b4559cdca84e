#include "pcsim/scene/design_variant.hpp"

#include "pcsim/catenary/geometry.hpp"
#include "pcsim/scene/design_reader.hpp"
#include "pcsim/scene/yaml_input.hpp"

namespace pcsim::catenary {

namespace {
bool is_parametric(const InputNode& root) {
  return root.is_map() && root.has("type") && root.get_string("type") == "parametric";
}
}  // namespace

CatenaryMesh load_catenary_design_scaled(const std::string& path, double factor,
                                         const std::string& option_file,
                                         const std::string& option_key) {
  if (factor == 1.0) return load_catenary_design(path);
  const InputNode root = InputNode::load_file(path);
  if (!is_parametric(root))
    throw InputError(option_file, option_key,
                     "the design '" + path + "' is not parametric: it has no element length");
  ParametricDesign design = read_parametric_design(root);
  design.element_length *= factor;
  CatenaryMesh mesh = build_parametric(design);
  mesh.source_file = path;
  return mesh;
}

double design_element_length(const std::string& path) {
  const InputNode root = InputNode::load_file(path);
  return is_parametric(root) ? read_parametric_design(root).element_length : 0.0;
}

}  // namespace pcsim::catenary
