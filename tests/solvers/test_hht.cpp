// HHT-α TS type "hht" (thesis 3.3.2): equality with PETSc's TSALPHA2 configured as HHT,
// order of accuracy, high-frequency spectral radius, step rejection, energy-norm test.

#include <gtest/gtest.h>
#include <petscts.h>

#include <Eigen/Dense>
#include <cmath>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <vector>

#include "hht_test_models.hpp"
#include "pcsim/core/error.hpp"
#include "pcsim/solvers/hht.hpp"

using namespace hht_models;

namespace {

// Initial acceleration exactly as PETSc 3.18's TSALPHA2 starts (TSAlpha_Restart in
// src/ts/impls/implicit/alpha/alpha2.c): two steps of its (alpha_m, alpha_f, gamma, beta) =
// (1, 1, 1, 1/2) scheme with h = dt/2 -- a scheme independent of the acceleration it starts
// from -- then the one-sided difference A0 = (-3 V0 + 4 V1 - V2) / h of that code.
VectorXd alpha2_start_acceleration(const Model& model, const VectorXd& u0, const VectorXd& v0,
                                   double dt) {
  TsRun be(model, TSALPHA2, u0, v0, dt / 2);
  be.direct_solver(false);
  PCSIM_PETSC(TSAlpha2SetParams(be.ts, 1, 1, 1, 0.5));
  be.solve_steps(2);
  return (-3 * be.v[0] + 4 * be.v[1] - be.v[2]) / (dt / 2);
}

}  // namespace

// (a) Linear system: HHT equals TSALPHA2 with alpha_m = 1, alpha_f = 1-α, γ = 1/2+α,
// β = (1+α)²/4. TSALPHA2 evaluates F at the interpolated state (t_n + (1-α)Δt, U_α, V_α,
// A_{n+1}); for F linear in (U, V) and a load affine in t this equals our averaged forces
// (1-α) F_{n+1} + α F_n exactly, so the trajectories agree to round-off. (A load that is not
// affine in t, e.g. a sine, would make them differ by O(Δt²) per step.)
TEST(HHT, LinearChainEqualsAlpha2ConfiguredAsHHT) {
  const Chain chain;
  const Model model = chain.model();
  VectorXd u0(3), v0(3);
  u0 << 0.01, -0.02, 0.03;
  v0 << 0.1, 0.0, -0.2;
  const double dt = 0.01, alpha = 0.1;
  const int steps = 200;
  const VectorXd a0 = alpha2_start_acceleration(model, u0, v0, dt);

  // Newton + LU for both: TSALPHA2 takes V_{n+1} from the last residual evaluation, which
  // SNESKSPONLY makes before its update (stale V), so it needs a Newton that re-evaluates.
  TsRun ref(model, TSALPHA2, u0, v0, dt);
  ref.direct_solver(false);
  PCSIM_PETSC(
      TSAlpha2SetParams(ref.ts, 1.0, 1.0 - alpha, 0.5 + alpha, 0.25 * (1 + alpha) * (1 + alpha)));
  ref.solve_steps(steps);

  TsRun hht(model, pcsim::solvers::kTSHHT, u0, v0, dt);
  hht.direct_solver(false);
  pcsim::solvers::hht_set_alpha(hht.ts, alpha);
  Vec A0;
  PCSIM_PETSC(VecDuplicate(hht.U, &A0));
  from_eigen(a0, A0);
  pcsim::solvers::hht_set_initial_acceleration(hht.ts, A0);
  PCSIM_PETSC(VecDestroy(&A0));
  hht.solve_steps(steps);

  ASSERT_EQ(ref.u.size(), static_cast<size_t>(steps + 1));
  ASSERT_EQ(hht.u.size(), ref.u.size());
  const double su = max_abs(ref.u), svel = max_abs(ref.v);
  double eu = 0, ev = 0;
  for (size_t i = 0; i < ref.u.size(); ++i) {
    EXPECT_NEAR(hht.t[i], ref.t[i], 1e-12);
    eu = std::max(eu, (hht.u[i] - ref.u[i]).cwiseAbs().maxCoeff());
    ev = std::max(ev, (hht.v[i] - ref.v[i]).cwiseAbs().maxCoeff());
  }
  EXPECT_LT(eu / su, 1e-10) << "max |dU| = " << eu;
  EXPECT_LT(ev / svel, 1e-10) << "max |dV| = " << ev;
  // The motion is not trivial (the comparison is meaningful).
  EXPECT_GT(su, 0.05);
}

