// Residuals and exact tangents of the pantograph models against central finite
// differences (thesis 3.3.3), kinematic derivatives of the closed loops (A.4–A.5), and
// the static equilibrium (2.12–2.14) against a general Newton solve.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "pcsim/pantograph/dsa380.hpp"
#include "pcsim/pantograph/lumped.hpp"
#include "pcsim/scene/pantograph_reader.hpp"

using namespace pcsim::pantograph;
using namespace pcsim::scene;

namespace {

const std::string kModels = std::string(PCSIM_SOURCE_DIR) + "/meshes/pantographs/";

std::unique_ptr<PantographModel> load(const std::string& file, const std::string& effects) {
  if (effects.empty()) return load_pantograph_model(kModels + file, nullptr, 83.33);
  const auto e = pcsim::scene::InputNode::load_string(effects, "effects.yaml");
  return load_pantograph_model(kModels + file, &e, 83.33);
}

double max_rel(const Eigen::MatrixXd& exact, const Eigen::MatrixXd& fd) {
  return (exact - fd).cwiseAbs().maxCoeff() / std::max(1e-300, exact.cwiseAbs().maxCoeff());
}

// Checks dR/dq, dR/dq̇, dR/dq̈ at (q, q̇, q̈) by central differences.
void check_tangents(const PantographModel& m, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                    const Eigen::VectorXd& qdd, double hq, double hv, double tol) {
  const int n = m.dof_count();
  Eigen::MatrixXd Kq(n, n), Cq(n, n), Mq(n, n);
  m.tangents(0.3, q, qd, qdd, Kq, Cq, Mq);
  Eigen::MatrixXd Kfd(n, n), Cfd(n, n), Mfd(n, n);
  Eigen::VectorXd Rp(n), Rm(n);
  for (int j = 0; j < n; ++j) {
    Eigen::VectorXd a = q, b = q;
    a[j] += hq;
    b[j] -= hq;
    m.residual(0.3, a, qd, qdd, Rp);
    m.residual(0.3, b, qd, qdd, Rm);
    Kfd.col(j) = (Rp - Rm) / (2 * hq);
    a = qd, b = qd;
    a[j] += hv;
    b[j] -= hv;
    m.residual(0.3, q, a, qdd, Rp);
    m.residual(0.3, q, b, qdd, Rm);
    Cfd.col(j) = (Rp - Rm) / (2 * hv);
    a = qdd, b = qdd;
    a[j] += 1e-3;
    b[j] -= 1e-3;
    m.residual(0.3, q, qd, a, Rp);
    m.residual(0.3, q, qd, b, Rm);
    Mfd.col(j) = (Rp - Rm) / 2e-3;
  }
  EXPECT_LE(max_rel(Kq, Kfd), tol) << "dR/dq\n" << Kq << "\nFD\n" << Kfd;
  if (Cq.cwiseAbs().maxCoeff() > 0 || Cfd.cwiseAbs().maxCoeff() > 0)
    EXPECT_LE(max_rel(Cq, Cfd), tol) << "dR/dqd\n" << Cq << "\nFD\n" << Cfd;
  EXPECT_LE(max_rel(Mq, Mfd), tol) << "dR/dqdd\n" << Mq << "\nFD\n" << Mfd;
  // mass() is the tangents' dR/dq̈ (the same arithmetic: equal), and R is affine in q̈:
  // R(q̈) - R(0) = M q̈ to rounding (1e-12 of |R(q̈)| + |R(0)|; a term quadratic in q̈
  // would leave its own size).
  Eigen::MatrixXd Mm(n, n);
  m.mass(0.3, q, qd, Mm);
  EXPECT_EQ(max_rel(Mq, Mm), 0.0) << "mass()\n" << Mm << "\ntangents\n" << Mq;
  Eigen::VectorXd R0(n), R1(n);
  m.residual(0.3, q, qd, Eigen::VectorXd::Zero(n), R0);
  m.residual(0.3, q, qd, qdd, R1);
  const double scale = R0.cwiseAbs().maxCoeff() + R1.cwiseAbs().maxCoeff();
  EXPECT_LE((R1 - R0 - Mq * qdd).cwiseAbs().maxCoeff(), 1e-12 * scale) << "R not affine in qdd";
}

struct State {
  Eigen::VectorXd q, qd, qdd;
};

// A perturbed state near the working equilibrium, with the frame rising or descending.
State dsa_state(PantographModel& m, double frame_rate) {
  State s;
  s.q = m.static_equilibrium(120.0, 1.2);
  s.q += Eigen::Vector4d(0.02, 0.01, -0.015, 0.03);
  s.qd = Eigen::Vector4d(frame_rate, -0.2, 0.35, 0.4);
  s.qdd = Eigen::Vector4d(-1.5, 2.0, 3.0, -4.0);
  return s;
}

}  // namespace

