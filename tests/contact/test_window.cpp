// The moving window's matched ends (catenary/window.hpp, NodeDashpots in
// assembly/catenary_terms.hpp) on a taut wire (data/window-wire.yaml): the
// released ends and their dashpot, the coupled tangent against finite
// differences of the residual with the dashpots and a pin in, and the energy a pulse
// leaves behind when it runs out through an end: the string's reflection
// coefficient r = (Z - c_d) / (Z + c_d) for a dashpot c_d on a string of
// impedance Z = sqrt(T rho), reflected energy r^2.
// pcsim-test-ranks: 1 2
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "../assembly/interaction_fixtures.hpp"
#include "pcsim/assembly/fe_catenary.hpp"
#include "pcsim/catenary/window.hpp"
#include "pcsim/scene/design_reader.hpp"
#include "pcsim/simulation/statics.hpp"

namespace {

using namespace pcsim;
using pcsim::testing::contact_data;

struct Wire {
  std::unique_ptr<assembly::CoupledSystem> system;
  catenary::CatenaryMesh mesh;  // with the released ends
  std::vector<int> ends;
};

// The wire's coupled system (no pantograph, no damping) with its ends released
// and dashpots of impedance_factor x Z on them.
Wire make_wire(double impedance_factor) {
  auto design = scene::load_catenary_design(contact_data("window-wire.yaml"));
  auto st = simulation::static_configuration(PETSC_COMM_WORLD, design, true, "static_");
  Wire w;
  w.ends = catenary::release_window_ends(st.mesh, st.result.node_values, impedance_factor);
  w.mesh = st.mesh;
  auto fe =
      std::make_unique<assembly::FECatenary>(PETSC_COMM_WORLD, st.mesh, st.result.node_values, 0,
                                             catenary::CatenaryFidelity::linear, &st.node_owner);
  contact::InteractionEffects effects;
  effects.dropper_slack = false;
  effects.rayleigh_damping = false;
  w.system = std::make_unique<assembly::CoupledSystem>(
      std::move(fe), std::vector<assembly::PantographSlot>{}, effects, 5e4);
  return w;
}

const catenary::Wire& contact_wire(const Wire& w) {
  return w.mesh.wires[w.mesh.contact_wire];
}

double norm(Vec x) {
  PetscReal n;
  PCSIM_PETSC(VecNorm(x, NORM_2, &n));
  return n;
}

const assembly::DofLayout& layout(Wire& w) {
  return dynamic_cast<assembly::FECatenary&>(w.system->catenary()).system().layout();
}

// The window's shift map on the EN 50318 line (10 spans of 60 m, stagger
// alternating): every node has a partner two spans ahead at the same
// lateral and vertical design position, except those of the last two spans.
TEST(WindowShift, EveryNodeButTheLastTwoSpansHasAPartnerTwoSpansAhead) {
  const auto mesh =
      scene::load_catenary_design(std::string(PCSIM_SOURCE_DIR) + "/meshes/en50318-reference.yaml");
  const double shift = 120.0, x_last = mesh.support_x.back();
  const auto partner = catenary::shifted_nodes(mesh, shift);
  ASSERT_EQ(partner.size(), mesh.nodes.size());
  std::size_t with = 0;
  for (std::size_t n = 0; n < mesh.nodes.size(); ++n) {
    const Eigen::Vector3d& p = mesh.nodes[n].position;
    const bool expected = p.x() + shift <= x_last + 1e-6;
    ASSERT_EQ(partner[n] >= 0, expected) << "node " << n << " at x = " << p.x();
    if (partner[n] < 0) continue;
    ++with;
    const Eigen::Vector3d d = mesh.nodes[partner[n]].position - p;
    EXPECT_NEAR(d.x(), shift, 1e-6);
    EXPECT_NEAR(d.y(), 0.0, 1e-6);  // the stagger repeats every two spans
    EXPECT_NEAR(d.z(), 0.0, 1e-6);
  }
  // Every partner is used once: the map is one-to-one.
  std::vector<int> sorted;
  for (int m : partner)
    if (m >= 0) sorted.push_back(m);
  std::sort(sorted.begin(), sorted.end());
  EXPECT_EQ(std::unique(sorted.begin(), sorted.end()) - sorted.begin(), static_cast<long>(with));
  EXPECT_GT(with, mesh.nodes.size() * 7 / 10);  // 8 of 10 spans
}

TEST(WindowEnds, OnlyTheContactWireEndsAreReleasedWithItsImpedance) {
  Wire w = make_wire(1.0);
  // The messenger is held at every support of the line: its ends stay.
  ASSERT_EQ(w.ends.size(), 2u);
  const auto& cw = contact_wire(w);
  EXPECT_EQ(w.ends[0], cw.nodes.front());
  EXPECT_EQ(w.ends[1], cw.nodes.back());
  ASSERT_EQ(w.mesh.dashpots.size(), 2u);
  const double Z = std::sqrt(cw.tension * cw.mass_per_length / (1 + cw.tension / cw.EA));
  for (const auto& d : w.mesh.dashpots) {
    EXPECT_EQ(d.dof, 2);
    EXPECT_NEAR(d.coefficient, Z, 1e-12 * Z);  // T / c = sqrt(T rho_T)
    EXPECT_FALSE(w.mesh.nodes[d.node].fixed[2]);
  }
}

// J(sv, sa) d against the central difference of F along (d, sv d, sa d), and
// dF/dV on the two end DOFs alone: exactly c_d (no damping otherwise).
TEST(WindowEnds, TangentMatchesFiniteDifferences) {
  Wire w = make_wire(1.0);
  auto& sys = *w.system;
  Vec U = sys.create_vector(), V = sys.create_vector(), A = sys.create_vector();
  Vec d = sys.create_vector(), Jd = sys.create_vector(), Fp = sys.create_vector(),
      Fm = sys.create_vector();
  Vec Up, Vp, Ap;
  sys.catenary().reference_state(U);
  PetscRandom rng;
  PCSIM_PETSC(PetscRandomCreate(PETSC_COMM_WORLD, &rng));
  PCSIM_PETSC(PetscRandomSetInterval(rng, -1.0, 1.0));
  PCSIM_PETSC(PetscRandomSetSeed(rng, 77));
  PCSIM_PETSC(PetscRandomSeed(rng));
  PCSIM_PETSC(VecSetRandom(d, rng));
  PCSIM_PETSC(VecAXPY(U, 1e-4, d));
  PCSIM_PETSC(VecSetRandom(V, rng));
  PCSIM_PETSC(VecSetRandom(A, rng));
  PCSIM_PETSC(VecSetRandom(d, rng));
  for (Vec* v : {&Up, &Vp, &Ap}) PCSIM_PETSC(VecDuplicate(U, v));
  Mat J = sys.create_matrix();
  auto fd_error = [&](double sv, double sa, double wu, double h) {
    sys.jacobian(0.0, U, V, A, {sv, sa}, J);
    PCSIM_PETSC(MatMult(J, d, Jd));
    for (int side = 0; side < 2; ++side) {
      const double s = side == 0 ? h : -h;
      PCSIM_PETSC(VecWAXPY(Up, s * wu, d, U));
      PCSIM_PETSC(VecWAXPY(Vp, s * sv, d, V));
      PCSIM_PETSC(VecWAXPY(Ap, s * sa, d, A));
      sys.residual(0.0, Up, Vp, Ap, side == 0 ? Fp : Fm);
    }
    PCSIM_PETSC(VecAXPY(Fp, -1.0, Fm));
    PCSIM_PETSC(VecScale(Fp, 0.5 / h));
    PCSIM_PETSC(VecAXPY(Fp, -1.0, Jd));
    return norm(Fp) / norm(Jd);
  };
  // The terms are linear here (linearised cables, linear bars, dashpots): the
  // central difference is exact up to round-off, ~1e-16 |F| / (h |J d|) with
  // |F| ~ 1e4 N: below 1e-8 for h = 1e-4; the bound 1e-7 leaves a factor 10.
  const double e_step = fd_error(0.6 / 0.3025e-3, 1.0 / (0.3025e-6 * 0.9), 1.0, 1e-4);
  // dF/dV alone on the end DOFs: C d, C = c_d on each (|F| / (h c) ~ 1e4: the
  // round-off of the difference ~1e-16 x 1e4 / 1e-3 / 164 ~ 1e-11).
  PCSIM_PETSC(VecSet(d, 0.0));
  const auto& L = layout(w);
  for (const auto& dp : w.mesh.dashpots)
    if (L.owner(dp.node) == L.rank())
      PCSIM_PETSC(VecSetValue(d, L.global_dof(dp.node, dp.dof), 1.0, INSERT_VALUES));
  PCSIM_PETSC(VecAssemblyBegin(d));
  PCSIM_PETSC(VecAssemblyEnd(d));
  sys.jacobian(0.0, U, V, A, {1.0, 0.0}, J);
  PCSIM_PETSC(MatMult(J, d, Jd));
  Mat K = sys.create_matrix();
  sys.jacobian(0.0, U, V, A, {0.0, 0.0}, K);
  PCSIM_PETSC(MatMult(K, d, Fp));
  PCSIM_PETSC(VecAXPY(Jd, -1.0, Fp));  // (J(1, 0) - J(0, 0)) d = dF/dV d = C d
  const double c = w.mesh.dashpots.front().coefficient;
  EXPECT_NEAR(norm(Jd), c * std::sqrt(2.0), 1e-9 * c);
  const double h = 1e-3;  // F is linear in V: exact up to round-off
  PCSIM_PETSC(VecWAXPY(Vp, h, d, V));
  sys.residual(0.0, U, Vp, A, Fp);
  PCSIM_PETSC(VecWAXPY(Vp, -h, d, V));
  sys.residual(0.0, U, Vp, A, Fm);
  PCSIM_PETSC(VecAXPY(Fp, -1.0, Fm));
  PCSIM_PETSC(VecScale(Fp, 0.5 / h));
  PCSIM_PETSC(VecAXPY(Fp, -1.0, Jd));
  const double e_v = norm(Fp) / norm(Jd);
  PetscPrintf(PETSC_COMM_WORLD, "  rel. error HHT step %.2e, dF/dV at the ends %.2e\n", e_step,
              e_v);
  EXPECT_LT(e_step, 1e-7);
  EXPECT_LT(e_v, 1e-7);
  // The pin of the rear end, active: dF/dU along that DOF (the pin's k = 1e9
  // N/m dominates a random direction, so it is checked alone), and its row
  // holds k more than without it.
  auto& mesh = dynamic_cast<assembly::FECatenary&>(sys.catenary()).system().mutable_mesh();
  ASSERT_EQ(mesh.pins.size(), 2u);
  PCSIM_PETSC(VecSet(d, 0.0));
  const auto& rear = mesh.pins.front();
  const PetscInt g_rear = L.global_dof(rear.node, rear.dof);
  if (L.owner(rear.node) == L.rank()) PCSIM_PETSC(VecSetValue(d, g_rear, 1.0, INSERT_VALUES));
  PCSIM_PETSC(VecAssemblyBegin(d));
  PCSIM_PETSC(VecAssemblyEnd(d));
  mesh.pins.front().active = true;
  const double e_pin = fd_error(0.0, 0.0, 1.0, 1e-4);
  mesh.pins.front().active = false;
  sys.jacobian(0.0, U, V, A, {0.0, 0.0}, K);
  PCSIM_PETSC(MatMult(K, d, Fm));  // without the pin
  mesh.pins.front().active = true;
  sys.jacobian(0.0, U, V, A, {0.0, 0.0}, K);
  PCSIM_PETSC(MatMult(K, d, Jd));
  PCSIM_PETSC(VecAXPY(Jd, -1.0, Fm));  // k on the pinned DOF alone
  EXPECT_NEAR(norm(Jd), catenary::kPinStiffness, 1e-6 * catenary::kPinStiffness);
  PetscPrintf(PETSC_COMM_WORLD, "  rel. error dF/dU along the pinned DOF %.2e\n", e_pin);
  EXPECT_LT(e_pin, 1e-7);
  mesh.pins.front().active = false;
  for (Vec* v : {&U, &V, &A, &d, &Jd, &Fp, &Fm, &Up, &Vp, &Ap}) VecDestroy(v);
  MatDestroy(&J);
  MatDestroy(&K);
  PetscRandomDestroy(&rng);
}

// A right-running pulse z = a exp(-(x - x0)^2 / (2 s^2)), dz/dt = -c dz/dx,
// on the contact wire; the energy left in the wire (above the static
// configuration's) when it has run out through the right end, over the
// energy it started with.
double energy_left(double impedance_factor) {
  Wire w = make_wire(impedance_factor);
  auto& sys = *w.system;
  const auto& cw = contact_wire(w);
  const double c = catenary::wave_speed(cw), a = 1e-3, s = 1.5, x0 = 40.0;
  Vec U = sys.create_vector(), V = sys.create_vector(), Vs = sys.create_vector();
  sys.catenary().reference_state(U);
  PCSIM_PETSC(VecSet(Vs, 0.0));
  const double e_static = sys.energy(0.0, U, Vs);
  const auto& L = layout(w);
  for (int n : cw.nodes) {
    if (L.owner(n) != L.rank()) continue;
    const double x = w.mesh.nodes[n].position.x();
    const double f = a * std::exp(-0.5 * (x - x0) * (x - x0) / (s * s));
    const double df = -(x - x0) / (s * s) * f;
    const PetscInt gz = L.global_dof(n, 2), gs = L.global_dof(n, 5);
    if (gz >= 0) {
      PCSIM_PETSC(VecSetValue(U, gz, f, ADD_VALUES));
      PCSIM_PETSC(VecSetValue(V, gz, -c * df, INSERT_VALUES));
    }
    if (gs >= 0) PCSIM_PETSC(VecSetValue(U, gs, df, ADD_VALUES));
  }
  for (Vec v : {U, V}) {
    PCSIM_PETSC(VecAssemblyBegin(v));
    PCSIM_PETSC(VecAssemblyEnd(v));
  }
  const double e0 = sys.energy(0.0, U, V) - e_static;
  // Out through the right end (80 m + 4 s away) at 0.75 s; a reflection is
  // then still on the wire (back at the left end after 1.3 s).
  const double dt = 2.5e-4, duration = 0.75;
  solvers::DynamicSolver solver(sys, dt, duration);
  solver.set_initial_state(U, V);
  PCSIM_PETSC(TSSolve(solver.ts(), nullptr));
  Vec Ut, Vt;
  PCSIM_PETSC(TS2GetSolution(solver.ts(), &Ut, &Vt));
  const double e1 = sys.energy(duration, Ut, Vt) - e_static;
  for (Vec* v : {&U, &V, &Vs}) VecDestroy(v);
  return e1 / e0;
}

TEST(WindowEnds, MatchedDashpotAbsorbsAPulseAndAMismatchedOneReflectsR2) {
  const double matched = energy_left(1.0), half = energy_left(0.5), none = energy_left(0.0);
  const double r_half = (1.0 - 0.5) / (1.0 + 0.5);
  PetscPrintf(PETSC_COMM_WORLD,
              "  energy left: matched %.3e, half impedance %.4f (string: %.4f), no dashpot %.4f\n",
              matched, half, r_half * r_half, none);
  // Measured (1 and 2 ranks): matched 8.0e-7, half 0.1108 against 1/9, none
  // 0.9998. Without a dashpot the free end reflects everything (HHT alpha =
  // 0.1 takes 2e-4 from a pulse of ~40 elements per wavelength); the bending
  // stiffness and the discretisation leave the matched end ~1e-6. Bounds: a
  // factor ~10 on what is not absorbed, 1 % of r^2 for the mismatched end.
  EXPECT_GT(none, 0.999);
  EXPECT_NEAR(half, r_half * r_half, 1.1e-3);
  EXPECT_LT(matched, 1e-5);
}

}  // namespace
