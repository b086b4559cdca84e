// Unit tests of the catenary element kernels (thesis 3.1.1-3.1.2): gradients
// and tangents against finite differences, invariance, uniform stretch, mass,
// gravity and the Euler-Bernoulli cantilever.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <cmath>
#include <functional>
#include <random>
#include <string>

#include "pcsim/catenary/elements.hpp"

namespace pcsim::catenary {
namespace {

constexpr double kFdTolerance = 1e-6;

// Relative error ||a - b|| / max(||b||, floor).
template <class A, class B>
double relative_error(const A& a, const B& b, double floor) {
  return (a - b).norm() / std::max(b.norm(), floor);
}

template <int N>
Eigen::Matrix<double, N, 1> fd_gradient(
    const std::function<double(const Eigen::Matrix<double, N, 1>&)>& fun,
    const Eigen::Matrix<double, N, 1>& x, double h) {
  Eigen::Matrix<double, N, 1> g;
  for (int i = 0; i < N; ++i) {
    Eigen::Matrix<double, N, 1> xp = x, xm = x;
    xp(i) += h;
    xm(i) -= h;
    g(i) = (fun(xp) - fun(xm)) / (2 * h);
  }
  return g;
}

template <int N>
Eigen::Matrix<double, N, N> fd_jacobian(
    const std::function<Eigen::Matrix<double, N, 1>(const Eigen::Matrix<double, N, 1>&)>& fun,
    const Eigen::Matrix<double, N, 1>& x, double h) {
  Eigen::Matrix<double, N, N> J;
  for (int i = 0; i < N; ++i) {
    Eigen::Matrix<double, N, 1> xp = x, xm = x;
    xp(i) += h;
    xm(i) -= h;
    J.col(i) = (fun(xp) - fun(xm)) / (2 * h);
  }
  return J;
}

Eigen::Vector3d random_vector(std::mt19937& rng, double amplitude) {
  std::uniform_real_distribution<double> u(-amplitude, amplitude);
  return {u(rng), u(rng), u(rng)};
}

Eigen::Matrix3d some_rotation() {
  return (Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, -0.5).normalized()) *
          Eigen::AngleAxisd(-1.9, Eigen::Vector3d(-0.3, 0.4, 1).normalized()))
      .toRotationMatrix();
}

Vec12 rotate(const Eigen::Matrix3d& R, const Vec12& q) {
  Vec12 out;
  for (int k = 0; k < 4; ++k) out.segment<3>(3 * k) = R * q.segment<3>(3 * k);
  return out;
}

// A stretched, bent, 3D element configuration (Lref = 4.5 m).
struct CableCase {
  double Lref = 4.5;
  double L0 = 4.47;
  Vec12 q;
};

CableCase deformed_cable(unsigned seed) {
  std::mt19937 rng(seed);
  CableCase c;
  const Eigen::Vector3d t = Eigen::Vector3d(1.0, 0.2, -0.1).normalized();
  const Eigen::Vector3d ri = random_vector(rng, 3.0);
  const Eigen::Vector3d rj = ri + 1.01 * c.Lref * t + random_vector(rng, 0.15);
  c.q.segment<3>(0) = ri;
  c.q.segment<3>(3) = 1.02 * t + random_vector(rng, 0.08);
  c.q.segment<3>(6) = rj;
  c.q.segment<3>(9) = 0.99 * t + random_vector(rng, 0.08);
  return c;
}

// Axial only, bending only, comparable, realistic contact wire.
const CableSection kSections[] = {
    {1.0e5, 0.0, 1.0}, {0.0, 200.0, 1.0}, {1.0e4, 50.0, 1.0}, {1.44e7, 195.0, 1.35}};