TEST(PantographJet, LoopDerivativesMatchFiniteDifferences) {
  const auto p =
      load_dsa380_parameters(pcsim::scene::InputNode::load_file(kModels + "dsa380_rigid.yaml"));
  const double th = 0.65, h = 1e-5;
  const auto k0 = dsa380_kinematics(p, th);
  const auto kp = dsa380_kinematics(p, th + h), km = dsa380_kinematics(p, th - h);
  ASSERT_TRUE(k0.assembled);
  auto check = [&](const Jet& j0, const Jet& jp, const Jet& jm, int order, const char* what) {
    for (int k = 0; k < order; ++k) {
      const double fd = (jp[k] - jm[k]) / (2 * h);
      EXPECT_NEAR(j0[k + 1], fd, 1e-6 * (1 + std::abs(fd))) << what << " order " << k + 1;
    }
  };
  check(k0.y5, kp.y5, km.y5, 3, "y5");
  check(k0.x5, kp.x5, km.x5, 3, "x5");
  check(k0.theta2, kp.theta2, km.theta2, 3, "theta2");
  check(k0.theta6, kp.theta6, km.theta6, 3, "theta6");
  check(k0.damper_length, kp.damper_length, km.damper_length, 3, "l_a");
  check(k0.inertia, kp.inertia, km.inertia, 2, "a(theta)");
  check(k0.gravity_energy, kp.gravity_energy, km.gravity_energy, 3, "Vg");
  // Loop closure (A.1) holds.
  EXPECT_NEAR(std::hypot(k0.x4[0] - k0.x3[0], k0.y4[0] - k0.y3[0]), p.L3, 1e-12);
  EXPECT_NEAR(std::hypot(k0.x5[0] - k0.xj[0], k0.y5[0] - k0.yj[0]), p.L6, 1e-12);
  // (A.4) with the known slip fixed: J = dθ3/dθ solves the lower-loop velocity system.
  const double J = k0.theta3[1], K = k0.theta2[1];
  EXPECT_NEAR(
      -p.L1 * std::sin(th) + p.L2 * K * std::sin(k0.theta2[0]) + p.L3 * J * std::sin(k0.theta3[0]),
      0.0, 1e-12);
}

TEST(PantographTangents, LumpedEn50318) {
  auto m = load("en50318_two_mass.yaml", "aerodynamic: true");
  EXPECT_TRUE(m->is_linear());
  const Eigen::Vector2d q(0.01, -0.02), qd(0.3, -0.1), qdd(2.0, 1.0);
  check_tangents(*m, q, qd, qdd, 1e-6, 1e-6, 1e-6);
  Eigen::VectorXd R(2);
  m->residual(0, q, qd, qdd, R);
  // Head row: m1 q̈1 + c1 (q̇1 − q̇2) + k1 (q1 − q2).
  EXPECT_NEAR(R[0], 7.2 * 2.0 + 10 * 0.4 + 4200 * 0.03, 1e-9);
  EXPECT_NEAR(R[1], 15.0 * 1.0 + 10 * -0.4 + 90 * -0.1 + 4200 * -0.03 + 50 * -0.02 - 120, 1e-9);
}

TEST(PantographTangents, Dsa380Plain) {
  auto m = load("dsa380_rigid.yaml", "");
  auto s = dsa_state(*m, 0.3);
  check_tangents(*m, s.q, s.qd, s.qdd, 1e-6, 1e-6, 1e-6);
}

TEST(PantographTangents, Dsa380AllEffectsRising) {
  auto m = load("dsa380_rigid.yaml",
                "friction: {force: 10, kt: 5.0e-3}\ndamper: {one_way: true, quadratic: 800}\n"
                "aerodynamic: true\n");
  auto s = dsa_state(*m, 0.3);
  check_tangents(*m, s.q, s.qd, s.qdd, 1e-6, 1e-7, 1e-6);
}