// The initial acceleration solved by the TS equals M^{-1}(f - C v0 - K u0): the run with it
// coincides with a run given that exact acceleration.
TEST(HHT, ComputedInitialAccelerationIsConsistent) {
  const Chain chain;
  const Model model = chain.model();
  VectorXd u0(3), v0(3);
  u0 << 0.01, -0.02, 0.03;
  v0 << 0.1, 0.0, -0.2;
  const VectorXd a_exact = chain.M.inverse() * (chain.f0 - chain.C * v0 - chain.K * u0);
  TsRun computed(model, pcsim::solvers::kTSHHT, u0, v0, 0.01);
  computed.solve_steps(50);
  TsRun given(model, pcsim::solvers::kTSHHT, u0, v0, 0.01);
  Vec A0;
  PCSIM_PETSC(VecDuplicate(given.U, &A0));
  from_eigen(a_exact, A0);
  pcsim::solvers::hht_set_initial_acceleration(given.ts, A0);
  PCSIM_PETSC(VecDestroy(&A0));
  given.solve_steps(50);
  for (size_t i = 0; i < given.u.size(); ++i)
    EXPECT_LT((computed.u[i] - given.u[i]).norm(), 1e-11 * max_abs(given.u));
}

// Fitted slope of log(error at t_end) against log(Δt) for the damped pendulum with mass
// variation mu; the reference is RK4 with a step 1/1000 of the finest HHT step.
double observed_order(double mu, const char* prefix = nullptr) {
  const double c = 0.1, k = 4.0, t_end = 4.0;
  const Model model = nonlinear_pendulum(c, k, mu);
  const VectorXd u0 = VectorXd::Constant(1, 1.5), v0 = VectorXd::Constant(1, 0.3);
  // Reference: RK4 on u' = v, v' = -(c v + k sin u)/(1 + mu sin² u).
  auto rhs = [&](const Eigen::Vector2d& y) {
    const double s = std::sin(y(0));
    return Eigen::Vector2d(y(1), -(c * y(1) + k * s) / (1 + mu * s * s));
  };
  Eigen::Vector2d y(u0(0), v0(0));
  const int n_ref = 800000;
  const double h = t_end / n_ref;
  for (int i = 0; i < n_ref; ++i) {
    const Eigen::Vector2d k1 = rhs(y), k2 = rhs(y + 0.5 * h * k1), k3 = rhs(y + 0.5 * h * k2),
                          k4 = rhs(y + h * k3);
    y += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
  }
  std::vector<double> log_dt, log_err;
  for (double dt : {0.04, 0.02, 0.01, 0.005}) {
    TsRun run(model, pcsim::solvers::kTSHHT, u0, v0, dt, prefix);
    if (prefix) PCSIM_PETSC(TSSetFromOptions(run.ts));
    run.direct_solver(false, 1e-13);
    run.solve_until(t_end);
    EXPECT_NEAR(run.t.back(), t_end, 1e-12);
    const double err = std::hypot(run.u.back()(0) - y(0), run.v.back()(0) - y(1));
    log_dt.push_back(std::log(dt));
    log_err.push_back(std::log(err));
  }
  const double n = log_dt.size();
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (size_t i = 0; i < log_dt.size(); ++i) {
    sx += log_dt[i];
    sy += log_err[i];
    sxx += log_dt[i] * log_dt[i];
    sxy += log_dt[i] * log_err[i];
  }
  std::cout << "[ measured ] mu=" << mu << (prefix ? " (options " : "") << (prefix ? prefix : "")
            << (prefix ? ")" : "") << ": error at dt=0.005 " << std::exp(log_err.back());
  const double slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  std::cout << ", slope " << slope << "\n";
  return slope;
}

// (b) Observed order 2 on a nonlinear (large-amplitude, damped) pendulum.
TEST(HHT, SecondOrderOnNonlinearOscillator) {
  const double slope = observed_order(0.0);
  EXPECT_GT(slope, 1.9);
  EXPECT_LT(slope, 2.1);
}