TEST(CableElement, HermiteDerivativesMatchFiniteDifferences) {
  const double L = 3.7, h = 1e-5;
  for (double chi : {0.0, 0.4, 1.3, 2.9, 3.7}) {
    const HermiteValues v = hermite(chi, L), p = hermite(chi + h, L), m = hermite(chi - h, L);
    for (int k = 0; k < 4; ++k) {
      EXPECT_NEAR(v.ds[k], (p.s[k] - m.s[k]) / (2 * h), 1e-8) << "k=" << k << " chi=" << chi;
      EXPECT_NEAR(v.dds[k], (p.ds[k] - m.ds[k]) / (2 * h), 1e-8) << "k=" << k << " chi=" << chi;
    }
  }
  // Interpolation at the ends (eq. 3.3): r(0) = r_i, r'(0) = r'_i, r(L) = r_j, r'(L) = r'_j.
  const CableCase c = deformed_cable(3);
  const CablePoint a = cable_point(c.Lref, c.q, 0.0), b = cable_point(c.Lref, c.q, c.Lref);
  EXPECT_LT((a.r - c.q.segment<3>(0)).norm(), 1e-13);
  EXPECT_LT((a.r_chi - c.q.segment<3>(3)).norm(), 1e-13);
  EXPECT_LT((b.r - c.q.segment<3>(6)).norm(), 1e-13);
  EXPECT_LT((b.r_chi - c.q.segment<3>(9)).norm(), 1e-13);
}

TEST(CableElement, ForceIsGradientOfEnergy) {
  for (const CableSection& section : kSections) {
    for (unsigned seed : {1u, 2u}) {
      const CableCase c = deformed_cable(seed);
      Vec12 f;
      cable_internal_force(section, c.Lref, c.L0, c.q, f);
      const Vec12 fd = fd_gradient<12>(
          [&](const Vec12& x) { return cable_strain_energy(section, c.Lref, c.L0, x); }, c.q, 1e-6);
      EXPECT_LT(relative_error(f, fd, 1e-12), kFdTolerance)
          << "EA=" << section.EA << " EI=" << section.EI;
      EXPECT_GT(f.norm(), 0.0);
    }
  }
}

TEST(CableElement, TangentIsJacobianOfForceAndSymmetric) {
  for (const CableSection& section : kSections) {
    const CableCase c = deformed_cable(7);
    Vec12 f;
    Mat12 K;
    cable_internal_force(section, c.Lref, c.L0, c.q, f, &K);
    const Mat12 fd = fd_jacobian<12>(
        [&](const Vec12& x) {
          Vec12 fx;
          cable_internal_force(section, c.Lref, c.L0, x, fx);
          return fx;
        },
        c.q, 1e-6);
    EXPECT_LT(relative_error(K, fd, 1e-12), kFdTolerance)
        << "EA=" << section.EA << " EI=" << section.EI;
    EXPECT_LT((K - K.transpose()).norm(), 1e-10 * K.norm());
  }
}

TEST(CableElement, UnstressedLengthDerivativeMatchesFiniteDifferences) {
  for (const CableSection& section : kSections) {
    const CableCase c = deformed_cable(11);
    Vec12 f, df_dL0;
    cable_internal_force(section, c.Lref, c.L0, c.q, f, nullptr, &df_dL0);
    const double h = 1e-6;
    Vec12 fp, fm;
    cable_internal_force(section, c.Lref, c.L0 + h, c.q, fp);
    cable_internal_force(section, c.Lref, c.L0 - h, c.q, fm);
    const Vec12 fd = (fp - fm) / (2 * h);
    if (section.EA > 0) {
      EXPECT_LT(relative_error(df_dL0, fd, 1e-12), kFdTolerance) << "EA=" << section.EA;
    } else {
      EXPECT_EQ(df_dL0.norm(), 0.0);  // bending does not depend on L0
    }
  }
}

TEST(CableElement, MeanAxialForceGradientsMatchFiniteDifferences) {
  for (const CableSection& section : kSections) {
    if (section.EA == 0) continue;
    const CableCase c = deformed_cable(5);
    Vec12 dT_dq;
    double dT_dL0 = 0;
    cable_mean_axial_force(section, c.Lref, c.L0, c.q, &dT_dq, &dT_dL0);
    const Vec12 fd = fd_gradient<12>(
        [&](const Vec12& x) { return cable_mean_axial_force(section, c.Lref, c.L0, x); }, c.q,
        1e-6);
    EXPECT_LT(relative_error(dT_dq, fd, 1e-12), kFdTolerance) << "EA=" << section.EA;
    const double h = 1e-6;
    const double fd_L0 = (cable_mean_axial_force(section, c.Lref, c.L0 + h, c.q) -
                          cable_mean_axial_force(section, c.Lref, c.L0 - h, c.q)) /
                         (2 * h);
    EXPECT_LT(std::abs(dT_dL0 - fd_L0), kFdTolerance * std::abs(fd_L0)) << "EA=" << section.EA;
  }
}