TEST(PantographTangents, Dsa380AllEffectsDescending) {
  auto m = load("dsa380_rigid.yaml",
                "friction: {force: 10, kt: 5.0e-4}\ndamper: {one_way: true, quadratic: 800}\n");
  auto s = dsa_state(*m, -0.3);
  s.qd[2] = -0.3 * 1.0;  // relative head–frame velocity of a few mm/s
  check_tangents(*m, s.q, s.qd, s.qdd, 1e-6, 1e-8, 1e-6);
}

TEST(PantographTangents, Dsa380Restraints) {
  for (const char* r : {"head_restraint: rotation", "head_restraint: horizontal"}) {
    auto m = load("dsa380_rigid.yaml", r);
    auto s = dsa_state(*m, 0.25);
    check_tangents(*m, s.q, s.qd, s.qdd, 1e-6, 1e-6, 1e-6);
  }
}

TEST(PantographTangents, Dsa380HeadWithOffsetCentreOfGravity) {
  auto p =
      load_dsa380_parameters(pcsim::scene::InputNode::load_file(kModels + "dsa380_rigid.yaml"));
  p.LG[6] = 0.12;
  p.thetaG[6] = -M_PI / 2;
  p.kl3 = 2e5;
  Dsa380Pantograph m(p, Dsa380Effects{}, 0.0);
  auto s = dsa_state(m, 0.3);
  check_tangents(m, s.q, s.qd, s.qdd, 1e-6, 1e-6, 1e-6);
}

// Moving base (issue 25): the inertial load a_b Σ m_i ∂z_i/∂q depends on θ and θ7; a
// large a_b (3 g) and an offset head centre of gravity make its tangent count.
TEST(PantographTangents, Dsa380MovingBase) {
  const BaseMotion base{[](double t) { return 0.01 * t; }, [](double) { return 0.01; },
                        [](double) { return 29.4; }};
  auto m = load("dsa380_rigid.yaml", "damper: {quadratic: 800}");
  m->set_base_motion(base);
  auto s = dsa_state(*m, 0.3);
  check_tangents(*m, s.q, s.qd, s.qdd, 1e-6, 1e-6, 1e-6);
  auto p =
      load_dsa380_parameters(pcsim::scene::InputNode::load_file(kModels + "dsa380_rigid.yaml"));
  p.LG[6] = 0.12;
  p.thetaG[6] = -M_PI / 3;
  for (auto restraint : {Dsa380Effects::HeadRestraint::none, Dsa380Effects::HeadRestraint::rotation,
                         Dsa380Effects::HeadRestraint::horizontal}) {
    Dsa380Effects e;
    e.head_restraint = restraint;
    Dsa380Pantograph offset(p, e, 0.0);
    offset.set_base_motion(base);
    auto so = dsa_state(offset, 0.3);
    check_tangents(offset, so.q, so.qd, so.qdd, 1e-6, 1e-6, 1e-6);
  }
}

TEST(PantographStatics, TwoStepMatchesGeneralNewton) {
  for (const char* eff : {"", "head_restraint: rotation", "head_restraint: horizontal"}) {
    auto base = load("dsa380_rigid.yaml", eff);
    auto& m = dynamic_cast<Dsa380Pantograph&>(*base);
    const double F0 = 120, h0 = 1.2;
    const Eigen::VectorXd q0 = m.static_equilibrium(F0, h0);
    // Contact height and head descent (2.12–2.13).
    EXPECT_NEAR(q0[2] + m.contact_offset(), h0, 1e-12);
    const auto k = dsa380_kinematics(m.parameters(), q0[0]);
    EXPECT_NEAR(k.y5[0] - q0[2], m.head_descent(F0), 1e-10);
    // Bellows torque equals the closed formula (2.14).
    EXPECT_NEAR(m.bellows_torque(), m.bellows_torque_formula(q0, F0),
                1e-9 * std::abs(m.bellows_torque()));
    // Full residual vanishes with the contact force added.
    Eigen::VectorXd R(4);
    const Eigen::VectorXd z = Eigen::VectorXd::Zero(4);
    m.residual(0, q0, z, z, R);
    R[2] += F0;
    EXPECT_LT(R.norm(), 1e-8);
    // General Newton from a distant start returns to the same q0.
    Eigen::VectorXd start = q0 + Eigen::Vector4d(0.05, 0.02, -0.03, 0.02);
    const Eigen::VectorXd qn = m.solve_static(F0, start);
    EXPECT_LT((qn - q0).cwiseAbs().maxCoeff(), 1e-9) << qn.transpose() << " vs " << q0.transpose();
  }
}

