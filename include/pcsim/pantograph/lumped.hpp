// Lumped-mass pantograph with any number of stages (thesis Fig. 2.1; EN 50318 reference
// two-mass model). q[i] is the upward displacement of stage i from its unloaded position;
// stage 0 is the head. Stage i is joined to stage i+1 by (k_i, c_i); the last stage is
// joined to the roof. Q = static uplift on one stage − gravity (optional) + aerodynamic
// force a + b v + c v² on the head (optional) + the load of a prescribed roof motion
// z_b(t) on the last stage, k z_b + c v_b (optional, issue 25).
#pragma once

#include <string>
#include <vector>

#include "pcsim/pantograph/model.hpp"

namespace pcsim::pantograph {

struct LumpedStage {
  std::string name;
  double mass = 0;
  double stiffness = 0;  // to the stage below (roof for the last)
  double damping = 0;
};

struct LumpedParameters {
  std::string name;
  std::vector<LumpedStage> stages;
  double uplift_force = 0;
  int uplift_stage = 0;
  bool gravity = false;
  double g = 9.81;
  double aero_a = 0, aero_b = 0, aero_c = 0;  // F = a + b v + c v² (N, v in m/s)
};

class LumpedPantograph : public PantographModel {
 public:
  LumpedPantograph(LumpedParameters params, bool aerodynamic, double speed_m_s);

  std::string kind() const override { return "lumped"; }
  int dof_count() const override { return static_cast<int>(p_.stages.size()); }
  std::vector<std::string> dof_names() const override;
  int contact_dof() const override { return 0; }
  double contact_offset() const override { return offset_; }
  void residual(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                const Eigen::VectorXd& qdd, Eigen::Ref<Eigen::VectorXd> R) const override;
  void tangents(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                const Eigen::VectorXd& qdd, Eigen::Ref<Eigen::MatrixXd> dR_dq,
                Eigen::Ref<Eigen::MatrixXd> dR_dqd,
                Eigen::Ref<Eigen::MatrixXd> dR_dqdd) const override;
  bool is_linear() const override { return true; }
  Eigen::VectorXd static_equilibrium(double contact_force, double working_height) override;
  double kinetic_energy(const Eigen::VectorXd& q, const Eigen::VectorXd& qd) const override;
  double potential_energy(const Eigen::VectorXd& q) const override;
  PowerSplit power(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd) const override;
  BaseSupport base_support() const override;
  void set_base_motion(BaseMotion motion) override { base_ = std::move(motion); }

  const Eigen::MatrixXd& mass() const { return M_; }
  const Eigen::MatrixXd& damping() const { return C_; }
  const Eigen::MatrixXd& stiffness() const { return K_; }
  const Eigen::VectorXd& load() const { return Q_; }  // constant generalised force
  const LumpedParameters& parameters() const { return p_; }

 private:
  LumpedParameters p_;
  Eigen::MatrixXd M_, C_, K_;
  Eigen::VectorXd Q_;      // uplift − gravity + aerodynamic (constant)
  Eigen::VectorXd Q_ext_;  // the part of Q that is external work (uplift + aero)
  double offset_ = 0;
  BaseMotion base_;  // empty: the roof does not move

  // k z_b(t) + c v_b(t) on the last stage (0 without base motion).
  double base_load(double t) const;
};

}  // namespace pcsim::pantograph
