// Energy of the undamped coupled system (thesis 2.30-2.34 extended to the
// catenary): no Rayleigh damping, a two-mass pantograph without dampers
// (tests/contact/data/undamped_two_mass.yaml), linearised catenary, droppers
// with slack, penalty contact. The pantograph stands still (1e-6 m/s) and its
// uplift is released over 10 ms (ramp start): after that no external force does
// work and every force derives from a potential, so E = T + V of
// CoupledSystem::energy() (see its header for what is included) must
//  - stay constant with HHT alpha = 0 (the trapezoidal rule conserves the
//    energy of a linear system exactly). Left: the droppers' geometric
//    nonlinearity and the Newton residual of each step (the dynamic solver.s SNES
//    tolerances, |R| <= 1e-3 N; one exact linear solve leaves round-off), whose
//    work |R| |dU| over 500 steps is far below 1e-6 of the energy released
//    (3.4 J): tolerance 1e-6 relative (measured 4.9e-9);
//  - never exceed its value at the end of the ramp with alpha = 0.05, and end
//    lower. NOT step by step: HHT-alpha dissipates an algorithmic energy, and the
//    physical E oscillates around its decreasing trend (measured step increases
//    up to 3.0e-7 J = 8.8e-8 of the input, while E(t) - E(ramp end) stays
//    <= -8.6e-7 J); the criterion of the brief (steps non-increasing to 1e-9) is
//    therefore not a property of the method and is not tested.
// pcsim-test-ranks: 1 2
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "interaction_fixtures.hpp"

