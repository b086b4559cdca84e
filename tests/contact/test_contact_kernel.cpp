// Penalty contact kernel (thesis 3.2): contact-point location (3.12), gap (3.9, 3.13),
// penalty force (3.10), residual and tangent.
#include <gtest/gtest.h>

#include <cmath>

#include "pcsim/contact/contact_kernel.hpp"

using pcsim::contact::evaluate_penalty_contact;
using pcsim::contact::interpolate;
using pcsim::contact::locate_contact_point;
using pcsim::contact::Matrix13d;
using pcsim::contact::Vector12d;
using pcsim::contact::Vector13d;

namespace {

// Straight element from x0 along the track at height z0, slopes = unit tangent.
Vector12d straight_element(double x0, double z0, double lref) {
  Vector12d q;
  q << x0, 0.1, z0, 1, 0, 0, x0 + lref, 0.1, z0, 1, 0, 0;
  return q;
}

// A sagging, skewed, stretched element: slopes not unit, lateral and vertical curvature.
Vector12d curved_element(double x0, double lref) {
  Vector12d q;
  q << x0, 0.2, 5.3, 1.08, -0.05, -0.12,  //
      x0 + 1.03 * lref, -0.15, 5.25, 0.93, 0.04, 0.09;
  return q;
}

constexpr double kPenalty = 50000.0;  // thesis value (3.2)

}  // namespace

TEST(ContactKernel, ShapeFunctionsInterpolateEndsAndSlopes) {
  const double lref = 2.5;
  const Vector12d q = curved_element(100.0, lref);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(interpolate(q, 0.0, lref, c), q(c), 1e-14);
    EXPECT_NEAR(interpolate(q, lref, lref, c), q(6 + c), 1e-13);
    // slope by central differences at the ends equals the slope DOFs
    const double h = 1e-6;
    EXPECT_NEAR((interpolate(q, h, lref, c) - interpolate(q, -h, lref, c)) / (2 * h), q(3 + c),
                1e-7);
    EXPECT_NEAR((interpolate(q, lref + h, lref, c) - interpolate(q, lref - h, lref, c)) / (2 * h),
                q(9 + c), 1e-7);
  }
}

TEST(ContactKernel, CubicSolvedOnCurvedElements) {
  const double lref = 4.0;
  for (double x0 : {0.0, 123.456, 612.0}) {
    const Vector12d q = curved_element(x0, lref);
    const double x_end = q(6);
    for (int k = 0; k <= 50; ++k) {
      const double x_c = x0 + (x_end - x0) * k / 50.0;
      const auto loc = locate_contact_point(q, lref, x_c);
      ASSERT_TRUE(loc.inside) << "x_c=" << x_c;
      EXPECT_GE(loc.chi, 0.0);
      EXPECT_LE(loc.chi, lref);
      EXPECT_LE(std::abs(interpolate(q, loc.chi, lref, 0) - x_c), 1e-12) << "x_c=" << x_c;
      EXPECT_LT(loc.iterations, 60);
    }
  }
}

TEST(ContactKernel, ReversedElementAndOutsidePoints) {
  const double lref = 3.0;
  Vector12d q = curved_element(50.0, lref);
  // Element oriented against the track direction.
  Vector12d r;
  r << q.segment<3>(6), -q.segment<3>(9), q.segment<3>(0), -q.segment<3>(3);
  const auto loc = locate_contact_point(r, lref, 51.0);
  EXPECT_TRUE(loc.inside);
  EXPECT_LE(std::abs(interpolate(r, loc.chi, lref, 0) - 51.0), 1e-12);
  const auto before = locate_contact_point(q, lref, 49.0);
  EXPECT_FALSE(before.inside);
  EXPECT_EQ(before.chi, 0.0);
  const auto after = locate_contact_point(q, lref, q(6) + 0.5);
  EXPECT_FALSE(after.inside);
  EXPECT_EQ(after.chi, lref);
}

