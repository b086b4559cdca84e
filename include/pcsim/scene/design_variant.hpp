// Variants of a catenary design for studies (`pcsim study accuracy`): the
// design file read as usual, one parameter changed before the mesh is built.
#pragma once

#include <string>

#include "pcsim/catenary/mesh.hpp"

namespace pcsim::catenary {

// The design in 'path' with its element_length multiplied by 'factor'. Only
// parametric designs have an element length: for an explicit design a factor
// other than 1 is an InputError on (option_file, option_key).
CatenaryMesh load_catenary_design_scaled(const std::string& path, double factor,
                                         const std::string& option_file,
                                         const std::string& option_key);

// The element length of the design in 'path' (0 for an explicit design).
double design_element_length(const std::string& path);

}  // namespace pcsim::catenary
