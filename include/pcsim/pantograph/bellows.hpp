// Uplift characteristic of the DSA-380 bellows (docs/interaction.md section 2).
//
// With a fixed bellows torque M0 (thesis 2.12–2.14) the static contact force of the
// calibrated DSA-380 falls by 25.5 N per centimetre of rise (the frame's drive spring kr).
// With the characteristic on, the bellows torque follows a prescribed static force-height
// curve F(h) (constant F0 by default, or a table): the target torque at frame angle θ is
// the torque that holds the frame at θ with the curve's force at the contact, (2.14)
// written for any θ:
//   T(θ) = kr (θ − θr0) + dVg/dθ + (m7 g + F(h(θ)) − F_aero) dy5/dθ,
//   h(θ) = y5(θ) + L7p − z(m7 g + F(h) − F_aero)   (z: head descent, 2.12),
// and ΔM(θ) = T(θ) − T(θ0) is the change from the equilibrium's M0 at θ0, so that the
// static force is F(h) at every height (exactly for the rigid model with a symmetric head).
// The bellows torque M0 + ΔM acts
//  - at once (time_constant = 0): R_θ −= ΔM(θ); this takes away the frame's static
//    stiffness, so the frame mode of the pantograph alone goes to 0 Hz;
//  - through a pressure loop, two first-order lags (bellows volume τ1, valve τ2) in series:
//    one more coordinate m (the torque beyond M0),
//      R_θ −= m,   R_m = (τ1 τ2 m̈ + (τ1 + τ2) ṁ + m − ΔM(θ)) · 1 rad/(N m),
//    so that the frame keeps its fixed-torque dynamics above 1/(2π τ1) and follows the
//    characteristic below it. The row is scaled by 1 rad/(N m) so that q̇ᵀR is a power:
//    ½ τ1τ2 ṁ² and ½ m² (in J per rad/(N m)) enter T and V, (τ1 + τ2) ṁ² is dissipated and
//    ṁ ΔM(θ) is external power, as is the bellows' (M0 + m) θ̇.
#pragma once

#include <Eigen/Dense>
#include <vector>

#include "pcsim/pantograph/model.hpp"

namespace pcsim::pantograph {

struct Dsa380Parameters;
struct Dsa380Kinematics;

// The model file's `bellows:` section.
struct BellowsParameters {
  // Static force-height curve: heights (m, increasing) and forces (N), linearly
  // interpolated, constant beyond its ends; scaled so that it passes through (h0, F0) of
  // the static equilibrium. Empty: constant force F0.
  std::vector<double> heights, forces;
  double time_constant = 0;        // τ1 (s); 0: the torque follows the curve at once
  double valve_time_constant = 0;  // τ2 (s), > 0 when τ1 > 0
};

class Bellows {
 public:
  Bellows() = default;  // fixed torque: adds nothing
  Bellows(BellowsParameters params, bool follows_characteristic, double aero_force);

  bool follows_characteristic() const { return on_; }
  // One more coordinate (the pressure loop's state m) after the model's own.
  bool has_state() const { return on_ && b_.time_constant > 0; }

  // Anchors the curve at the equilibrium: F(h0) = F0 and ΔM(θ0) = 0. Until then (and
  // after clear_reference) ΔM ≡ 0, so a static solve sees the fixed torque.
  void set_reference(const Dsa380Parameters& p, double theta0, double contact_force,
                     double working_height);
  void clear_reference() { referenced_ = false; }

  // Static force of the curve at working height h, and dF/dh.
  double force(double h, double* dforce) const;
  // ΔM(θ) and dΔM/dθ. 'at': the rigid mechanism's kinematics at θ where the
  // caller has them (else computed here; the same bits either way).
  double torque_change(const Dsa380Parameters& p, double theta, double* derivative,
                       const Dsa380Kinematics* at = nullptr) const;

  // Contributions to R and its tangents; theta: index of θ, m: index of the loop's state.
  void add_residual(const Dsa380Parameters& p, int theta, int m, const Eigen::VectorXd& q,
                    const Eigen::VectorXd& qd, const Eigen::VectorXd& qdd,
                    Eigen::Ref<Eigen::VectorXd> R, const Dsa380Kinematics* at = nullptr) const;
  // Matrix: a dense matrix (or an Eigen::Ref of one), or any type whose (i, j)
  // takes +=, -= and = (the flexible DSA-380's sparse step tangent): the
  // entries set with = are the loop's row, which nothing else writes.
  template <class Matrix>
  void add_tangents(const Dsa380Parameters& p, int theta, int m, const Eigen::VectorXd& q,
                    Matrix& K, Matrix& C, Matrix& M, const Dsa380Kinematics* at = nullptr) const;
  template <class Matrix>
  void add_mass(int m, Matrix& M) const;  // add_tangents' M part alone
  double kinetic_energy(int m, const Eigen::VectorXd& qd) const;
  double potential_energy(int m, const Eigen::VectorXd& q) const;
  // Adds the bellows' power beyond M0 θ̇ (external) and the loop's (dissipative).
  void add_power(const Dsa380Parameters& p, int theta, int m, const Eigen::VectorXd& q,
                 const Eigen::VectorXd& qd, PowerSplit* power) const;

 private:
  // T(θ) of the header and dT/dθ.
  double holding_torque(const Dsa380Parameters& p, double theta, double* derivative,
                        const Dsa380Kinematics* at) const;
  // Working height of the rigid mechanism (the curve's force at the head)
  // below the head's top y5(θ) + L7p.
  double height_below(const Dsa380Parameters& p, double top) const;

  BellowsParameters b_;
  bool on_ = false;
  double aero_ = 0;
  bool referenced_ = false;
  double force0_ = 0, scale_ = 1, torque0_ = 0;
};

template <class Matrix>
void Bellows::add_tangents(const Dsa380Parameters& p, int theta, int m, const Eigen::VectorXd& q,
                           Matrix& K, Matrix& C, Matrix& M, const Dsa380Kinematics* at) const {
  if (!on_) return;
  double d = 0;
  torque_change(p, q[theta], &d, at);
  if (m < 0) {
    K(theta, theta) -= d;
    return;
  }
  const double t1 = b_.time_constant, t2 = b_.valve_time_constant;
  K(theta, m) -= 1;
  K(m, m) = 1;
  K(m, theta) = -d;
  C(m, m) = t1 + t2;
  add_mass(m, M);
}

template <class Matrix>
void Bellows::add_mass(int m, Matrix& M) const {
  if (on_ && m >= 0) M(m, m) = b_.time_constant * b_.valve_time_constant;
}

}  // namespace pcsim::pantograph