TEST(ContactKernel, StraightElementGivesChiEqualToDistance) {
  const double lref = 2.0, x0 = 300.0;
  const Vector12d q = straight_element(x0, 5.3, lref);
  double previous = -1;
  for (int k = 0; k <= 200; ++k) {
    const double x_c = x0 + lref * k / 200.0;
    const auto loc = locate_contact_point(q, lref, x_c);
    ASSERT_TRUE(loc.inside);
    EXPECT_NEAR(loc.chi, x_c - x0, 1e-12);
    EXPECT_GT(loc.chi, previous);  // continuous and increasing along the element
    previous = loc.chi;
  }
}

TEST(ContactKernel, NoForceWhenSeparated) {
  const double lref = 2.0;
  const Vector12d q = curved_element(10.0, lref);
  const double chi = 0.7;
  const double z_wire = interpolate(q, chi, lref, 2);
  const auto e = evaluate_penalty_contact(q, z_wire - 0.01, chi, lref, kPenalty);
  EXPECT_NEAR(e.gap, 0.01, 1e-14);
  EXPECT_EQ(e.force, 0.0);
  EXPECT_EQ(e.residual.norm(), 0.0);
  EXPECT_EQ(e.tangent.norm(), 0.0);
}

TEST(ContactKernel, ForceAndResidualInContact) {
  const double lref = 2.0;
  const Vector12d q = curved_element(10.0, lref);
  const double chi = 0.7, pen = 2.4e-3;  // head 2.4 mm above the wire
  const double z_wire = interpolate(q, chi, lref, 2);
  const auto e = evaluate_penalty_contact(q, z_wire + pen, chi, lref, kPenalty);
  EXPECT_NEAR(e.gap, -pen, 1e-14);
  EXPECT_NEAR(e.force, kPenalty * pen, 1e-9);   // 120 N
  EXPECT_NEAR(e.residual(12), e.force, 1e-12);  // head pushed down
  // The vertical position DOFs of the wire carry the whole force upwards (s1 + s3 = 1) and no
  // x or y DOF is loaded.
  EXPECT_NEAR(e.residual(2) + e.residual(8), -e.force, 1e-10);
  for (int i : {0, 1, 3, 4, 6, 7, 9, 10}) EXPECT_EQ(e.residual(i), 0.0);
  // Moment about node i: force times chi (the slope DOFs carry the moment).
  EXPECT_NEAR(-(e.residual(8) * lref + e.residual(5) + e.residual(11)), e.force * chi, 1e-9);
}

TEST(ContactKernel, TangentMatchesFiniteDifferences) {
  const double lref = 2.0;
  const Vector12d q = curved_element(10.0, lref);
  for (double chi : {0.0, 0.37, 1.2, 2.0}) {
    const double q_head = interpolate(q, chi, lref, 2) + 3e-3;  // in contact, away from dz = 0
    const auto e = evaluate_penalty_contact(q, q_head, chi, lref, kPenalty);
    Matrix13d fd;
    const double h = 1e-7;
    for (int j = 0; j < 13; ++j) {
      Vector12d qp = q, qm = q;
      double hp = q_head, hm = q_head;
      if (j < 12) {
        qp(j) += h;
        qm(j) -= h;
      } else {
        hp += h;
        hm -= h;
      }
      const Vector13d rp = evaluate_penalty_contact(qp, hp, chi, lref, kPenalty).residual;
      const Vector13d rm = evaluate_penalty_contact(qm, hm, chi, lref, kPenalty).residual;
      fd.col(j) = (rp - rm) / (2 * h);
    }
    EXPECT_LE((fd - e.tangent).norm(), 1e-6 * e.tangent.norm()) << "chi=" << chi;
    EXPECT_GT(e.tangent.norm(), kPenalty);  // non-trivial
    EXPECT_LE((e.tangent - e.tangent.transpose()).norm(), 1e-12 * e.tangent.norm());
  }
}
