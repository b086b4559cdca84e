#include "pcsim/pantograph/lumped.hpp"

namespace pcsim::pantograph {

LumpedPantograph::LumpedPantograph(LumpedParameters params, bool aerodynamic, double speed_m_s)
    : p_(std::move(params)) {
  const int n = dof_count();
  M_ = Eigen::MatrixXd::Zero(n, n);
  C_ = Eigen::MatrixXd::Zero(n, n);
  K_ = Eigen::MatrixXd::Zero(n, n);
  Q_ = Eigen::VectorXd::Zero(n);
  Q_ext_ = Eigen::VectorXd::Zero(n);
  for (int i = 0; i < n; ++i) {
    const auto& s = p_.stages[i];
    M_(i, i) = s.mass;
    // Element between stage i and stage i+1 (or the roof).
    K_(i, i) += s.stiffness;
    C_(i, i) += s.damping;
    if (i + 1 < n) {
      K_(i + 1, i + 1) += s.stiffness;
      K_(i, i + 1) -= s.stiffness;
      K_(i + 1, i) -= s.stiffness;
      C_(i + 1, i + 1) += s.damping;
      C_(i, i + 1) -= s.damping;
      C_(i + 1, i) -= s.damping;
    }
    if (p_.gravity) Q_(i) -= s.mass * p_.g;
  }
  Q_ext_(p_.uplift_stage) += p_.uplift_force;
  if (aerodynamic)
    Q_ext_(0) += p_.aero_a + p_.aero_b * speed_m_s + p_.aero_c * speed_m_s * speed_m_s;
  Q_ += Q_ext_;
}

std::vector<std::string> LumpedPantograph::dof_names() const {
  std::vector<std::string> names;
  for (const auto& s : p_.stages) names.push_back("z_" + s.name);
  return names;
}

BaseSupport LumpedPantograph::base_support() const {
  const auto& last = p_.stages.back();
  return {dof_count() - 1, last.stiffness, last.damping};
}

// The last stage's element k (z_n − z_b) + c (v_n − v_b): K q and C q̇ hold k z_n + c v_n,
// the prescribed rest is a load. The tangents do not change.
double LumpedPantograph::base_load(double t) const {
  if (!base_.displacement) return 0.0;
  const auto& last = p_.stages.back();
  return last.stiffness * base_.displacement(t) + last.damping * base_.velocity(t);
}

void LumpedPantograph::residual(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                                const Eigen::VectorXd& qdd, Eigen::Ref<Eigen::VectorXd> R) const {
  R.noalias() = M_ * qdd + C_ * qd + K_ * q - Q_;
  if (base_.displacement) R[dof_count() - 1] -= base_load(t);
}

void LumpedPantograph::tangents(double, const Eigen::VectorXd&, const Eigen::VectorXd&,
                                const Eigen::VectorXd&, Eigen::Ref<Eigen::MatrixXd> dR_dq,
                                Eigen::Ref<Eigen::MatrixXd> dR_dqd,
                                Eigen::Ref<Eigen::MatrixXd> dR_dqdd) const {
  dR_dq = K_;
  dR_dqd = C_;
  dR_dqdd = M_;
}

Eigen::VectorXd LumpedPantograph::static_equilibrium(double contact_force, double working_height) {
  Eigen::VectorXd rhs = Q_;
  rhs(0) -= contact_force;
  Eigen::VectorXd q0 = K_.fullPivLu().solve(rhs);
  if (!(K_ * q0).isApprox(rhs, 1e-10))
    throw SolverError("lumped pantograph: no static equilibrium (singular stiffness)");
  offset_ = working_height - q0(0);
  return q0;
}

double LumpedPantograph::kinetic_energy(const Eigen::VectorXd&, const Eigen::VectorXd& qd) const {
  return 0.5 * qd.dot(M_ * qd);
}

double LumpedPantograph::potential_energy(const Eigen::VectorXd& q) const {
  // Springs plus gravity (the gravity part of Q is conservative).
  return 0.5 * q.dot(K_ * q) - (Q_ - Q_ext_).dot(q);
}

// Springs and dampers measured with the roof at rest: the roof's motion does the work of
// its load on the last stage, (k z_b + c v_b) v_n.
PowerSplit LumpedPantograph::power(double t, const Eigen::VectorXd&,
                                   const Eigen::VectorXd& qd) const {
  return {-qd.dot(C_ * qd), Q_ext_.dot(qd), base_load(t) * qd[dof_count() - 1]};
}

}  // namespace pcsim::pantograph