// With configuration-dependent mass, the thesis form (inertia M(U_{n+1}) A_{n+1}) loses an
// order: A_{n+1} approximates the acceleration at t_{n+1} - αΔt but multiplies the mass at
// t_{n+1}. Averaging the inertia like the other forces restores order 2.
TEST(HHT, AveragedInertiaIsSecondOrderWithConfigurationDependentMass) {
  PCSIM_PETSC(PetscOptionsSetValue(nullptr, "-avg_ts_hht_average_inertia", "1"));
  const double slope_averaged = observed_order(0.5, "avg_");
  PCSIM_PETSC(PetscOptionsClearValue(nullptr, "-avg_ts_hht_average_inertia"));
  const double slope_thesis = observed_order(0.5);
  EXPECT_GT(slope_averaged, 1.9);
  EXPECT_LT(slope_averaged, 2.1);
  EXPECT_LT(slope_thesis, 1.5);  // the reason the option exists
}

// For a constant mass both inertia forms are the same method.
TEST(HHT, AveragedInertiaEqualsThesisFormForConstantMass) {
  const Model model = nonlinear_pendulum(0.1, 4.0, 0.0);
  TsRun thesis(model, pcsim::solvers::kTSHHT, VectorXd::Constant(1, 1.2),
               VectorXd::Constant(1, 0.0), 0.02);
  thesis.direct_solver(false, 1e-13);
  thesis.solve_steps(100);
  PCSIM_PETSC(PetscOptionsSetValue(nullptr, "-avgc_ts_hht_average_inertia", "1"));
  TsRun averaged(model, pcsim::solvers::kTSHHT, VectorXd::Constant(1, 1.2),
                 VectorXd::Constant(1, 0.0), 0.02, "avgc_");
  PCSIM_PETSC(TSSetFromOptions(averaged.ts));
  PCSIM_PETSC(PetscOptionsClearValue(nullptr, "-avgc_ts_hht_average_inertia"));
  averaged.direct_solver(false, 1e-13);
  averaged.solve_steps(100);
  ASSERT_EQ(thesis.u.size(), averaged.u.size());
  for (size_t i = 0; i < thesis.u.size(); ++i) EXPECT_NEAR(thesis.u[i](0), averaged.u[i](0), 1e-11);
}

// The step Jacobian the TS hands to its SNES (I2Jacobian with the HHT shifts, plus α/(1-α)
// M(U_n)/(βΔt²) for averaged inertia) matches finite differences of the step residual, on a
// model with configuration-dependent mass and damping.
TEST(HHT, StepJacobianMatchesFiniteDifferences) {
  for (const char* average : {"0", "1"}) {
    PCSIM_PETSC(PetscOptionsSetValue(nullptr, "-fdj_ts_hht_average_inertia", average));
    TsRun run(nonlinear_pendulum(0.7, 4.0, 0.5), pcsim::solvers::kTSHHT, VectorXd::Constant(1, 1.1),
              VectorXd::Constant(1, 0.4), 0.05, "fdj_");
    PCSIM_PETSC(TSSetFromOptions(run.ts));
    PCSIM_PETSC(PetscOptionsClearValue(nullptr, "-fdj_ts_hht_average_inertia"));
    run.direct_solver(false);
    run.solve_steps(3);  // the step data (U_n, V_n, A_n, Δt) of step 3 stay in place
    SNES snes = run.snes();
    Vec X, F;
    Mat J;
    PCSIM_PETSC(VecDuplicate(run.U, &X));
    PCSIM_PETSC(VecDuplicate(run.U, &F));
    PCSIM_PETSC(SNESGetJacobian(snes, &J, nullptr, nullptr, nullptr));
    for (double x : {0.9, 1.3}) {
      PCSIM_PETSC(VecSet(X, x));
      PCSIM_PETSC(SNESComputeJacobian(snes, X, J, J));
      PetscScalar jac;
      PetscInt zero = 0;
      PCSIM_PETSC(MatGetValues(J, 1, &zero, 1, &zero, &jac));
      const double h = 1e-6;
      double r[2];
      for (int k = 0; k < 2; ++k) {
        PCSIM_PETSC(VecSet(X, x + (k ? -h : h)));
        PCSIM_PETSC(SNESComputeFunction(snes, X, F));
        r[k] = to_eigen(F)(0);
      }
      const double fd = (r[0] - r[1]) / (2 * h);
      EXPECT_NEAR(jac, fd, 1e-6 * std::abs(jac)) << "average_inertia=" << average;
    }
    PCSIM_PETSC(VecDestroy(&X));
    PCSIM_PETSC(VecDestroy(&F));
  }
}

