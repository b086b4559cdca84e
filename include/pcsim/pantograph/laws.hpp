// Force laws of the DSA-380 models (rigid, dsa380.hpp; flexible, flexible_dsa380.hpp),
// each written once with its force, its derivative and its energy or power, so that the
// two models share them (like Bellows):
//  - HeadSpring: the head suspension springs, f = kl δ + kl3 δ³ (2.11);
//  - FrameDamper: the frame damper through its lever, f_d = c v_a + c2 v_a |v_a|
//    (A.13–A.19), one-way if asked: it acts only while the frame descends (ẏ5 < 0);
//  - HeadFriction: the smoothed Coulomb friction head–frame, F_f = (2/π) fr atan(v_r / kt)
//    (2.16–2.17), dF_f/dv_r (3.32).
// Powers are those the laws exchange with the model: dissipated power is negative.
#pragma once

#include <cmath>

namespace pcsim::pantograph {

struct HeadSpring {
  double kl = 0, kl3 = 0;  // N/m, N/m³
  // Force at elongation e = l − l0 (tension positive) and, if asked, df/de.
  double force(double e, double* stiffness = nullptr) const {
    if (stiffness) *stiffness = kl + 3 * kl3 * e * e;
    return kl * e + kl3 * e * e * e;
  }
  double energy(double e) const { return 0.5 * kl * e * e + 0.25 * kl3 * e * e * e * e; }
};

struct FrameDamper {
  double c = 0;          // N s/m
  double quadratic = 0;  // c2 (N s²/m²)
  bool one_way = false;
  // Whether it acts at the frame's vertical rate ẏ5.
  bool acts(double frame_rate) const { return !one_way || frame_rate < 0; }
  // Force at the damper's rate v_a and df/dv_a.
  double force(double va) const { return c * va + quadratic * va * std::abs(va); }
  double dforce(double va) const { return c + 2 * quadratic * std::abs(va); }
  double power(double va) const { return -force(va) * va; }
};

struct HeadFriction {
  double force_max = 0;  // fr (N)
  double kt = 5e-4;      // m/s
  // Force on the head at the relative rate v_r = ẏ10 − ẏ5, and dF/dv_r (3.32).
  double force(double vr) const { return force_max * M_2_PI * std::atan(vr / kt); }
  double dforce(double vr) const { return force_max * M_2_PI * kt / (kt * kt + vr * vr); }
  double power(double vr) const { return -force(vr) * vr; }
};

}  // namespace pcsim::pantograph