TEST(CableElement, RigidBodyMotionIsStressFree) {
  const CableSection section = kSections[3];
  const double L = 6.0;
  const Eigen::Matrix3d R = some_rotation();
  const Eigen::Vector3d t = R * Eigen::Vector3d::UnitX();
  const Eigen::Vector3d ri(12.0, -3.0, 5.5);
  Vec12 q;
  q << ri, t, ri + L * t, t;
  Vec12 f;
  cable_internal_force(section, L, L, q, f);
  EXPECT_LT(f.norm(), 1e-9 * section.EA);
  EXPECT_LT(cable_strain_energy(section, L, L, q), 1e-20 * section.EA * L);
  EXPECT_LT(std::abs(cable_mean_axial_force(section, L, L, q)), 1e-9 * section.EA);

  // Energy and force of a deformed configuration are objective.
  const CableCase c = deformed_cable(9);
  const Vec12 q_rot = rotate(R, c.q);
  Vec12 shift = Vec12::Zero();
  for (int k : {0, 6}) shift.segment<3>(k) = Eigen::Vector3d(-4.0, 7.0, 1.5);
  const double energy = cable_strain_energy(section, c.Lref, c.L0, c.q);
  EXPECT_GT(energy, 0.0);
  EXPECT_NEAR(cable_strain_energy(section, c.Lref, c.L0, q_rot + shift), energy, 1e-11 * energy);
  Vec12 f0, f1;
  cable_internal_force(section, c.Lref, c.L0, c.q, f0);
  cable_internal_force(section, c.Lref, c.L0, q_rot + shift, f1);
  EXPECT_LT((f1 - rotate(R, f0)).norm(), 1e-11 * f0.norm());
}

TEST(CableElement, UniformStretchGivesEndForcesAndMeanTension) {
  const CableSection section = kSections[3];
  const double Lref = 5.0, L0 = 4.99, l = 5.02;
  const Eigen::Vector3d t = Eigen::Vector3d(0.8, -0.3, 0.2).normalized();
  const Eigen::Vector3d ri(1.0, 2.0, 3.0);
  Vec12 q;
  q << ri, (l / Lref) * t, ri + l * t, (l / Lref) * t;
  const double lambda = l / L0;
  const double T = section.EA * 0.5 * (lambda * lambda - 1.0) * lambda;
  Vec12 f;
  cable_internal_force(section, Lref, L0, q, f);
  EXPECT_LT((f.segment<3>(0) + T * t).norm(), 1e-10 * T);
  EXPECT_LT((f.segment<3>(6) - T * t).norm(), 1e-10 * T);
  EXPECT_LT(f.segment<3>(3).norm(), 1e-10 * T * Lref);
  EXPECT_LT(f.segment<3>(9).norm(), 1e-10 * T * Lref);
  EXPECT_NEAR(cable_mean_axial_force(section, Lref, L0, q), T, 1e-10 * T);
  for (double chi : {0.0, 1.1, 2.5, 5.0})
    EXPECT_LT((cable_point(Lref, q, chi).r - (ri + (chi * l / Lref) * t)).norm(), 1e-12);
}

