// Flexible DSA-380: static equilibrium with the bellows torque, strain energy per bar.
#include <algorithm>
#include <cfloat>
#include <cmath>

#include "pcsim/pantograph/flexible_dsa380.hpp"

namespace pcsim::pantograph {

Eigen::VectorXd FlexibleDsa380Pantograph::static_equilibrium(double contact_force,
                                                             double working_height) {
  bellows_.clear_reference();  // the fixed-torque equilibrium: M0 at h0
  // Start: the rigid model's equilibrium (2.12–2.14) on the undeformed mechanism.
  Dsa380Pantograph rigid(p_.rigid, e_, speed_);
  const Eigen::VectorXd qr = rigid.static_equilibrium(contact_force, working_height);
  M0_ = rigid.bellows_torque();
  Eigen::VectorXd q = rigid_configuration(qr[0], qr[1], qr[2], qr[3]);
  // Unknowns: q with y10 = h0 − L7p held, and M0 in its place (dR/dM0 = −e_θ).
  const int n = dof_count(), x5 = mesh_.x5;
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
  Eigen::VectorXd R(n);
  Eigen::MatrixXd K(n, n), C(n, n), M(n, n);
  MatrixRef k(K), c(C), m(M);
  double weight = p_.rigid.m[6] * p_.rigid.g;
  for (const auto& t : sections_) weight += t.mass * p_.rigid.g;
  // Converged when |R| < 1e-9 of the load, or when the step has vanished and |R| is at the
  // rounding floor of the element forces.
  const double tol = 1e-9 * (std::abs(contact_force) + weight);
  const double floor = static_residual_floor();
  double last_step = 1;
  for (int it = 0; it < 50; ++it) {
    assemble(0.0, q, zero, zero, &R, &k, &c, &m);
    R[2] += contact_force;
    if (e_.head_restraint == Dsa380Effects::HeadRestraint::rotation) {
      R[3] = q[3];
      K.row(3).setZero();
      K(3, 3) = 1;
    } else if (e_.head_restraint == Dsa380Effects::HeadRestraint::horizontal) {
      R[1] = q[1] - q[x5];
      K.row(1).setZero();
      K(1, 1) = 1;
      K(1, x5) = -1;
    }
    if (R.norm() < tol || (R.norm() < floor && last_step < 1e-10)) {
      bellows_.set_reference(p_.rigid, q[0], contact_force, working_height);
      return q;
    }
    K.col(2) = -Eigen::VectorXd::Unit(n, 0);
    Eigen::VectorXd dz = K.partialPivLu().solve(-R);
    const double dM0 = dz[2];
    dz[2] = 0;
    const double big = dz.cwiseAbs().maxCoeff();
    const double scale = big > 0.05 ? 0.05 / big : 1.0;  // at most 5 cm or 0.05 rad a step
    q += scale * dz;
    M0_ += scale * dM0;
    last_step = scale * big;
  }
  throw SolverError("dsa380_flexible: static equilibrium (Newton on q and M0) did not converge");
}

// EA/l0 (up to ~5e10 N/m) times the rounding of coordinates of ~2 m.
double FlexibleDsa380Pantograph::static_residual_floor() const {
  double stiffest = 0;
  for (const auto& e : mesh_.elements)
    stiffest = std::max(stiffest, e.beam.section.EA / e.beam.length0);
  return 100 * DBL_EPSILON * 2.0 * stiffest;
}

std::array<FlexibleDsa380Pantograph::BarEnergy, 9> FlexibleDsa380Pantograph::bar_strain_energies(
    const Eigen::VectorXd& q0, const Eigen::VectorXd& dq) const {
  std::array<BarEnergy, 9> E{};
  for (const auto& e : mesh_.elements) {
    const Matrix36 B = planar_beam_strain_gradient(e.beam, gather(e, q0));
    Vector6 dqe;
    for (int a = 0; a < 6; ++a) dqe[a] = e.dof[a] >= 0 ? dq[e.dof[a]] : 0.0;
    const Eigen::Vector3d de = B * dqe;
    const Eigen::Matrix3d D = planar_beam_constitutive(e.beam);
    E[e.bar - 1].axial += 0.5 * D(0, 0) * de[0] * de[0];
    E[e.bar - 1].bending += 0.5 * de.tail<2>().dot(D.bottomRightCorner<2, 2>() * de.tail<2>());
  }
  return E;
}

}  // namespace pcsim::pantograph
