// Conditions (docs/conditions.md): a heavy wire between two supports, built
// bare, then iced or at another temperature, against the elastic catenary
// with the FE's constitutive law (Green strain: T = EA lambda (lambda^2 - 1) / 2
// for the force T at stretch lambda), integrated numerically:
//  - fixed terminations: the span is held, the tension changes;
//  - a tensioning weight at one end: the pull is held, the end moves (and a
//    move beyond the device's travel is a warning).
// pcsim-test-ranks: 1 2 3
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "../assembly/catenary_fixtures.hpp"
#include "pcsim/simulation/statics.hpp"
#include "single_wire.hpp"

using namespace pcsim;

namespace {

constexpr double kSpan = test::kWireSpan, kMass = test::kWireMass, kEA = test::kWireEA;
constexpr double kIce = 0.5, kG = 9.81;
constexpr int kElements = test::kWireElements;

using test::GreenCatenary;
using test::single_wire_mesh;

// The right end held by a weight (released with the bare wire's pull).
void add_weight(catenary::CatenaryMesh& mesh, double travel) {
  catenary::TensioningDevice weight;
  weight.node = kElements;
  weight.wire = 0;
  weight.mass = 20000 / kG;
  weight.travel = travel;
  mesh.tensioning_devices.push_back(weight);
}

double mid_sag(const simulation::StaticConfiguration& c) {
  return -c.result.node_values[6 * (kElements / 2) + 2];  // node 60: s = L0 / 2 (symmetry)
}

}  // namespace

TEST(Ice, FixedTerminationsRaiseTheTension) {
  const double L0 = kSpan / (1 + 20000 / kEA);
  auto mesh = single_wire_mesh(L0);
  const auto bare = simulation::static_configuration(PETSC_COMM_WORLD, mesh, false);
  mesh.conditions.ice.contact = kIce;
  const auto iced = simulation::static_configuration(PETSC_COMM_WORLD, mesh, false);
  GreenCatenary before{20000, kMass * kG, L0}, after{20000, (kMass + kIce) * kG, L0};
  before.fit_span(kSpan);
  after.fit_span(kSpan);
  const double e_bare = std::abs(mid_sag(bare) / before.sag() - 1);
  const double e_iced = std::abs(mid_sag(iced) / after.sag() - 1);
  std::printf(
      "fixed ends: sag %.6f -> %.6f m (analytic %.6f -> %.6f), H %.1f -> %.1f N, "
      "relative errors %.2e %.2e\n",
      mid_sag(bare), mid_sag(iced), before.sag(), after.sag(), before.H, after.H, e_bare, e_iced);
  // The sag grows by 33 % (the tension by 3.2 %); achieved ~1e-7 (the
  // cubic elements and the SNES tolerance), bound 10 x that: a line without
  // its ice misses by 33 %, one iced with the pull held (a weight) by 3 %.
  EXPECT_LT(e_bare, 1e-6);
  EXPECT_LT(e_iced, 1e-6);
  EXPECT_EQ(iced.mesh.wires[0].mass_per_length, kMass + kIce);
}

TEST(Ice, TensioningWeightHoldsThePull) {
  const double L0 = kSpan / (1 + 20000 / kEA);
  auto mesh = single_wire_mesh(L0);
  add_weight(mesh, 0.0);
  const auto bare = simulation::static_configuration(PETSC_COMM_WORLD, mesh, false);
  mesh.conditions.ice.contact = kIce;
  const auto iced = simulation::static_configuration(PETSC_COMM_WORLD, mesh, false);
  // The pull the weight was released with is the bare wire's horizontal
  // force; iced, the same H over the same unstressed length.
  GreenCatenary before{20000, kMass * kG, L0};
  before.fit_span(kSpan);
  GreenCatenary after{before.H, (kMass + kIce) * kG, L0};
  const double end_x = iced.result.node_values[6 * kElements];
  const double e_iced = std::abs(mid_sag(iced) / after.sag() - 1);
  const double e_end = std::abs(end_x - after.span());
  std::printf(
      "weight: sag %.6f -> %.6f m (analytic %.6f), end at %.6f m (analytic %.6f), "
      "errors %.2e, %.2e m\n",
      mid_sag(bare), mid_sag(iced), after.sag(), end_x, after.span(), e_iced, e_end);
  // Achieved 1.1e-7 and 2e-9 m; bounds 10 x and 50 x that. With fixed ends
  // instead the sag is 3 % less; the end moves 3.2 mm towards the span.
  EXPECT_LT(e_iced, 1e-6);
  EXPECT_LT(e_end, 1e-7);
  EXPECT_LT(end_x, kSpan - 3e-3);
}

