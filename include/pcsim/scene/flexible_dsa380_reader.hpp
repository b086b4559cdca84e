// Reader of a flexible-bar DSA-380 model file (meshes/pantographs/dsa380_flexible.yaml):
//   kind: dsa380_flexible
//   rigid_model: dsa380_rigid.yaml      # geometry, head, springs, damper, bar masses
//   material: {density: 7850, youngs_modulus: 2.1e11}
//   elements_per_bar: 8                 # bars 1–6 (a bar may override with 'elements')
//   bars:                               # the nine bars of Table 2.1, in order
//     - {name: lower arm, r_ext: 0.075} # r_int of bars 1–7 solved from the masses (2.29)
//     ...
//     - {name: ..., r_ext: 0.025, r_int: 0.024}  # bars 8, 9: massless, r_int given
// Errors name the file and the key (pcsim::InputError).
#pragma once

#include <string>

#include "pcsim/pantograph/flexible_dsa380.hpp"
#include "pcsim/scene/yaml_input.hpp"

namespace pcsim::scene {

pantograph::FlexibleDsa380Parameters read_flexible_dsa380(const InputNode& model);
pantograph::FlexibleDsa380Parameters read_flexible_dsa380_file(const std::string& path);

}  // namespace pcsim::scene
