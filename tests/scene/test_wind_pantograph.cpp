// The mean wind's component along the track in the pantograph's aerodynamic
// force (scene/run_scene.cpp, docs/conditions.md "Wind on the pantograph"):
// F = a + b v_air + c v_air^2 with v_air = v - V cos(direction).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "pcsim/pantograph/lumped.hpp"
#include "pcsim/scene/composition.hpp"
#include "pcsim/scene/run_scene.hpp"

namespace {

using namespace pcsim;

constexpr double kA = 10, kB = 0.2, kC = 0.01;  // N, N s/m, N s^2/m^2

// The constant generalised force on the head (uplift + aerodynamic) of the
// EN 50318 two-mass model at 300 km/h with the aerodynamic force on.
double head_load(const std::vector<std::string>& extra) {
  std::vector<std::string> overrides = {"pantographs[0].model.aerodynamic={a: 10, b: 0.2, c: 0.01}",
                                        "pantographs[0].effects={aerodynamic: true}"};
  overrides.insert(overrides.end(), extra.begin(), extra.end());
  std::vector<scene::InputOverride> parsed;
  for (const auto& o : overrides)
    parsed.push_back(scene::parse_override(o, {"", "test --set " + o}));
  auto run = scene::load_run_scene(
      scene::load_composed(std::string(PCSIM_SOURCE_DIR) + "/runs/en50318-300.yaml", parsed));
  const auto* lumped = dynamic_cast<const pantograph::LumpedPantograph*>(run.models.at(0).get());
  EXPECT_NE(lumped, nullptr);
  return lumped ? lumped->load()(0) : 0.0;
}

double aero(double v) {
  return kA + kB * v + kC * v * v;
}

TEST(WindOnPantograph, AHeadWindAddsToTheAirSpeed) {
  const double v = 300 / 3.6, still = head_load({});
  // A wind blowing towards -x (180 deg) meets the train head on: v + V.
  const double head = head_load({"conditions.wind={speed: 20, direction_deg: 180}"});
  EXPECT_NEAR(head - still, aero(v + 20) - aero(v), 1e-9 * aero(v + 20));
  // Towards +x (0 deg): a tail wind, v - V.
  const double tail = head_load({"conditions.wind={speed: 20, direction_deg: 0}"});
  EXPECT_NEAR(tail - still, aero(v - 20) - aero(v), 1e-9 * aero(v));
}

TEST(WindOnPantograph, ACrossWindLeavesItAlone) {
  // cos(90 deg) = 6e-17: the air speed moves by 1e-15 m/s.
  EXPECT_NEAR(head_load({"conditions.wind={speed: 30}"}), head_load({}), 1e-9);
}

}  // namespace
