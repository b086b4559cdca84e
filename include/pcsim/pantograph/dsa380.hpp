// Rigid-body DSA-380 pantograph (thesis 2.1.1, Annex A): 7 bars, 4 DOF
// q = {θ, x10, y10, θ7}. Bars 1–6 form a one-DOF mechanism driven by θ (two closed
// loops, A.1–A.5); the head (bar 7, centre point 10) is a free planar body hanging on
// two springs from point 5 (top of bar 4) to its ends 11, 12 (A.11).
//
// Equations (Lagrange, A.36), with the frame's generalised inertia a(θ) = Σ m_i|v_Gi/θ̇|²
// + I_i (dθ_i/dθ)² (A.7):
//   R_θ   = a θ̈ + ½ a' θ̇² + kr(θ−θr0) + dVg/dθ + Σ f_s ∂l_s/∂θ − M0 + f_d h + F_r ∂v_r/∂θ̇
//   R_x10 = m7 ẍ10 − m7 LG7 (s θ̈7 + c θ̇7²) + Σ f_s ∂l_s/∂x10
//   R_y10 = m7 ÿ10 + m7 LG7 (c θ̈7 − s θ̇7²) + m7 g + Σ f_s ∂l_s/∂y10 + F_r − F_aero
//   R_θ7  = m7 LG7 (c ÿ10 − s ẍ10) + (I7 + m7 LG7²) θ̈7 + m7 g LG7 c + Σ f_s ∂l_s/∂θ7
// with s, c = sin, cos(θ7 − θG7), spring force f_s = kl (l−l0) + kl3 (l−l0)³, damper
// force f_d(v_a) = c v_a + c2 v_a|v_a| along its length l_a with v_a = h θ̇, h = dl_a/dθ
// (A.13–A.19), friction F_r = fr (2/π) atan(v_r/kt), v_r = ẏ10 − ẏ5 (2.16–2.17).
// With the uplift characteristic (Dsa380Effects::uplift_characteristic) the bellows torque
// is M0 plus the change that the characteristic asks for (bellows.hpp).
#pragma once

#include <array>
#include <string>

#include "pcsim/pantograph/bellows.hpp"
#include "pcsim/pantograph/jet.hpp"
#include "pcsim/pantograph/laws.hpp"
#include "pcsim/pantograph/model.hpp"

namespace pcsim::pantograph {

struct Dsa380Parameters {
  std::string name = "dsa380";
  // Geometry (m, rad). Point 2 is the origin; points 1 and 13 are fixed.
  double x1 = 0, y1 = 0;
  double L1 = 0, L2 = 0, L3 = 0, L4 = 0, L5 = 0, L6 = 0, L7 = 0;
  double theta34 = M_PI;                   // angle between bars 3 and 4 (θ4 = θ3 + θ34 − π)
  double r = 0, theta_r = 0;               // point 6 on bar 1
  double L1p = 0, theta_1p = 0;            // damper lever (point 1p on bar 1)
  double x13 = 0, y13 = 0;                 // damper's fixed end
  double L7p = 0;                          // height of the contact strips above point 10
  int lower_branch = 1, upper_branch = 1;  // assembly branch of the two loops (±1)
  // Inertia: mass, moment of inertia about the centre of gravity, CG position (LGi, θGi)
  // from the bar's first point (bar 7: from point 10).
  std::array<double, 7> m{}, I{}, LG{}, thetaG{};
  // Springs and damper.
  double kr = 0, theta_r0 = 0;  // torsional spring of the drive (N m/rad, rad)
  double kl = 0, kl3 = 0;       // head springs: f = kl δ + kl3 δ³ (N/m, N/m³)
  double l10 = 0, l20 = 0;      // unstretched lengths of the head springs
  double c = 0;                 // damper (N s/m)
  double g = 9.81;
  double aero_a = 0, aero_b = 0, aero_c = 0;  // vertical aerodynamic force on the head
  BellowsParameters bellows;                  // uplift characteristic (bellows.hpp)
  // Reference conditions (used by studies and the calibration).
  double theta_guess = 0.6;  // start of the Newton search for θ (2.13)
};

struct Dsa380Effects {
  enum class HeadRestraint { none, rotation, horizontal };  // θ7 = 0 (A.37), x10 = x5 (A.38)
  HeadRestraint head_restraint = HeadRestraint::none;
  bool friction = false;
  double friction_force = 0, friction_kt = 5e-4;  // fr (N), kt (m/s)
  bool damper = true;
  bool damper_one_way = false;  // acts only while the frame descends (ẏ5 < 0)
  double damper_quadratic = 0;  // c2 (N s²/m²)
  bool aerodynamic = false;
  // The bellows torque follows the uplift characteristic (bellows.hpp); else fixed M0.
  bool uplift_characteristic = false;
};

// The force laws of both DSA-380 models (laws.hpp) from their parameters.
inline HeadSpring head_spring(const Dsa380Parameters& p) {
  return {p.kl, p.kl3};
}
inline FrameDamper frame_damper(const Dsa380Parameters& p, const Dsa380Effects& e) {
  return {p.c, e.damper_quadratic, e.damper_one_way};
}
inline HeadFriction head_friction(const Dsa380Effects& e) {
  return {e.friction_force, e.friction_kt};
}

// Name of the mode whose dominant coordinate is q[dof]: "frame", "head horizontal",
// "head vertical", "head rotation" ("" outside 0..3).
const char* dsa380_mode_label(int dof);

// Positions of the mechanism for a frame angle θ, with derivatives d/dθ up to 3.
struct Dsa380Kinematics {
  Jet theta2, theta3, theta4, theta5, theta6;
  Jet x3, y3, x4, y4, x5, y5, x6, y6, xj, yj;  // j: joint of bars 5 and 6
  Jet damper_length;                           // l_a(θ)
  Jet inertia;                                 // a(θ) (entries 0..2 valid)
  Jet gravity_energy;                          // Vg of bars 1–6 (entries 0..3)
  std::array<Jet, 6> xg, yg;                   // centres of gravity of bars 1–6
  bool assembled = true;
};
Dsa380Kinematics dsa380_kinematics(const Dsa380Parameters& p, double theta);

// Head descent z under the vertical load W = m7 g + F0 − F_aero carried by the two head
// springs (2.12): 2 f(l) z / l = W, l = √(z² + (L7/2)²); dz/dW in *dz_dload.
double dsa380_head_descent(const Dsa380Parameters& p, double load, double* dz_dload);

class Dsa380Pantograph : public PantographModel {
 public:
  Dsa380Pantograph(Dsa380Parameters params, Dsa380Effects effects, double speed_m_s);