// The initial acceleration solved with a configuration-dependent mass M(U0).
TEST(HHT, ComputedInitialAccelerationWithConfigurationDependentMass) {
  const double c = 0.7, k = 4.0, mu = 0.5, u0 = 1.1, v0 = 0.4;
  const double a_exact = -(c * v0 + k * std::sin(u0)) / (1 + mu * std::pow(std::sin(u0), 2));
  const Model model = nonlinear_pendulum(c, k, mu);
  TsRun computed(model, pcsim::solvers::kTSHHT, VectorXd::Constant(1, u0),
                 VectorXd::Constant(1, v0), 0.01);
  computed.direct_solver(false, 1e-13);
  computed.solve_steps(20);
  TsRun given(model, pcsim::solvers::kTSHHT, VectorXd::Constant(1, u0), VectorXd::Constant(1, v0),
              0.01);
  given.direct_solver(false, 1e-13);
  Vec A0;
  PCSIM_PETSC(VecDuplicate(given.U, &A0));
  PCSIM_PETSC(VecSet(A0, a_exact));
  pcsim::solvers::hht_set_initial_acceleration(given.ts, A0);
  PCSIM_PETSC(VecDestroy(&A0));
  given.solve_steps(20);
  for (size_t i = 0; i < given.u.size(); ++i) EXPECT_NEAR(computed.u[i](0), given.u[i](0), 1e-12);
}

// After the state is replaced from outside at the same time, hht_recompute_initial_acceleration
// makes the next step start like a fresh run from that state.
TEST(HHT, RecomputeInitialAccelerationAfterExternalChange) {
  const Model model = nonlinear_pendulum(0.2, 4.0, 0.5);
  TsRun run(model, pcsim::solvers::kTSHHT, VectorXd::Constant(1, 1.0), VectorXd::Constant(1, 0.0),
            0.05);
  run.direct_solver(false, 1e-13);
  run.solve_steps(4);
  PetscReal t;
  PCSIM_PETSC(TSGetTime(run.ts, &t));
  PCSIM_PETSC(VecSet(run.U, 0.3));
  PCSIM_PETSC(VecSet(run.V, -0.5));
  pcsim::solvers::hht_recompute_initial_acceleration(run.ts);
  run.solve_steps(7);
  TsRun fresh(model, pcsim::solvers::kTSHHT, VectorXd::Constant(1, 0.3),
              VectorXd::Constant(1, -0.5), 0.05);
  fresh.direct_solver(false, 1e-13);
  PCSIM_PETSC(TSSetTime(fresh.ts, t));
  fresh.solve_steps(3);
  EXPECT_NEAR(run.u.back()(0), fresh.u.back()(0), 1e-12);
  EXPECT_NEAR(run.v.back()(0), fresh.v.back()(0), 1e-11);
  EXPECT_NEAR(run.t.back(), fresh.t.back(), 1e-14);
}

// (c) High-frequency spectral radius. For an undamped oscillator with ωΔt = 1e4 the one-step
// map of the free response acts on the state z = (u, Δt v, Δt² a); its columns are measured by
// one HHT step from each unit state, and its spectral radius must approach (1-α)/(1+α).
TEST(HHT, HighFrequencySpectralRadius) {
  const double dt = 1e-2, omega = 1e4 / dt;
  for (double alpha : {0.1, 0.3}) {
    Model m = duffing(0.0, omega * omega, 0.0);
    MatrixXd amp(3, 3);
    for (int j = 0; j < 3; ++j) {
      Eigen::Vector3d z = Eigen::Vector3d::Zero();
      z(j) = 1;
      TsRun run(m, pcsim::solvers::kTSHHT, VectorXd::Constant(1, z(0)),
                VectorXd::Constant(1, z(1) / dt), dt);
      run.direct_solver(true);
      pcsim::solvers::hht_set_alpha(run.ts, alpha);
      Vec A0;
      PCSIM_PETSC(VecDuplicate(run.U, &A0));
      PCSIM_PETSC(VecSet(A0, z(2) / (dt * dt)));
      pcsim::solvers::hht_set_initial_acceleration(run.ts, A0);
      PCSIM_PETSC(VecDestroy(&A0));
      run.solve_steps(1);
      ASSERT_EQ(run.u.size(), 2u);
      Vec A1;
      PCSIM_PETSC(VecDuplicate(run.U, &A1));
      pcsim::solvers::hht_get_acceleration(run.ts, A1);
      amp.col(j) << run.u[1](0), dt * run.v[1](0), dt * dt * to_eigen(A1)(0);
      PCSIM_PETSC(VecDestroy(&A1));
    }
    const double rho = amp.eigenvalues().cwiseAbs().maxCoeff();
    std::cout << "[ measured ] alpha=" << alpha << ": spectral radius " << rho << " (expected "
              << (1 - alpha) / (1 + alpha) << ")\n";
    EXPECT_NEAR(rho, (1 - alpha) / (1 + alpha), 1e-3);
  }
}

