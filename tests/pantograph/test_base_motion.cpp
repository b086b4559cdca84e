// Prescribed motion of the pantograph's base (issue 25) on the EN 50318 two-mass model:
// the base-to-head transmissibility against its closed form, the steady-state head
// amplitude of a time response (RK4) against |H(f)|, and the energy balance with the
// base's work.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>

#include "pcsim/pantograph/linear.hpp"
#include "pcsim/pantograph/lumped.hpp"
#include "pcsim/scene/pantograph_reader.hpp"
#include "pcsim/solvers/pantograph_time.hpp"

using namespace pcsim::pantograph;
using namespace pcsim::solvers;

namespace {
const std::string kTwoMass =
    std::string(PCSIM_SOURCE_DIR) + "/meshes/pantographs/en50318_two_mass.yaml";

// Two masses: head m1 on (k1, c1) over frame m2 on (k2, c2) over the base. With
// a_i = k_i + iωc_i: z1 / z_b = a1 a2 / [(a1 − ω² m1)(a1 + a2 − ω² m2) − a1²].
std::complex<double> two_mass_transmissibility(const LumpedParameters& p, double w) {
  const auto& head = p.stages[0];
  const auto& frame = p.stages[1];
  const std::complex<double> a1(head.stiffness, w * head.damping),
      a2(frame.stiffness, w * frame.damping);
  return a1 * a2 / ((a1 - w * w * head.mass) * (a1 + a2 - w * w * frame.mass) - a1 * a1);
}

std::unique_ptr<PantographModel> two_mass() {
  return pcsim::scene::load_pantograph_model(kTwoMass, nullptr, 0.0);
}

}  // namespace

// Both sides are exact arithmetic on a 2 x 2 system (LU vs the closed form): they agree
// to rounding, measured 1.0e-14 relative over 0.1-50 Hz;
// 1e-12 leaves room for another LU's rounding.
TEST(BaseMotion, TransmissibilityMatchesClosedForm) {
  auto model = two_mass();
  const Eigen::VectorXd q0 = model->static_equilibrium(120.0, 5.3);
  const LinearModel lin = linearise(*model, q0);
  const auto& p = dynamic_cast<const LumpedPantograph&>(*model).parameters();
  double worst = 0;
  for (int k = 0; k <= 200; ++k) {
    const double f = 0.1 * std::pow(500.0, k / 200.0), w = 2 * M_PI * f;
    const auto h = transmissibility_direct(lin, model->base_support(), 0, w);
    const auto exact = two_mass_transmissibility(p, w);
    worst = std::max(worst, std::abs(h - exact) / std::abs(exact));
  }
  RecordProperty("max_relative_difference", std::to_string(worst));
  std::printf("transmissibility vs closed form: max relative difference %.3e\n", worst);
  EXPECT_LT(worst, 1e-12);
  // Quasi-static limit: the whole pantograph follows its base.
  EXPECT_NEAR(std::abs(transmissibility_direct(lin, model->base_support(), 0, 1e-6)), 1.0, 1e-9);
}

// Base driven at A sin(2π f t) under a constant 120 N contact force from the static
// equilibrium: after 20 s (the slowest free motion, the overdamped frame's root
// −0.664 1/s, is down to e^{−13} ≈ 2e-6) the head's harmonic at f, projected over 25
// whole periods, is |H(f)| A. Measured relative differences 2.1e-10 (2 Hz), 6.0e-8 (5 Hz),
// 1.8e-7 (10 Hz): RK4's O((ω dt)^4) error; asserted 1e-6.
TEST(BaseMotion, SteadyHeadAmplitudeIsTransmissibilityTimesBaseAmplitude) {
  const double A = 0.002, dt = 1e-3;
  for (double f : {2.0, 5.0, 10.0}) {
    auto model = two_mass();
    const Eigen::VectorXd q0 = model->static_equilibrium(120.0, 5.3);
    const LinearModel lin = linearise(*model, q0);
    model->set_base_motion(harmonic_base_motion(A, f));
    TimeOptions opt;
    opt.scheme = "rk4";
    opt.dt = dt;
    const int per_period = static_cast<int>(std::lround(1 / (f * dt)));
    const int measured = 25 * per_period;
    opt.t_end = 20.0 + measured * dt;
    const auto h = integrate_pantograph(
        *model, q0, Eigen::VectorXd::Zero(2), [](double) { return 120.0; }, opt);
    const std::size_t first = h.t.size() - measured;
    std::complex<double> sum = 0;  // (2/N) Σ Δz e^{-iωt}
    for (std::size_t k = first; k < h.t.size(); ++k)
      sum += (h.q[k][0] - q0[0]) * std::exp(std::complex<double>(0, -2 * M_PI * f * h.t[k]));
    const double amplitude = 2.0 * std::abs(sum) / measured;
    const double expected =
        A * std::abs(transmissibility_direct(lin, model->base_support(), 0, 2 * M_PI * f));
    std::printf("f = %4.1f Hz: head amplitude %.6e m, |H| A = %.6e m, relative %.2e\n", f,
                amplitude, expected, std::abs(amplitude / expected - 1));
    EXPECT_NEAR(amplitude / expected, 1.0, 1e-6) << f << " Hz";
  }
}

// [T+V]_t − [T+V]_0 − W_diss − W_ext = 0 with the base's work (k z_b + c v_b) v_frame in
// W_ext; the balance is RK4's error only: measured 4.6e-9 J of a turnover of 0.75 J
// (6e-9), asserted 1e-7.
TEST(BaseMotion, EnergyBalanceCountsTheBaseWork) {
  auto model = two_mass();
  const Eigen::VectorXd q0 = model->static_equilibrium(120.0, 5.3);
  model->set_base_motion(harmonic_base_motion(0.002, 5.0));
  TimeOptions opt;
  opt.dt = 1e-3;
  opt.t_end = 5.0;
  const auto h = integrate_pantograph(
      *model, q0, Eigen::VectorXd::Zero(2), [](double) { return 120.0; }, opt);
  const auto b = h.energy_balance();
  double worst = 0, turnover = 0;
  for (std::size_t k = 0; k < b.size(); ++k) {
    worst = std::max(worst, std::abs(b[k]));
    turnover = std::max(turnover, std::abs(h.work_external[k]) + std::abs(h.work_dissipative[k]));
  }
  std::printf("base motion energy balance: max residual %.3e J of turnover %.3e J\n", worst,
              turnover);
  ASSERT_GT(turnover, 1e-3);
  EXPECT_LT(worst / turnover, 1e-7);
}