  std::string kind() const override { return "dsa380"; }
  // q = {θ, x10, y10, θ7} and, with the bellows' pressure loop, its state (bellows.hpp).
  int dof_count() const override { return bellows_.has_state() ? 5 : 4; }
  std::vector<std::string> dof_names() const override;
  int contact_dof() const override { return 2; }
  double contact_offset() const override { return p_.L7p; }
  void residual(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                const Eigen::VectorXd& qdd, Eigen::Ref<Eigen::VectorXd> R) const override;
  void tangents(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                const Eigen::VectorXd& qdd, Eigen::Ref<Eigen::MatrixXd> dR_dq,
                Eigen::Ref<Eigen::MatrixXd> dR_dqd,
                Eigen::Ref<Eigen::MatrixXd> dR_dqdd) const override;
  bool is_linear() const override { return false; }
  // Two-step procedure (2.12–2.14): head descent z, then θ with y5(θ) = h0 − L7p + z,
  // then the bellows torque M0. Sets M0 and returns q0. A base motion is held at rest
  // meanwhile (M0 is the bellows' setting, not a reaction to a_b(0)).
  Eigen::VectorXd static_equilibrium(double contact_force, double working_height) override;
  // Heights are measured above the pantograph's base: nominal working height 1.2 m.
  double default_working_height() const override { return 1.2; }
  double kinetic_energy(const Eigen::VectorXd& q, const Eigen::VectorXd& qd) const override;
  double potential_energy(const Eigen::VectorXd& q) const override;
  PowerSplit power(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd) const override;
  // Base motion (issue 25, dsa380_base.cpp): q is measured in the moving frame of the base;
  // every body carries −m_i a_b(t) (gravity g becomes g + a_b).
  bool moving_frame() const override { return true; }
  void set_base_motion(BaseMotion motion) override { frame_.set(std::move(motion), kind()); }
  Eigen::VectorXd base_inertia(const Eigen::VectorXd& q) const override;
  double frame_height(double t) const override { return frame_.height(t); }
  double frame_velocity(double t) const override { return frame_.velocity(t); }

  // General Newton solve of R(q, 0, 0) + F0 e_c = 0 for the current M0, with restrained
  // rows replaced by their position constraints. Throws SolverError if it fails.
  Eigen::VectorXd solve_static(double contact_force, Eigen::VectorXd q_start) const;
  // Head descent z of step 1 (2.12).
  double head_descent(double contact_force) const;
  // Bellows torque M0 from the closed formula (2.14) at q0 (symmetric head, LG7 = 0).
  double bellows_torque_formula(const Eigen::VectorXd& q0, double contact_force) const;

  double bellows_torque() const { return M0_; }
  void set_bellows_torque(double M0) { M0_ = M0; }
  const Dsa380Parameters& parameters() const { return p_; }
  const Dsa380Effects& effects() const { return e_; }
  const Bellows& bellows() const { return bellows_; }

 private:
  // static_equilibrium() with the base at rest (dsa380.cpp).
  Eigen::VectorXd equilibrium_at_rest(double contact_force, double working_height);
  [[noreturn]] void fail_working_height(double theta, double h0, double z,
                                        const std::string& what) const;
  int bellows_dof() const { return bellows_.has_state() ? 4 : -1; }
  // a_b(t) base_inertia(q) into R and its q-derivative into dR/dq (no base motion: nothing).
  void add_base_residual(double t, const Dsa380Kinematics& k, const Eigen::VectorXd& q,
                         Eigen::Ref<Eigen::VectorXd> R) const;
  void add_base_tangent(double t, const Dsa380Kinematics& k, const Eigen::VectorXd& q,
                        Eigen::Ref<Eigen::MatrixXd> Kq) const;
  Dsa380Parameters p_;
  Dsa380Effects e_;
  double aero_force_ = 0;
  double M0_ = 0;
  Bellows bellows_;
  HeadSpring spring_;
  FrameDamper damper_;
  HeadFriction friction_;
  MovingFrame frame_;
};

}  // namespace pcsim::pantograph