// The free response decays by the same factor per step: over steps 200..400 of an undamped
// stiff oscillator the amplitude ratio per step is (1-α)/(1+α) (the polynomial factor of the
// nearly double root is divided out by comparing equally long windows).
TEST(HHT, FreeResponseDecaysAtSpectralRadius) {
  const double dt = 1e-2, omega = 1e4 / dt, alpha = 0.1;
  TsRun run(duffing(0.0, omega * omega, 0.0), pcsim::solvers::kTSHHT, VectorXd::Constant(1, 1.0),
            VectorXd::Constant(1, 0.0), dt);
  run.direct_solver(true);
  run.solve_steps(400);
  auto amplitude = [&](int i) { return std::abs(run.u[i](0)) + std::abs(run.u[i + 1](0)); };
  // amplitude(i) ~ C i ρ^i: eliminate i by using three points.
  const int a = 200, b = 300, c = 400 - 1;
  const double la = std::log(amplitude(a)), lb = std::log(amplitude(b)),
               lc = std::log(amplitude(c));
  // log A = log C + log i + i log ρ; solve for log ρ from the pair differences.
  const double log_rho_1 = (lb - la - std::log(double(b) / a)) / (b - a);
  const double log_rho_2 = (lc - lb - std::log(double(c) / b)) / (c - b);
  std::cout << "[ measured ] free-response decay per step " << std::exp(log_rho_1) << ", "
            << std::exp(log_rho_2) << " (expected " << (1 - alpha) / (1 + alpha) << ")\n";
  EXPECT_NEAR(std::exp(log_rho_1), (1 - alpha) / (1 + alpha), 1e-3);
  EXPECT_NEAR(std::exp(log_rho_2), (1 - alpha) / (1 + alpha), 1e-3);
}

// (d) Newton limited to 2 iterations fails on a stiff cubic spring at the user's Δt: the step is
// rejected, retried with Δt halved, the run completes, and Δt grows back once the motion has
// decayed (damped).
TEST(HHT, RejectedStepsAreRetriedWithSmallerStep) {
  const double dt = 0.05, t_end = 4.0;
  const Model model = duffing(2.0, 1.0, 1e4);
  TsRun run(model, pcsim::solvers::kTSHHT, VectorXd::Constant(1, 0.5), VectorXd::Constant(1, 0.0),
            dt);
  run.direct_solver(false, 1e-8, 2);
  run.solve_until(t_end);
  TSConvergedReason reason;
  PCSIM_PETSC(TSGetConvergedReason(run.ts, &reason));
  EXPECT_EQ(reason, TS_CONVERGED_TIME);
  EXPECT_NEAR(run.t.back(), t_end, 1e-12);
  PetscInt rejections = 0;
  PCSIM_PETSC(TSGetStepRejections(run.ts, &rejections));
  EXPECT_GT(rejections, 0);
  double dt_min = 1e30;
  for (size_t i = 1; i < run.t.size(); ++i) dt_min = std::min(dt_min, run.t[i] - run.t[i - 1]);
  std::cout << "[ measured ] rejections " << rejections << ", smallest accepted dt " << dt_min
            << ", accepted steps " << run.t.size() - 1 << "\n";
  EXPECT_LT(dt_min, 0.5 * dt + 1e-15);
  // Grown back: the last full steps (before the final one clipped to t_end) have the user's dt.
  ASSERT_GT(run.t.size(), 3u);
  EXPECT_NEAR(run.t[run.t.size() - 2] - run.t[run.t.size() - 3], dt, 1e-12);
  // Accuracy of the mixed-step run against a fixed small-step run with full Newton.
  TsRun fine(model, pcsim::solvers::kTSHHT, VectorXd::Constant(1, 0.5), VectorXd::Constant(1, 0.0),
             dt / 64);
  fine.direct_solver(false, 1e-12, 50);
  fine.solve_until(1.0);
  TsRun check(model, pcsim::solvers::kTSHHT, VectorXd::Constant(1, 0.5), VectorXd::Constant(1, 0.0),
              dt);
  check.direct_solver(false, 1e-8, 2);
  check.solve_until(1.0);
  EXPECT_NEAR(check.u.back()(0), fine.u.back()(0), 0.02 * 0.5);
}