TEST(CableElement, MassMatrixAndGravity) {
  const CableSection section{0.0, 0.0, 1.35};
  const double L = 4.5;
  const Mat12 M = cable_mass_matrix(section, L);
  EXPECT_LT((M - M.transpose()).norm(), 1e-14 * M.norm());
  const Eigen::Vector3d t = Eigen::Vector3d(0.3, -1.0, 0.6).normalized();
  Vec12 u = Vec12::Zero();
  u.segment<3>(0) = t;
  u.segment<3>(6) = t;
  EXPECT_NEAR(u.dot(M * u), section.mass_per_length * L, 1e-12);
  EXPECT_GT(Eigen::SelfAdjointEigenSolver<Mat12>(M).eigenvalues().minCoeff(), 0.0);

  // Closed forms against a composite Simpson integration of the shape functions.
  const int n = 2000;
  Eigen::Matrix4d m_num = Eigen::Matrix4d::Zero();
  Eigen::Vector4d s_num = Eigen::Vector4d::Zero();
  for (int i = 0; i <= n; ++i) {
    const double w = (i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0);
    const HermiteValues h = hermite(L * i / n, L);
    const Eigen::Vector4d s(h.s[0], h.s[1], h.s[2], h.s[3]);
    m_num += (w * L / (3.0 * n)) * s * s.transpose();
    s_num += (w * L / (3.0 * n)) * s;
  }
  for (int k = 0; k < 4; ++k)
    for (int j = 0; j < 4; ++j)
      EXPECT_NEAR(M(3 * k + 1, 3 * j + 1), section.mass_per_length * m_num(k, j), 1e-10);

  const Eigen::Vector3d g(0.0, 0.0, -9.81);
  const Vec12 fg = cable_gravity_force(section, L, g);
  const Eigen::Vector3d total = fg.segment<3>(0) + fg.segment<3>(6);
  EXPECT_LT((total - section.mass_per_length * L * g).norm(), 1e-12);
  for (int k = 0; k < 4; ++k)
    EXPECT_LT((fg.segment<3>(3 * k) - section.mass_per_length * s_num(k) * g).norm(), 1e-10);
  // Consistency: gravity is M applied to a uniform acceleration of the positions.
  Vec12 acc = Vec12::Zero();
  acc.segment<3>(0) = g;
  acc.segment<3>(6) = g;
  EXPECT_LT((M * acc - fg).norm(), 1e-12 * fg.norm());
}

// Wire::mass_per_length is per unstressed length (the wire as bought): an
// element stretched from L0 to its design length Lref weighs rho L0 g, and
// the wire's wave speed is sqrt(T / rho_T) with rho_T = rho / (1 + T/EA) the
// mass per stretched length (issue 12). Exact formulas: round-off margins.
TEST(CableElement, MassIsPerUnstressedLength) {
  Wire wire;
  wire.mass_per_length = 1.35, wire.EA = 1.44e7, wire.EI = 195.0, wire.tension = 20000.0;
  CableElement element;
  element.ref_length = 0.5;
  element.unstressed_length = 0.5 / (1.0 + wire.tension / wire.EA);
  const CableSection section = cable_section(wire, element);
  const Eigen::Vector3d g(0.0, 0.0, -9.81);
  const Vec12 fg = cable_gravity_force(section, element.ref_length, g);
  const Eigen::Vector3d total = fg.segment<3>(0) + fg.segment<3>(6);
  EXPECT_LT((total - wire.mass_per_length * element.unstressed_length * g).norm(), 1e-13);
  // 0.14 % lighter than the design length would make it (T/EA = 1.39e-3).
  EXPECT_NEAR(total.norm() / (wire.mass_per_length * element.ref_length * 9.81),
              1.0 / (1.0 + wire.tension / wire.EA), 1e-15);
  const double rho_stretched = wire.mass_per_length / (1.0 + wire.tension / wire.EA);
  EXPECT_NEAR(wave_speed(wire), std::sqrt(wire.tension / rho_stretched), 1e-12);
  // A worn element: the mass scales with the section left.
  element.section_factor = 0.8;
  EXPECT_NEAR(cable_section(wire, element).mass_per_length, 0.8 * section.mass_per_length, 1e-15);
}