namespace {

using pcsim::testing::integrate;
using pcsim::testing::make_problem;
using pcsim::testing::scene_from_text;

struct EnergyHistory {
  std::vector<double> t, E, contact_force;
  PetscInt steps = 0;
};

EnergyHistory run_undamped(double alpha, bool dropper_slack, double duration) {
  auto run = scene_from_text(std::string(R"(
name: energy
catenary: {design: three-span.yaml}
pantographs:
  - {name: p, model: undamped_two_mass.yaml, start_x: 13.1, static_force: 120,
     start: ramp, ramp_distance: 1.0e-8}
simulation: {speed_kmh: 3.6e-6, end_x: 80}
analysis: {from_span: 2, to_span: 2}
effects: {catenary_nonlinear: false, rayleigh_damping: false, dropper_slack: )") +
                             (dropper_slack ? "true" : "false") + "}\n");
  auto problem = make_problem(run);
  Vec U0 = problem->create_vector(), V0 = problem->create_vector();
  problem->initial_state(U0, V0);
  EnergyHistory h;
  int rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  h.steps = integrate(
      *problem, U0, V0, 1e-3, duration, 100000,
      [&](TS ts) { pcsim::solvers::hht_set_alpha(ts, alpha); },
      [&](double t, Vec U, Vec V) {
        const double E = problem->energy(t, U, V);
        const auto rec = problem->record(t, U);
        h.t.push_back(t);
        h.E.push_back(E);
        h.contact_force.push_back(rank == 0 ? rec.contact_force[0] : 0.0);
      });
  VecDestroy(&U0);
  VecDestroy(&V0);
  return h;
}

// Index of the first sample after the 10 ms ramp.
std::size_t after_ramp(const EnergyHistory& h) {
  std::size_t i = 0;
  while (i < h.t.size() && h.t[i] < 0.01 + 1e-9) ++i;
  return i;
}

TEST(InteractionEnergy, ConservedWithTrapezoidalRule) {
  const auto h = run_undamped(0.0, true, 0.5);
  const std::size_t i0 = after_ramp(h);
  ASSERT_LT(i0 + 100, h.E.size());
  double max_drift = 0, min_force = 1e9, max_force = 0;
  for (std::size_t i = i0; i < h.E.size(); ++i)
    max_drift = std::max(max_drift, std::abs(h.E[i] - h.E[i0]));
  for (std::size_t i = i0; i < h.E.size(); ++i) {
    min_force = std::min(min_force, h.contact_force[i]);
    max_force = std::max(max_force, h.contact_force[i]);
  }
  const double scale = std::abs(h.E[i0] - h.E[0]);  // energy put in by the release
  PetscPrintf(PETSC_COMM_WORLD,
              "  alpha = 0: E(0) = %.6e J, E(ramp end) = %.6e J, max |E - E(ramp end)| = %.3e J "
              "(%.2e of the input), contact force %.1f..%.1f N\n",
              h.E[0], h.E[i0], max_drift, max_drift / scale, min_force, max_force);
  int rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (rank == 0) EXPECT_GT(min_force, 0.0);  // contact kept: the system stays linear
  EXPECT_GT(scale, 1.0);                     // the release does work (J)
  EXPECT_LT(max_drift, 1e-6 * scale);
}

TEST(InteractionEnergy, NeverAboveItsStartWithHhtDissipation) {
  const auto h = run_undamped(0.05, true, 0.5);
  const std::size_t i0 = after_ramp(h);
  ASSERT_LT(i0 + 100, h.E.size());
  const double scale = std::abs(h.E[i0] - h.E[0]);
  double max_increase = -1e300, max_above_start = -1e300;
  for (std::size_t i = i0 + 1; i < h.E.size(); ++i) {
    max_increase = std::max(max_increase, h.E[i] - h.E[i - 1]);
    max_above_start = std::max(max_above_start, h.E[i] - h.E[i0]);
  }
  PetscPrintf(PETSC_COMM_WORLD,
              "  alpha = 0.05: E(ramp end) = %.6e J, E(end) - E(ramp end) = %.3e J, "
              "max E(t) - E(ramp end) = %.3e J, largest step increase %.3e J (%.2e of the "
              "input, not asserted)\n",
              h.E[i0], h.E.back() - h.E[i0], max_above_start, max_increase, max_increase / scale);
  EXPECT_LT(max_above_start, 1e-9 * scale);       // round-off allowance
  EXPECT_LT(h.E.back(), h.E[i0] - 1e-6 * scale);  // measured drop 1.1e-5 of the input
}

}  // namespace

namespace {

// Energy balance E(t) - E(0) = W_ext(t) + W_diss(t) of a moving, damped run
// (Rayleigh damping, the damped EN 50318 two-mass pantograph, static start,
// the contact point moving at 100 km/h: its work is W_ext), the works
// integrated from the terms' powers by the trapezoidal rule. HHT alpha = 0
// (no algorithmic dissipation). Left: the trapezoidal quadrature of the
// powers against the scheme's own energy identity (O(dt^2)) and the Newton
// residual of each step. (A ramp start's power jumps to zero inside a step at
// the end of the ramp: its trapezoidal quadrature then errs by ~P dt/2,
// measured 1.8e-2 J, which is why the hard cases start their balance after
// the ramps.)
struct Balance {
  double max_error = 0, dissipated = 0, external = 0, turnover = 0;
};

Balance balance_run(bool nonlinear, double dt) {
  auto run = scene_from_text(std::string(R"(
name: balance
catenary: {design: three-span.yaml}
pantographs:
  - {name: p, model: )") + pcsim::testing::pantograph_model("en50318_two_mass.yaml") +
                             R"(, start_x: 13.1, static_force: 120, start: static}
simulation: {speed_kmh: 100, end_x: 80}
analysis: {from_span: 2, to_span: 2}
effects: {catenary_nonlinear: )" +
                             (nonlinear ? "true" : "false") +
                             ", rayleigh_damping: true, dropper_slack: true}\n");
  auto problem = make_problem(run);
  Vec U0 = problem->create_vector(), V0 = problem->create_vector();
  problem->initial_state(U0, V0);
  Balance b;
  double E0 = 0, t_prev = 0, w_ext = 0, w_diss = 0;
  pcsim::assembly::TermPower p_prev;
  integrate(
      *problem, U0, V0, dt, 0.3, 100000, [&](TS ts) { pcsim::solvers::hht_set_alpha(ts, 0.0); },
      [&](double t, Vec U, Vec V) {
        const double E = problem->energy(t, U, V);
        const auto p = problem->system().power(t, U, V);
        if (t == 0) {
          E0 = E;
        } else {
          w_ext += 0.5 * (t - t_prev) * (p.external + p_prev.external);
          w_diss += 0.5 * (t - t_prev) * (p.dissipative + p_prev.dissipative);
        }
        b.max_error = std::max(b.max_error, std::abs(E - E0 - w_ext - w_diss));
        b.turnover = std::max(b.turnover, std::abs(E - E0));
        t_prev = t;
        p_prev = p;
      });
  b.dissipated = w_diss;
  b.external = w_ext;
  VecDestroy(&U0);
  VecDestroy(&V0);
  return b;
}

TEST(InteractionEnergy, BalanceOfAMovingDampedRun) {
  for (bool nonlinear : {false, true}) {
    const auto b = balance_run(nonlinear, 1e-3), half = balance_run(nonlinear, 5e-4);
    PetscPrintf(PETSC_COMM_WORLD,
                "  %s catenary: W_ext %.4e J, W_diss %.4e J, max |E - E0| %.4e J, "
                "max |E - E0 - W| %.3e J (dt 1 ms), %.3e J (dt 0.5 ms)\n",
                nonlinear ? "nonlinear" : "linearised", b.external, b.dissipated, b.turnover,
                b.max_error, half.max_error);
    EXPECT_GT(std::abs(b.dissipated), 0.0);
    // Measured 1.6e-4 J = 6.7e-4 of the energy turnover at 1 ms, 3.6e-5 J at
    // 0.5 ms (ratio 4.5: the quadrature's second order). A missing power
    // (the moving contact's: 3e-2 J here) would break both bounds.
    EXPECT_LT(b.max_error, 1e-3 * b.turnover);
    EXPECT_LT(half.max_error, 0.3 * b.max_error);  // second order: 1/4
  }
}

}  // namespace
