// The uplift characteristic of the DSA-380 bellows (pantograph/bellows.hpp): the static
// contact force against the working height with the bellows torque following the curve
// (constant and tabulated, rigid and flexible models) and with the fixed torque; the
// tangents of the torque change and of the pressure loop against central differences;
// the power balance with the loop; and the loop's effect on the modes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "pcsim/pantograph/dsa380.hpp"
#include "pcsim/pantograph/flexible_dsa380.hpp"
#include "pcsim/pantograph/linear.hpp"
#include "pcsim/scene/flexible_dsa380_reader.hpp"
#include "pcsim/scene/pantograph_reader.hpp"
#include "pcsim/solvers/pantograph_modes.hpp"

using namespace pcsim::pantograph;

namespace {

const std::string kModels = std::string(PCSIM_SOURCE_DIR) + "/meshes/pantographs/";
constexpr double kF0 = 120.0, kH0 = 1.2;

Dsa380Parameters rigid_params(double time_constant = 0) {
  auto p = pcsim::scene::load_dsa380_parameters(
      pcsim::scene::InputNode::load_file(kModels + "dsa380_rigid.yaml"));
  p.bellows.time_constant = time_constant;
  p.bellows.valve_time_constant = time_constant > 0 ? 0.05 : 0.0;
  return p;
}

Dsa380Effects characteristic(bool on = true) {
  Dsa380Effects e;
  e.uplift_characteristic = on;
  return e;
}

// Static contact force with the contact point held at height h: Newton on
// R(q, 0, 0) + F e_c = 0 for q (without the contact coordinate) and F.
double static_force_at(const PantographModel& m, Eigen::VectorXd* start, double h) {
  const int n = m.dof_count(), c = m.contact_dof();
  Eigen::VectorXd& q = *start;
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
  Eigen::VectorXd R(n);
  Eigen::MatrixXd K(n, n), C(n, n), M(n, n);
  q[c] = h - m.contact_offset();
  double F = kF0, step = 1;
  for (int it = 0; it < 60; ++it) {
    m.residual(0, q, zero, zero, R);
    R[c] += F;
    // Converged: |R| at the rounding floor of the flexible model's stiff elements
    // (~1e-4 N, test_flexible_model) once the steps have vanished.
    if (R.norm() < 1e-9 * kF0 || (R.norm() < 1e-2 && step < 1e-12)) return F;
    m.tangents(0, q, zero, zero, K, C, M);
    K.col(c) = Eigen::VectorXd::Unit(n, c);  // dR/dF
    Eigen::VectorXd dz = K.partialPivLu().solve(-R);
    F += dz[c];
    dz[c] = 0;
    // At most 5 cm or 0.05 rad a step (the pressure loop's torque, in N m, is not limited).
    const int mechanism = m.dof_names().back() == "bellows_dM" ? n - 1 : n;
    step = dz.head(mechanism).cwiseAbs().maxCoeff();
    q += step > 0.05 ? (0.05 / step) * dz : dz;
  }
  ADD_FAILURE() << "static force at h = " << h << " did not converge, |R| = " << R.norm();
  return std::nan("");
}

// Largest |F(h)/F_curve(h) − 1| over h0 ± 0.1 m (every 2 cm), walking out from h0 so that
// each Newton solve starts from its neighbour's configuration.
template <class Curve>
double worst_deviation(const PantographModel& m, const Eigen::VectorXd& q0, Curve curve) {
  double worst = 0;
  for (double direction : {-1.0, 1.0}) {
    Eigen::VectorXd q = q0;
    for (int k = 0; k <= 5; ++k) {
      const double h = kH0 + direction * 0.02 * k;
      const double deviation = std::abs(static_force_at(m, &q, h) / curve(h) - 1);
      worst = std::isnan(deviation) ? deviation : std::max(worst, deviation);
    }
  }
  return worst;
}

double column_relative_error(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B) {
  double worst = 0;
  for (int j = 0; j < A.cols(); ++j) {
    const double scale = A.col(j).cwiseAbs().maxCoeff();
    if (scale > 0) worst = std::max(worst, (A.col(j) - B.col(j)).cwiseAbs().maxCoeff() / scale);
  }
  return worst;
}

// Largest column-relative error of dR/dq, dR/dq̇, dR/dq̈ against central differences.
double tangent_error(const PantographModel& m, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                     const Eigen::VectorXd& qdd) {
  const int n = m.dof_count();
  Eigen::MatrixXd K(n, n), C(n, n), M(n, n), Kfd(n, n), Cfd(n, n), Mfd(n, n);
  m.tangents(0, q, qd, qdd, K, C, M);
  Eigen::VectorXd Rp(n), Rm(n);
  const auto names = m.dof_names();
  for (int j = 0; j < n; ++j) {
    const Eigen::VectorXd e = Eigen::VectorXd::Unit(n, j);
    // The loop's torque (N m) enters R linearly, next to beam forces of ~1e5 N: a step of
    // 1e-6 would leave rounding of eps |R| / h ~ 1e-5 in its unit column.
    const double h = names[j] == "bellows_dM" ? 1e-3 : 1e-6;
    m.residual(0, q + h * e, qd, qdd, Rp);
    m.residual(0, q - h * e, qd, qdd, Rm);
    Kfd.col(j) = (Rp - Rm) / (2 * h);
    m.residual(0, q, qd + h * e, qdd, Rp);
    m.residual(0, q, qd - h * e, qdd, Rm);
    Cfd.col(j) = (Rp - Rm) / (2 * h);
    m.residual(0, q, qd, qdd + e, Rp);
    m.residual(0, q, qd, qdd - e, Rm);
    Mfd.col(j) = (Rp - Rm) / 2;
  }
  return std::max({column_relative_error(K, Kfd), column_relative_error(C, Cfd),
                   column_relative_error(M, Mfd)});
}

// q̇ᵀR − (d(T + V)/dt − P_ext − P_diss) along q + t q̇ + ½t² q̈, relative to d(T+V)/dt.
double power_balance_error(const PantographModel& m, const Eigen::VectorXd& q,
                           const Eigen::VectorXd& qd, const Eigen::VectorXd& qdd) {
  auto energy = [&](double t) {
    const Eigen::VectorXd qt = q + t * qd + 0.5 * t * t * qdd, qdt = qd + t * qdd;
    return m.kinetic_energy(qt, qdt) + m.potential_energy(qt);
  };
  auto central = [&](double h) { return (energy(h) - energy(-h)) / (2 * h); };
  const double rate = (4 * central(5e-6) - central(1e-5)) / 3;  // Richardson
  Eigen::VectorXd R(m.dof_count());
  m.residual(0, q, qd, qdd, R);
  const PowerSplit P = m.power(0, q, qd);
  return std::abs(qd.dot(R) - (rate - P.external - P.dissipative)) / std::abs(rate);
}

}  // namespace

