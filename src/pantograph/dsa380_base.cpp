// Base motion of the DSA-380 models (issue 25), rigid and flexible. Their coordinates are
// measured in the frame of the base, which moves vertically by z_b(t): with v_abs = v_rel +
// v_b e_z, Lagrange's
// equations (A.36) gain the generalised force −a_b Σ m_i ∂z_i/∂q, i.e. g becomes g + a_b
// in the gravity terms of (A.36). Joints, springs, bellows and damper act between frame
// and arms: unchanged. The contact point's absolute height gains z_b (frame_height()).
#include <cmath>
#include <utility>

#include "pcsim/pantograph/dsa380.hpp"
#include "pcsim/pantograph/flexible_dsa380.hpp"

namespace pcsim::pantograph {

Eigen::VectorXd Dsa380Pantograph::static_equilibrium(double contact_force, double working_height) {
  MovingFrame held = std::exchange(frame_, MovingFrame{});
  try {
    Eigen::VectorXd q0 = equilibrium_at_rest(contact_force, working_height);
    frame_ = std::move(held);
    return q0;
  } catch (...) {
    frame_ = std::move(held);
    throw;
  }
}

// Σ m_i ∂z_i/∂q: bars 1–6 through θ, the head (bar 7) through y10 and θ7; the rotation
// restraint replaces the θ7 row (A.37), the bellows state has no mass.
Eigen::VectorXd Dsa380Pantograph::base_inertia(const Eigen::VectorXd& q) const {
  const auto k = dsa380_kinematics(p_, q[0]);
  Eigen::VectorXd b = Eigen::VectorXd::Zero(dof_count());
  for (int i = 0; i < 6; ++i) b[0] += p_.m[i] * k.yg[i][1];
  b[2] = p_.m[6];
  if (e_.head_restraint != Dsa380Effects::HeadRestraint::rotation)
    b[3] = p_.m[6] * p_.LG[6] * std::cos(q[3] - p_.thetaG[6]);
  return b;
}

// The gravity rows of (A.36) with a_b for g (before the restraints replace their rows).
void Dsa380Pantograph::add_base_residual(double t, const Dsa380Kinematics& k,
                                         const Eigen::VectorXd& q,
                                         Eigen::Ref<Eigen::VectorXd> R) const {
  if (!frame_.moves()) return;
  const double ab = frame_.acceleration(t);
  double frame = 0;
  for (int i = 0; i < 6; ++i) frame += p_.m[i] * k.yg[i][1];
  R[0] += ab * frame;
  R[2] += ab * p_.m[6];
  R[3] += ab * p_.m[6] * p_.LG[6] * std::cos(q[3] - p_.thetaG[6]);
}

void Dsa380Pantograph::add_base_tangent(double t, const Dsa380Kinematics& k,
                                        const Eigen::VectorXd& q,
                                        Eigen::Ref<Eigen::MatrixXd> Kq) const {
  if (!frame_.moves()) return;
  const double ab = frame_.acceleration(t);
  double frame = 0;
  for (int i = 0; i < 6; ++i) frame += p_.m[i] * k.yg[i][2];
  Kq(0, 0) += ab * frame;
  Kq(3, 3) -= ab * p_.m[6] * p_.LG[6] * std::sin(q[3] - p_.thetaG[6]);
}

// ---- flexible DSA-380 (thesis 2.2): the beams' lumped weights and the head's, g + a_b ----

Eigen::VectorXd FlexibleDsa380Pantograph::base_inertia(const Eigen::VectorXd& q) const {
  const Dsa380Parameters& p = p_.rigid;
  Eigen::VectorXd b = bar_masses_;
  b[2] += p.m[6];
  if (e_.head_restraint != Dsa380Effects::HeadRestraint::rotation)
    b[3] += p.m[6] * p.LG[6] * std::cos(q[3] - p.thetaG[6]);
  else
    b[3] = 0;
  if (e_.head_restraint == Dsa380Effects::HeadRestraint::horizontal) b[1] = 0;
  return b;
}

}  // namespace pcsim::pantograph