// (d') When halving does not help within -ts_hht_max_reject, the TS stops with
// TS_DIVERGED_NONLINEAR_SOLVE.
TEST(HHT, GivesUpAfterMaxRejections) {
  TsRun run(duffing(0.0, 1.0, 1e4), pcsim::solvers::kTSHHT, VectorXd::Constant(1, 0.5),
            VectorXd::Constant(1, 0.0), 0.05);
  run.direct_solver(false, 1e-8, 1);
  PCSIM_PETSC(PetscOptionsSetValue(nullptr, "-giveup_ts_hht_max_reject", "2"));
  PCSIM_PETSC(TSSetOptionsPrefix(run.ts, "giveup_"));
  PCSIM_PETSC(TSSetFromOptions(run.ts));
  PCSIM_PETSC(PetscOptionsClearValue(nullptr, "-giveup_ts_hht_max_reject"));
  PCSIM_PETSC(TSSetErrorIfStepFails(run.ts, PETSC_FALSE));
  run.solve_steps(10);
  TSConvergedReason reason;
  PCSIM_PETSC(TSGetConvergedReason(run.ts, &reason));
  EXPECT_EQ(reason, TS_DIVERGED_NONLINEAR_SOLVE);
  EXPECT_EQ(pcsim::solvers::hht_get_info(run.ts).rejected_steps, 3);
  // No step accepted: time and solution untouched (TSSolve monitors once more at the end).
  EXPECT_EQ(run.t.back(), 0.0);
  EXPECT_EQ(run.u.back()(0), 0.5);
}

// (e) With the usual norms disabled (rtol = stol = 0, atol ~ 0) Newton only stops through the
// energy-norm test |Δqᵀ R| < tol; without it the same step fails at max_it.
TEST(HHT, EnergyNormTestStopsNewton) {
  const Model model = duffing(0.1, 1.0, 50.0);
  const VectorXd u0 = VectorXd::Constant(1, 0.8), v0 = VectorXd::Constant(1, 0.0);
  auto make = [&](double tol) {
    auto run = std::make_unique<TsRun>(model, pcsim::solvers::kTSHHT, u0, v0, 0.1);
    run->direct_solver(false, 0.0, 30);
    PCSIM_PETSC(SNESSetTolerances(run->snes(), 0.0, 0.0, 0.0, 30, 100000));
    if (tol > 0) pcsim::solvers::hht_set_energy_norm_tol(run->ts, tol);
    PCSIM_PETSC(TSSetErrorIfStepFails(run->ts, PETSC_FALSE));
    return run;
  };
  std::vector<PetscInt> iterations;
  for (double tol : {1e-6, 1e-20}) {
    auto run = make(tol);
    run->solve_steps(1);
    SNESConvergedReason reason;
    PetscInt its;
    PCSIM_PETSC(SNESGetConvergedReason(run->snes(), &reason));
    PCSIM_PETSC(SNESGetIterationNumber(run->snes(), &its));
    const auto info = pcsim::solvers::hht_get_info(run->ts);
    EXPECT_GT(reason, 0);
    EXPECT_TRUE(info.converged_by_energy);
    EXPECT_LT(info.last_energy_norm, tol);
    EXPECT_LT(its, 30);
    EXPECT_EQ(info.rejected_steps, 0);
    iterations.push_back(its);
  }
  EXPECT_LT(iterations[0], iterations[1]);  // looser energy tolerance, fewer iterations
  auto without = make(0.0);
  PCSIM_PETSC(TSSetOptionsPrefix(without->ts, "noenergy_"));
  PCSIM_PETSC(PetscOptionsSetValue(nullptr, "-noenergy_ts_hht_max_reject", "0"));
  PCSIM_PETSC(TSSetFromOptions(without->ts));
  PCSIM_PETSC(PetscOptionsClearValue(nullptr, "-noenergy_ts_hht_max_reject"));
  PCSIM_PETSC(SNESSetTolerances(without->snes(), 0.0, 0.0, 0.0, 30, 100000));
  without->solve_steps(1);
  SNESConvergedReason reason;
  PCSIM_PETSC(SNESGetConvergedReason(without->snes(), &reason));
  EXPECT_EQ(reason, SNES_DIVERGED_MAX_IT);
}