TEST(CableElement, CantileverTipDeflectionIsEulerBernoulli) {
  // One element clamped at node i (r_i, r'_i fixed), tip load P at node j;
  // linear analysis with EA = 0: tip deflection P L^3/(3EI), rotation P L^2/(2EI).
  const CableSection section{0.0, 300.0, 1.0};
  const double L = 2.0, P = 50.0;
  const Eigen::Vector3d ex = Eigen::Vector3d::UnitX();
  Vec12 q;
  q << Eigen::Vector3d::Zero(), ex, L * ex, ex;
  Vec12 f;
  Mat12 K;
  cable_internal_force(section, L, L, q, f, &K);
  EXPECT_LT(f.norm(), 1e-12);
  const Mat6 K_free = K.block<6, 6>(6, 6);
  for (int dir : {1, 2}) {
    Vec6 load = Vec6::Zero();
    load(dir) = P;
    const Vec6 u = K_free.ldlt().solve(load);
    EXPECT_NEAR(u(dir), P * L * L * L / (3.0 * section.EI), 1e-12) << "dir " << dir;
    EXPECT_NEAR(u(3 + dir), P * L * L / (2.0 * section.EI), 1e-12) << "dir " << dir;
  }
}

// ------------------------------------------------------------------ bar ----

struct BarCase {
  const char* name;
  BarParameters bar;
  double length;  // current length
  bool active;    // stiff regime
};

Vec6 bar_configuration(double length) {
  const Eigen::Vector3d e = Eigen::Vector3d(0.2, -0.1, 1.0).normalized();
  const Eigen::Vector3d ri(3.0, 0.4, 5.1);
  Vec6 q;
  q << ri, ri + length * e;
  return q;
}

const BarCase kBarCases[] = {
    {"none stretched", {2.0e5, 1.2, SlackCriterion::none, 0, 0}, 1.25, true},
    {"none compressed", {2.0e5, 1.2, SlackCriterion::none, 0, 0}, 1.15, true},
    {"force active", {2.0e5, 1.2, SlackCriterion::force, 0, 0}, 1.25, true},
    {"force slack", {2.0e5, 1.2, SlackCriterion::force, 0, 0}, 1.15, false},
    {"length active", {2.0e5, 1.2, SlackCriterion::length, 1.22, 150.0}, 1.25, true},
    {"length slack", {2.0e5, 1.2, SlackCriterion::length, 1.22, 150.0}, 1.18, false},
};

TEST(BarElement, ForceTangentAndLengthDerivativeMatchFiniteDifferences) {
  for (const BarCase& c : kBarCases) {
    SCOPED_TRACE(c.name);
    const Vec6 q = bar_configuration(c.length);
    const double scale = c.bar.stiffness * c.bar.unstressed_length;  // force scale
    Vec6 f, df_dL0;
    Mat6 K;
    const double N = bar_internal_force(c.bar, q, f, &K, &df_dL0);
    const Vec6 fd_f =
        fd_gradient<6>([&](const Vec6& x) { return bar_strain_energy(c.bar, x); }, q, 1e-7);
    EXPECT_LT(relative_error(f, fd_f, 1e-3 * scale), kFdTolerance);
    const Mat6 fd_K = fd_jacobian<6>(
        [&](const Vec6& x) {
          Vec6 fx;
          bar_internal_force(c.bar, x, fx);
          return fx;
        },
        q, 1e-7);
    EXPECT_LT(relative_error(K, fd_K, 1e-3 * c.bar.stiffness), kFdTolerance);
    EXPECT_LT((K - K.transpose()).norm(), 1e-10 * std::max(K.norm(), 1.0));
    BarParameters p = c.bar, m = c.bar;
    const double h = 1e-7;
    p.unstressed_length += h;
    m.unstressed_length -= h;
    Vec6 fp, fm;
    bar_internal_force(p, q, fp);
    bar_internal_force(m, q, fm);
    EXPECT_LT(relative_error(df_dL0, Vec6((fp - fm) / (2 * h)), 1e-3 * c.bar.stiffness),
              kFdTolerance);

    // Axial force per criterion, and dN/dl.
    double dN_dl = -1;
    EXPECT_DOUBLE_EQ(bar_axial_force(c.bar, q, &dN_dl), N);
    EXPECT_DOUBLE_EQ(dN_dl, c.active ? c.bar.stiffness : 0.0);
    double expected = 0;
    switch (c.bar.slack) {
      case SlackCriterion::none:
        expected = c.bar.stiffness * (c.length - c.bar.unstressed_length);
        break;
      case SlackCriterion::force:
        expected = std::max(c.bar.stiffness * (c.length - c.bar.unstressed_length), 0.0);
        break;
      case SlackCriterion::length:
        expected = c.bar.equilibrium_force +
                   c.bar.stiffness * std::max(c.length - c.bar.equilibrium_length, 0.0);
        break;
    }
    EXPECT_NEAR(N, expected, 1e-9 * scale);
    const Eigen::Vector3d e = (q.segment<3>(3) - q.segment<3>(0)).normalized();
    EXPECT_LT((f.segment<3>(3) - N * e).norm(), 1e-10 * scale);
    EXPECT_LT((f.segment<3>(0) + f.segment<3>(3)).norm(), 1e-10 * scale);
  }
}