TEST(UpliftCharacteristic, FixedTorqueLosesForceWithHeight) {
  Dsa380Pantograph m(rigid_params(), characteristic(false), 0.0);
  const Eigen::VectorXd q0 = m.static_equilibrium(kF0, kH0);
  Eigen::VectorXd q = q0;
  const double slope =
      (static_force_at(m, &q, kH0 + 1e-4) - static_force_at(m, &q, kH0 - 1e-4)) / 2e-4;
  std::printf("fixed bellows torque: dF/dh = %.1f N/m at h0\n", slope);
  // docs/interaction.md section 2 (interaction_static_curve.py): −2555 N/m.
  EXPECT_NEAR(slope, -2555, 5);
}

TEST(UpliftCharacteristic, RigidStaticForceIsF0AtEveryHeight) {
  for (double tau : {0.0, 0.5}) {  // at once, and through the pressure loop (statics alike)
    Dsa380Pantograph m(rigid_params(tau), characteristic(), 0.0);
    const Eigen::VectorXd q0 = m.static_equilibrium(kF0, kH0);
    const double worst = worst_deviation(m, q0, [](double) { return kF0; });
    std::printf("rigid, constant curve, tau %.1f s: max |F/F0 - 1| over h0 +- 0.1 m = %.1e\n", tau,
                worst);
    // (2.14) at every θ holds the frame with F0 exactly (symmetric head): rounding only,
    // measured 2.4e-13 (the requirement of issue 13 is 2 %).
    EXPECT_LT(worst, 1e-9);
  }
}

