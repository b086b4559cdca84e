#include "pcsim/scene/flexible_dsa380_reader.hpp"

#include <cmath>

#include "pcsim/scene/composition.hpp"
#include "pcsim/scene/pantograph_reader.hpp"

namespace pcsim::scene {

pantograph::FlexibleDsa380Parameters read_flexible_dsa380(const InputNode& model) {
  model.allow_only(
      {"kind", "name", "source", "rigid_model", "material", "elements_per_bar", "bars"});
  if (model.get_string("kind") != "dsa380_flexible")
    model.fail_key("kind", "must be 'dsa380_flexible' for this reader");
  pantograph::FlexibleDsa380Parameters p;
  p.rigid = load_dsa380_parameters(model.load_referenced("rigid_model"));
  if (model.has("material")) {
    const auto m = model["material"];
    m.allow_only({"density", "youngs_modulus"});
    p.density = m.get_positive("density", limits::density, p.density);
    p.youngs_modulus = m.get_positive("youngs_modulus", limits::youngs_modulus, p.youngs_modulus);
  }
  const long default_elements = model.get_int("elements_per_bar", 8);
  if (default_elements < 1) model.fail_key("elements_per_bar", "must be at least 1");
  const auto bars = model["bars"];
  if (!bars.is_sequence() || bars.size() != 9) bars.fail("must list the 9 bars of Table 2.1");
  const auto& r = p.rigid;
  const double length[7] = {r.L1, r.L2, r.L3, r.L4, r.L5, r.L6, r.L7};
  for (std::size_t i = 0; i < 9; ++i) {
    const auto b = bars.at(i);
    if (i < 6)
      b.allow_only({"name", "r_ext", "elements"});
    else if (i == 6)
      b.allow_only({"name", "r_ext"});
    else
      b.allow_only({"name", "r_ext", "r_int"});
    p.r_ext[i] = b.get_positive("r_ext", limits::pantograph_length);
    if (i < 7) {  // (2.29) needs r_int² = r_ext² − m/(ρπL) ≥ 0
      const double capacity = p.density * M_PI * p.r_ext[i] * p.r_ext[i] * length[i];
      if (r.m[i] > capacity)
        b.fail_key("r_ext", "a solid steel bar of this radius weighs " + std::to_string(capacity) +
                                " kg, less than the rigid model's " + std::to_string(r.m[i]) +
                                " kg (2.29)");
    } else {
      p.massless_r_int[i - 7] = b.get_nonnegative("r_int", limits::pantograph_length);
      if (!(p.massless_r_int[i - 7] < p.r_ext[i]))
        b.fail_key("r_int", "must be smaller than r_ext");
    }
    if (i < 6) {
      const long n = b.get_int("elements", default_elements);
      if (n < 1) b.fail_key("elements", "must be at least 1");
      p.elements[i] = static_cast<int>(n);
    }
  }
  return p;
}

pantograph::FlexibleDsa380Parameters read_flexible_dsa380_file(const std::string& path) {
  return read_flexible_dsa380(load_composed(path));
}

}  // namespace pcsim::scene