// A bar given by its EA (droppers.EA): k = EA / L0 follows L0, so df/dL0
// includes dk/dL0 (the form-finding Jacobian column of a dropper's length).
TEST(BarElement, AxialRigidityStiffnessFollowsUnstressedLength) {
  for (SlackCriterion slack : {SlackCriterion::none, SlackCriterion::force}) {
    for (double length : {1.25, 1.15}) {
      SCOPED_TRACE(std::to_string(static_cast<int>(slack)) + " l=" + std::to_string(length));
      BarElement bar;
      bar.axial_rigidity = 2.4e5;
      bar.stiffness = 1.0;  // overwritten by the length
      bar.slack = slack;
      set_bar_unstressed_length(bar, 1.2);
      EXPECT_DOUBLE_EQ(bar.stiffness, 2.4e5 / 1.2);
      const BarParameters params = bar_parameters(bar);
      EXPECT_DOUBLE_EQ(params.stiffness, 2.4e5 / 1.2);
      const Vec6 q = bar_configuration(length);
      Vec6 f, df_dL0;
      const double N = bar_internal_force(params, q, f, nullptr, &df_dL0);
      const bool active = slack == SlackCriterion::none || length > 1.2;
      EXPECT_NEAR(N, active ? 2.4e5 * (length - 1.2) / 1.2 : 0.0, 1e-9);
      const double h = 1e-7;
      BarElement p = bar, m = bar;
      set_bar_unstressed_length(p, 1.2 + h);
      set_bar_unstressed_length(m, 1.2 - h);
      Vec6 fp, fm;
      bar_internal_force(bar_parameters(p), q, fp);
      bar_internal_force(bar_parameters(m), q, fm);
      EXPECT_LT(relative_error(df_dL0, Vec6((fp - fm) / (2 * h)), 1e-3 * params.stiffness),
                kFdTolerance);
      if (active) {  // dN/dL0 = -EA l / L0^2, not -k
        const Eigen::Vector3d e = (q.segment<3>(3) - q.segment<3>(0)).normalized();
        EXPECT_NEAR(df_dL0.segment<3>(3).dot(e), -2.4e5 * length / (1.2 * 1.2), 1e-6);
      }
    }
  }
}

TEST(BarElement, LumpedMassAndGravity) {
  const double mass = 0.64;
  const Vec6 m = bar_lumped_mass(mass);
  EXPECT_DOUBLE_EQ(m(0), 0.32);
  EXPECT_DOUBLE_EQ(m(5), 0.32);
  EXPECT_NEAR(m.sum(), 3.0 * mass, 1e-15);  // each direction carries the whole mass
  const Eigen::Vector3d g(0.0, 0.0, -9.81);
  const Vec6 fg = bar_gravity_force(mass, g);
  EXPECT_LT((fg.segment<3>(0) + fg.segment<3>(3) - mass * g).norm(), 1e-15);
  EXPECT_LT((fg.segment<3>(0) - fg.segment<3>(3)).norm(), 1e-15);
}

}  // namespace
}  // namespace pcsim::catenary