TEST(UpliftCharacteristic, RigidStaticForceFollowsATable) {
  Dsa380Parameters p = rigid_params();
  p.bellows.heights = {1.0, 1.15, 1.3, 1.5};
  p.bellows.forces = {50, 55, 70, 80};  // scaled by 120/60 through (h0, F0)
  Dsa380Pantograph m(p, characteristic(), 0.0);
  const Eigen::VectorXd q0 = m.static_equilibrium(kF0, kH0);
  const double worst =
      worst_deviation(m, q0, [&](double h) { return m.bellows().force(h, nullptr); });
  std::printf("rigid, table: max |F/F_table - 1| over h0 +- 0.1 m = %.1e; F(1.1) = %.3f N\n", worst,
              m.bellows().force(1.1, nullptr));
  EXPECT_NEAR(m.bellows().force(1.1, nullptr), 120.0 / 60.0 * (50 + 5 * 2.0 / 3.0), 1e-12);
  EXPECT_LT(worst, 1e-9);  // measured 2.8e-13: exact, as the constant curve
}

TEST(UpliftCharacteristic, FlexibleStaticForceWithinTwoPercent) {
  auto params = pcsim::scene::read_flexible_dsa380_file(kModels + "dsa380_flexible.yaml");
  params.rigid.bellows = rigid_params().bellows;
  FlexibleDsa380Pantograph m(params, characteristic(), 0.0);
  const Eigen::VectorXd q0 = m.static_equilibrium(kF0, kH0);
  const double worst = worst_deviation(m, q0, [](double) { return kF0; });
  std::printf("flexible, constant curve: max |F/F0 - 1| over h0 +- 0.1 m = %.2e\n", worst);
  // The torque change is the rigid mechanism's; the bars' deflection changes a little with
  // the frame angle: measured 2.5e-4. Issue 13: within 2 %; the bound keeps a margin of 4.
  EXPECT_LT(worst, 1e-3);
}

TEST(UpliftCharacteristic, TangentsMatchFiniteDifferences) {
  Dsa380Parameters table = rigid_params(0.5);
  table.bellows.heights = {1.0, 1.15, 1.3, 1.5};
  table.bellows.forces = {50, 55, 70, 80};
  struct Case {
    const char* name;
    Dsa380Parameters p;
  };
  for (const Case& c : {Case{"constant, at once", rigid_params()},
                        Case{"constant, loop", rigid_params(0.5)}, Case{"table, loop", table}}) {
    Dsa380Effects e = characteristic();
    e.damper_one_way = true;
    Dsa380Pantograph m(c.p, e, 0.0);
    Eigen::VectorXd q = m.static_equilibrium(kF0, kH0);
    const int n = m.dof_count();
    q.head<4>() += Eigen::Vector4d(0.03, 0.01, -0.015, 0.03);  // h ≈ 1.23 m, off the knots
    Eigen::VectorXd qd = Eigen::VectorXd::Constant(n, 0.2),
                    qdd = Eigen::VectorXd::Constant(n, -1.0);
    if (n == 5) q[4] = 35, qd[4] = 80, qdd[4] = -400;  // the loop's torque change (N m)
    const double err = tangent_error(m, q, qd, qdd);
    std::printf("rigid, %s: tangents vs central differences %.1e\n", c.name, err);
    // Measured 7.3e-8 (rounding of R over h = 1e-6 in the small head columns, as in
    // test_model_tangents); dropping the torque change's dF/dh term gives 3e-3.
    EXPECT_LT(err, 1e-6) << c.name;
  }
  auto params = pcsim::scene::read_flexible_dsa380_file(kModels + "dsa380_flexible.yaml");
  params.rigid.bellows = table.bellows;
  params.elements.fill(2);
  FlexibleDsa380Pantograph flex(params, characteristic(), 0.0);
  Eigen::VectorXd q = flex.static_equilibrium(kF0, kH0);
  const int n = flex.dof_count();
  q[0] += 0.03;
  q[n - 1] = 35;
  const Eigen::VectorXd qd = Eigen::VectorXd::Constant(n, 0.2),
                        qdd = Eigen::VectorXd::Constant(n, -1.0);
  const double err = tangent_error(flex, q, qd, qdd);
  std::printf("flexible, table, loop: tangents vs central differences %.1e\n", err);
  EXPECT_LT(err, 1e-6);  // measured 1.1e-8
}

