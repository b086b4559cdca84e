#include "pcsim/pantograph/planar_beam.hpp"

#include <cmath>

namespace pcsim::pantograph {
namespace {

struct Chord {
  double l, beta;
  Eigen::Vector2d n;   // unit chord direction
  Eigen::Matrix2d Hl;  // ∂²l/∂d², d = X2 − X1
  Eigen::Matrix2d Hb;  // ∂²β/∂d²
};

Chord chord(const Vector6& qe, bool with_hessians) {
  Chord c;
  const double dx = qe[3] - qe[0], dy = qe[4] - qe[1];
  c.l = std::hypot(dx, dy);
  c.beta = std::atan2(dy, dx);
  c.n = Eigen::Vector2d(dx, dy) / c.l;
  if (with_hessians) {
    const double nx = c.n.x(), ny = c.n.y(), l2 = c.l * c.l;
    c.Hl << ny * ny, -nx * ny, -nx * ny, nx * nx;
    c.Hl /= c.l;
    c.Hb << 2 * nx * ny, ny * ny - nx * nx, ny * ny - nx * nx, -2 * nx * ny;
    c.Hb /= l2;
  }
  return c;
}

// Hessian in d mapped to qe: d = X2 − X1 gives the block pattern [H −H; −H H] on the
// translations {0, 1} and {3, 4}.
void add_translation_hessian(const Eigen::Matrix2d& H, double weight, Matrix6* K) {
  const int t[2] = {0, 3};
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b) {
      const double sign = a == b ? 1.0 : -1.0;
      K->block<2, 2>(t[a], t[b]) += sign * weight * H;
    }
}

}  // namespace

double wrap_angle(double a) {
  return std::atan2(std::sin(a), std::cos(a));
}

Eigen::Matrix3d planar_beam_constitutive(const PlanarBeamElement& e) {
  const double l0 = e.length0, EI = e.section.EI;
  Eigen::Matrix3d D = Eigen::Matrix3d::Zero();
  D(0, 0) = e.section.EA / l0;
  if (e.hinge_end2) {
    D(1, 1) = 3 * EI / l0;  // M2 = 0 condensed: θ̄2 = −θ̄1/2
  } else {
    D(1, 1) = D(2, 2) = 4 * EI / l0;
    D(1, 2) = D(2, 1) = 2 * EI / l0;
  }
  return D;
}

namespace {

// ∂l/∂qe = {−n, 0, n, 0}; ∂β/∂qe = {−t, 0, t, 0}/l with t = (−ny, nx).
Matrix36 strain_gradient(const Chord& c) {
  const double nx = c.n.x(), ny = c.n.y(), il = 1.0 / c.l;
  Matrix36 B;
  B.row(0) << -nx, -ny, 0, nx, ny, 0;
  const Vector6 dbeta = (Vector6() << ny * il, -nx * il, 0, -ny * il, nx * il, 0).finished();
  B.row(1) = -dbeta.transpose();
  B.row(2) = -dbeta.transpose();
  B(1, 2) += 1;
  B(2, 5) += 1;
  return B;
}

// An angle's difference wrapped to (−π, π]: itself where it lies there (a
// beam's deformation angles, small: no rounding added), else wrap_angle().
double wrapped(double a) {
  return a > -M_PI && a <= M_PI ? a : wrap_angle(a);
}

}  // namespace

Matrix36 planar_beam_strain_gradient(const PlanarBeamElement&, const Vector6& qe) {
  return strain_gradient(chord(qe, false));
}

PlanarBeamState planar_beam_evaluate(const PlanarBeamElement& e, const Vector6& qe,
                                     bool with_stiffness) {
  PlanarBeamState s;
  const Chord c = chord(qe, with_stiffness);
  s.strain << c.l - e.length0, wrapped(qe[2] - c.beta - e.offset1),
      e.hinge_end2 ? 0.0 : wrapped(qe[5] - c.beta - e.offset2);
  const Eigen::Matrix3d D = planar_beam_constitutive(e);
  s.stress = D * s.strain;
  s.energy = 0.5 * s.strain.dot(s.stress);
  const Matrix36 B = strain_gradient(c);  // from the chord above, as planar_beam_strain_gradient()
  s.force = B.transpose() * s.stress;
  if (with_stiffness) {
    s.stiffness = B.transpose() * D * B;
    add_translation_hessian(c.Hl, s.stress[0], &s.stiffness);                   // N ∂²l
    add_translation_hessian(c.Hb, -(s.stress[1] + s.stress[2]), &s.stiffness);  // M ∂²θ̄
  }
  return s;
}

Matrix6 planar_beam_mass(const PlanarBeamElement& e) {
  const double m = e.section.mass_per_length * e.length0;
  const double J = 0.5 * e.section.rotary_inertia_per_length * e.length0;
  Matrix6 M = Matrix6::Zero();
  for (int k = 0; k < 2; ++k) {  // x, y
    M(k, k) = M(3 + k, 3 + k) = m / 3;
    M(k, 3 + k) = M(3 + k, k) = m / 6;
  }
  M(2, 2) = J;
  M(5, 5) = e.hinge_end2 ? 0.0 : J;
  return M;
}

Vector6 planar_beam_weight(const PlanarBeamElement& e, double g) {
  const double w = 0.5 * e.section.mass_per_length * e.length0 * g;
  return (Vector6() << 0, w, 0, 0, w, 0).finished();
}

}  // namespace pcsim::pantograph
