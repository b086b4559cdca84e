// The mean wind's component along the track in the pantograph's aerodynamic
// force (scene/run_scene.cpp, docs/conditions.md "Wind on the pantograph"):
// F = a + b v_air + c v_air^2 with v_air = v - V cos(direction); and the
// cross-wind's lateral force on it, F_y = rho CdA V_y |V_y| / 2, with the
// head's deflection F_y / k_y ("pantographs[].cross_wind").
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
scene::RunScene en50318_with(std::vector<std::string> overrides) {
  std::vector<scene::InputOverride> parsed;
  for (const auto& o : overrides)
    parsed.push_back(scene::parse_override(o, {"", "test --set " + o}));
  return scene::load_run_scene(
      scene::load_composed(std::string(PCSIM_SOURCE_DIR) + "/runs/en50318-300.yaml", parsed));
}

double head_load(const std::vector<std::string>& extra) {
  std::vector<std::string> overrides = {"pantographs[0].model.aerodynamic={a: 10, b: 0.2, c: 0.01}",
                                        "pantographs[0].effects={aerodynamic: true}"};
  overrides.insert(overrides.end(), extra.begin(), extra.end());
  auto run = en50318_with(overrides);
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

// The cross-wind's force and the head's deflection for a wind of 'speed' at
// 'direction' degrees, CdA 0.6 m^2, k_y 4e4 N/m.
contact::PantographRun cross_wind(double speed, double direction) {
  auto run = en50318_with({"conditions.wind={speed: " + std::to_string(speed) +
                               ", direction_deg: " + std::to_string(direction) + "}",
                           "pantographs[0].cross_wind={drag_area: 0.6, lateral_stiffness: 4e4}"});
  return run.pantographs.at(0);
}

TEST(WindOnPantograph, ACrossWindPushesTheHeadAside) {
  const double rho = 1.25, cda = 0.6, k = 4e4;
  // Across towards +y: F = rho CdA V^2 / 2 = 0.375 * 900 = 337.5 N, 8.4375 mm.
  const auto across = cross_wind(30, 90);
  EXPECT_TRUE(across.cross_wind);
  EXPECT_NEAR(across.cross_wind_force, 0.5 * rho * cda * 900, 1e-9);
  EXPECT_NEAR(across.head_lateral_offset, 0.5 * rho * cda * 900 / k, 1e-15);
  // Towards -y the force and the deflection change sign.
  const auto back = cross_wind(30, 270);
  EXPECT_NEAR(back.cross_wind_force, -across.cross_wind_force, 1e-9);
  // At 30 deg to the track only V sin(30 deg) = 15 m/s acts across (the
  // cross-flow principle): a quarter of the force.
  EXPECT_NEAR(cross_wind(30, 30).cross_wind_force, 0.25 * across.cross_wind_force, 1e-9);
  // Along the track, none; without the key, nothing either.
  EXPECT_NEAR(cross_wind(30, 0).cross_wind_force, 0.0, 1e-9);
  const auto without = en50318_with({"conditions.wind={speed: 30}"}).pantographs.at(0);
  EXPECT_FALSE(without.cross_wind);
  EXPECT_EQ(without.head_lateral_offset, 0.0);
}

}  // namespace