// -ts_type hht selects the type; -ts_hht_alpha sets α, γ and β follow (3.24); -ts_view prints
// them.
TEST(HHT, OptionsAndView) {
  pcsim::solvers::register_hht_ts();
  pcsim::solvers::register_hht_ts();  // idempotent
  PCSIM_PETSC(PetscOptionsSetValue(nullptr, "-opt_ts_type", "hht"));
  PCSIM_PETSC(PetscOptionsSetValue(nullptr, "-opt_ts_hht_alpha", "0.25"));
  PCSIM_PETSC(PetscOptionsSetValue(nullptr, "-opt_ts_hht_energy_norm_tol", "1e-7"));
  TsRun run(duffing(0.0, 1.0, 0.0), TSALPHA2, VectorXd::Constant(1, 1.0),
            VectorXd::Constant(1, 0.0), 0.1, "opt_");
  PCSIM_PETSC(TSSetFromOptions(run.ts));
  for (const char* o : {"-opt_ts_type", "-opt_ts_hht_alpha", "-opt_ts_hht_energy_norm_tol"})
    PCSIM_PETSC(PetscOptionsClearValue(nullptr, o));
  TSType type;
  PCSIM_PETSC(TSGetType(run.ts, &type));
  EXPECT_STREQ(type, "hht");
  PetscReal alpha, gamma, beta;
  pcsim::solvers::hht_get_params(run.ts, &alpha, &gamma, &beta);
  EXPECT_DOUBLE_EQ(alpha, 0.25);
  EXPECT_DOUBLE_EQ(gamma, 0.75);
  EXPECT_DOUBLE_EQ(beta, 1.25 * 1.25 / 4);
  run.solve_steps(3);
  const std::string path = "hht_view_test.txt";
  PetscViewer viewer;
  PCSIM_PETSC(PetscViewerASCIIOpen(PETSC_COMM_SELF, path.c_str(), &viewer));
  PCSIM_PETSC(TSView(run.ts, viewer));
  PCSIM_PETSC(PetscViewerDestroy(&viewer));
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  std::remove(path.c_str());
  EXPECT_NE(text.str().find("alpha=0.25, gamma=0.75, beta=0.390625"), std::string::npos)
      << text.str();
  EXPECT_NE(text.str().find("energy-norm tol=1e-07"), std::string::npos) << text.str();
  EXPECT_THROW(pcsim::solvers::hht_set_alpha(run.ts, 0.5), pcsim::SolverError);
}

// Rolling back a step and taking it again reproduces it exactly (state kept at setup).
TEST(HHT, RollBackReproducesStep) {
  TsRun run(nonlinear_pendulum(0.1, 4.0), pcsim::solvers::kTSHHT, VectorXd::Constant(1, 1.0),
            VectorXd::Constant(1, 0.0), 0.05);
  run.direct_solver(false);
  PCSIM_PETSC(TSSetMaxSteps(run.ts, 100));
  PCSIM_PETSC(TSSetUp(run.ts));
  PCSIM_PETSC(TSStep(run.ts));
  PCSIM_PETSC(TSStep(run.ts));
  const VectorXd u2 = to_eigen(run.U), v2 = to_eigen(run.V);
  PetscReal t2;
  PCSIM_PETSC(TSGetTime(run.ts, &t2));
  PCSIM_PETSC(TSRollBack(run.ts));
  PetscReal t1;
  PCSIM_PETSC(TSGetTime(run.ts, &t1));
  EXPECT_NEAR(t1, 0.05, 1e-15);
  EXPECT_NE(to_eigen(run.U)(0), u2(0));
  PCSIM_PETSC(TSStep(run.ts));
  EXPECT_EQ(to_eigen(run.U)(0), u2(0));
  EXPECT_EQ(to_eigen(run.V)(0), v2(0));
  PCSIM_PETSC(TSGetTime(run.ts, &t1));
  EXPECT_EQ(t1, t2);
}