// dT = -30 K, fixed ends: the wire shortens by alpha dT (1.7e-5 /K, the
// default), the tension rises, the sag falls.
TEST(Temperature, FixedTerminationsTightenWhenCold) {
  const double L0 = kSpan / (1 + 20000 / kEA), dT = -30;
  auto mesh = single_wire_mesh(L0);
  mesh.conditions.temperature_change_k = dT;
  const auto cold = simulation::static_configuration(PETSC_COMM_WORLD, mesh, false);
  GreenCatenary before{20000, kMass * kG, L0};
  GreenCatenary after{20000, kMass * kG, L0 * (1 + catenary::kCopperThermalExpansion * dT)};
  before.fit_span(kSpan);
  after.fit_span(kSpan);
  const double e = std::abs(mid_sag(cold) / after.sag() - 1);
  std::printf(
      "cold, fixed ends: sag %.6f m (analytic %.6f, bare %.6f), H %.1f -> %.1f N "
      "(EA alpha dT %.1f N), error %.2e\n",
      mid_sag(cold), after.sag(), before.sag(), before.H, after.H,
      -kEA * catenary::kCopperThermalExpansion * dT, e);
  // Achieved ~1e-7 (as for ice); the sag falls by 25 % (H +34 %).
  EXPECT_LT(e, 1e-6);
  EXPECT_LT(after.sag(), 0.95 * before.sag());
}

// dT = +40 K, a weight: the pull is held, the end moves out by ~alpha dT L0
// (41 mm), beyond a travel of 30 mm: a warning names the device.
TEST(Temperature, WeightMovesAndRunsOutOfTravel) {
  const double L0 = kSpan / (1 + 20000 / kEA), dT = 40;
  auto mesh = single_wire_mesh(L0);
  add_weight(mesh, 0.03);
  mesh.conditions.temperature_change_k = dT;
  const auto warm = simulation::static_configuration(PETSC_COMM_WORLD, mesh, false);
  GreenCatenary before{20000, kMass * kG, L0};
  before.fit_span(kSpan);
  GreenCatenary after{before.H, kMass * kG, L0 * (1 + catenary::kCopperThermalExpansion * dT)};
  const double end_x = warm.result.node_values[6 * kElements];
  std::printf("warm, weight: end at %.6f m (analytic %.6f), travel %.1f mm, sag error %.2e\n",
              end_x, after.span(), 1e3 * warm.conditions.max_device_travel_m,
              std::abs(mid_sag(warm) / after.sag() - 1));
  EXPECT_LT(std::abs(end_x - after.span()), 1e-7);  // achieved ~1e-9 m
  EXPECT_LT(std::abs(mid_sag(warm) / after.sag() - 1), 1e-6);
  EXPECT_NEAR(warm.conditions.max_device_travel_m, end_x - kSpan, 1e-12);
  ASSERT_EQ(warm.result.warnings.size(), 1u);
  EXPECT_NE(warm.result.warnings[0].find("beyond its 30 mm (tensioning.travel)"), std::string::npos)
      << warm.result.warnings[0];
}

// A hold along the track at mid-span (a fixed support): the left half lies
// between the anchored end and the hold, no device: one warning.
TEST(Temperature, HeldStretchIsNamed) {
  auto mesh = single_wire_mesh(kSpan / (1 + 20000 / kEA));
  add_weight(mesh, 0.0);
  mesh.nodes[kElements / 2].fixed[0] = true;
  mesh.conditions.temperature_change_k = -20;
  const auto cold = simulation::static_configuration(PETSC_COMM_WORLD, mesh, false);
  ASSERT_EQ(cold.result.warnings.size(), 1u);
  EXPECT_NE(cold.result.warnings[0].find("1 of its stretches lie between supports that hold it"),
            std::string::npos)
      << cold.result.warnings[0];
  mesh.conditions.temperature_change_k = 0;  // no temperature change: no warning
  mesh.conditions.ice.contact = kIce;
  EXPECT_TRUE(
      simulation::static_configuration(PETSC_COMM_WORLD, mesh, false).result.warnings.empty());
}