// The bellows' torque change with the rigid mechanism's kinematics given by
// the caller (the DSA-380's residual and tangents pass theirs) is the one it
// computes itself, bit for bit, over the working range.
TEST(PantographBellows, GivenKinematicsGiveTheSameTorque) {
  auto base = load("dsa380_rigid.yaml", "uplift_characteristic: true");
  auto& m = dynamic_cast<Dsa380Pantograph&>(*base);
  const Eigen::VectorXd q0 = m.static_equilibrium(120, 1.2);
  const Dsa380Parameters& p = m.parameters();
  Bellows bellows(p.bellows, true, 0.0);
  bellows.set_reference(p, q0[0], 120, 1.2);
  for (double dtheta : {-0.05, -0.01, 0.0, 0.02, 0.06}) {
    const double theta = q0[0] + dtheta;
    const auto k = dsa380_kinematics(p, theta);
    double d_own = 0, d_given = 0;
    const double own = bellows.torque_change(p, theta, &d_own);
    const double given = bellows.torque_change(p, theta, &d_given, &k);
    EXPECT_EQ(own, given) << "dtheta " << dtheta;
    EXPECT_EQ(d_own, d_given) << "dtheta " << dtheta;
    if (dtheta != 0) EXPECT_NE(own, 0.0);  // the characteristic acts
  }
}

TEST(PantographStatics, LumpedEquilibriumSetsHeight) {
  auto m = load("en50318_two_mass.yaml", "");
  const Eigen::VectorXd q0 = m->static_equilibrium(120.0, 5.3);
  Eigen::VectorXd R(2);
  const Eigen::VectorXd z = Eigen::VectorXd::Zero(2);
  m->residual(0, q0, z, z, R);
  R[0] += 120.0;
  EXPECT_LT(R.norm(), 1e-10);
  EXPECT_NEAR(q0[0] + m->contact_offset(), 5.3, 1e-12);
  // The uplift (120 N) balances the contact force: the frame spring is unloaded.
  EXPECT_NEAR(q0[1], 0.0, 1e-12);
  EXPECT_NEAR(q0[0], -120.0 / 4200.0, 1e-12);
}

TEST(PantographInput, UnknownEffectIsRejected) {
  try {
    load("dsa380_rigid.yaml", "frictoin: {force: 3}");
    FAIL() << "accepted an unknown key";
  } catch (const pcsim::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("frictoin"), std::string::npos);
  }
  EXPECT_THROW(load("en50318_two_mass.yaml", "head_restraint: rotation"), pcsim::InputError);
}

TEST(PantographEffects, AerodynamicForceLiftsHeadAndCostsNothingWhenOff) {
  auto p =
      load_dsa380_parameters(pcsim::scene::InputNode::load_file(kModels + "dsa380_rigid.yaml"));
  p.aero_a = 5;
  p.aero_b = 0.1;
  p.aero_c = 0.004;
  const double v = 300 / 3.6, Fa = 5 + 0.1 * v + 0.004 * v * v;
  Dsa380Effects on;
  on.aerodynamic = true;
  Dsa380Pantograph with(p, on, v), without(p, Dsa380Effects{}, v);
  const Eigen::VectorXd q0 = without.static_equilibrium(120.0, 1.2);
  Eigen::VectorXd Ra(4), Rb(4);
  const Eigen::VectorXd qd = Eigen::Vector4d(0.1, 0.2, 0.3, 0.4), z = Eigen::VectorXd::Zero(4);
  with.set_bellows_torque(without.bellows_torque());
  with.residual(0, q0, qd, z, Ra);
  without.residual(0, q0, qd, z, Rb);
  EXPECT_NEAR(Ra[2] - Rb[2], -Fa, 1e-12);  // upward force on the head
  EXPECT_NEAR((Ra - Rb).norm(), Fa, 1e-12);
  // With the aerodynamic lift the head hangs less: smaller descent z (2.12).
  EXPECT_LT(with.head_descent(120.0), without.head_descent(120.0));
  EXPECT_NEAR(with.power(0, q0, qd).external - without.power(0, q0, qd).external, Fa * qd[2],
              1e-12);
}