TEST(UpliftCharacteristic, PowerBalanceWithThePressureLoop) {
  Dsa380Parameters p = rigid_params(0.5);
  Dsa380Pantograph m(p, characteristic(), 0.0);
  Eigen::VectorXd q = m.static_equilibrium(kF0, kH0);
  q += Eigen::Vector<double, 5>(0.03, 0.01, -0.015, 0.03, 35);
  const Eigen::VectorXd qd = Eigen::Vector<double, 5>(0.3, -0.2, 0.35, 0.4, 80);
  const Eigen::VectorXd qdd = Eigen::Vector<double, 5>(-1.5, 2.0, 3.0, -4.0, -400);
  const double err = power_balance_error(m, q, qd, qdd);
  std::printf("rigid with the pressure loop: power balance %.1e\n", err);
  // Measured 7e-11 (rounding of the energy over h, as test_flexible_model's 1e-12 ×
  // the loop's large ½ m² term).
  EXPECT_LT(err, 1e-9);
}

// Damped modes (2.27) of the pantograph alone about the equilibrium. The fixed torque's
// frame mode is 1.244 Hz (ζ 0.05). With the characteristic at once the frame has no static
// stiffness: it is neutral (λ = 0) and, with the damper, overdamped; the pressure loop
// keeps an oscillating frame mode near 1.24 Hz (the loop lags ΔM behind θ).
TEST(UpliftCharacteristic, LoopKeepsTheFrameModeAtOnceRemovesIt) {
  struct Row {
    const char* name;
    double tau;
    bool on;
    int frame_modes;  // oscillating modes between 1 and 1.5 Hz
  };
  for (const Row& r : {Row{"fixed torque", 0, false, 1}, Row{"loop 1 s", 1.0, true, 1},
                       Row{"loop 0.5 s", 0.5, true, 1}, Row{"at once", 0, true, 0}}) {
    Dsa380Pantograph m(rigid_params(r.tau), characteristic(r.on), 0.0);
    const LinearModel lin = linearise(m, m.static_equilibrium(kF0, kH0));
    int frame_modes = 0;
    double smallest_root = 1e300;
    for (const Mode& mode : pcsim::solvers::damped_modes_slepc(lin)) {
      std::printf("%-12s %s %.4g Hz  zeta %+.4f\n", r.name,
                  mode.real_root ? "real root" : "         ", mode.frequency_hz,
                  mode.damping_ratio);
      if (!mode.real_root && mode.frequency_hz > 1.0 && mode.frequency_hz < 1.5) ++frame_modes;
      if (mode.real_root) smallest_root = std::min(smallest_root, mode.frequency_hz);
    }
    EXPECT_EQ(frame_modes, r.frame_modes) << r.name;
    // Neutral frame: a zero root (measured below 3e-14 Hz, either sign: rounding).
    if (r.on) EXPECT_LT(smallest_root, 1e-9) << r.name;
  }
}
