// Penalty contact between one contact-wire ANCF element and one pantograph head
// (thesis 3.2, eqs 3.9–3.13). Pure functions on Eigen types; no PETSc.
//
// Element DOFs q = [r_i, r'_i, r_j, r'_j], each a 3-vector (x along the track, y lateral,
// z vertical), so x_i = q(0), x'_i = q(3), x_j = q(6), x'_j = q(9) and the z entries are
// q(2), q(5), q(8), q(11). Cubic Hermite interpolation on chi in [0, Lref], xi = chi/Lref:
//   s1 = 1-3xi²+2xi³, s2 = Lref(xi-2xi²+xi³), s3 = 3xi²-2xi³, s4 = Lref(-xi²+xi³).
// Self-contained on purpose (does not use the catenary element code).
//
// Sign convention: residual = internal - external forces. With the contact force
// Fc = -kH dz >= 0 (3.10), dz = z_cc - z_H (3.9), the wire gets the upward force Fc at chi_c,
// residual -Fc S_zᵀ, and the head gets Fc downwards, residual +Fc. chi_c is held fixed during
// a time step (as the thesis does), so the tangent is kH [S_z; -1][S_z; -1]ᵀ in contact.
#pragma once

#include <Eigen/Core>
#include <array>

namespace pcsim::contact {

using Vector12d = Eigen::Matrix<double, 12, 1>;
using Vector13d = Eigen::Matrix<double, 13, 1>;
using Matrix13d = Eigen::Matrix<double, 13, 13>;

// The shape functions s1..s4: catenary::hermite() (one implementation).

// Component c (0 = x, 1 = y, 2 = z) of r(chi) (3.12, 3.13).
double interpolate(const Vector12d& q, double chi, double lref, int component);
// 12-vector S_c with interpolate(q, chi, lref, c) = S_c · q.
Vector12d shape_row(double chi, double lref, int component);

struct ContactLocation {
  double chi = 0;       // local coordinate with x(chi) = x_c (clamped to [0, Lref] if outside)
  bool inside = false;  // x_c lies in [x(0), x(Lref)] (either orientation)
  int iterations = 0;
};
// Solves the cubic x(chi) = x_c (3.12) by Newton safeguarded with bisection on [0, Lref]. When
// x(chi) is not monotone and several roots exist, a root in a bracketing interval is returned.
ContactLocation locate_contact_point(const Vector12d& q, double lref, double x_c);

struct ContactEvaluation {
  double gap = 0;                          // dz = z_cc - z_H (3.9); < 0 means interpenetration
  double force = 0;                        // Fc >= 0 (3.10)
  Vector13d residual = Vector13d::Zero();  // 12 wire DOFs, then the head coordinate q_H
  Matrix13d tangent = Matrix13d::Zero();   // d residual / d [q, q_H], chi fixed
};
// Penalty contact at fixed chi_c with stiffness kH (thesis value 50 000 N/m).
ContactEvaluation evaluate_penalty_contact(const Vector12d& q, double q_head, double chi_c,
                                           double lref, double k_penalty);

}  // namespace pcsim::contact
