// Pantograph models for the pantograph–catenary interaction (thesis chapter 2).
//
// A model states its equations of motion in residual form WITHOUT the contact force:
//   R(t, q, q̇, q̈) = M(q) q̈ + f(q, q̇) − Q(t)
// (uplift, aerodynamic force, gravity, springs, dampers, friction and restraints as
// enabled). The contact force Fc ≥ 0 pushes the head DOWN; a coupling adds it as
//   R_total = R + Fc · e_c,   e_c = unit vector of contact_dof(),
// and the contact point height is q[contact_dof()] + contact_offset().
// Exact tangents dR/dq, dR/dq̇, dR/dq̈ are given for implicit integration (thesis 3.3.3).
#pragma once

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "pcsim/core/error.hpp"

namespace pcsim::pantograph {

// Power of the non-conservative generalised forces contained in R (W = ∫ P dt).
struct PowerSplit {
  double dissipative = 0;  // damper, friction (≤ 0 for passive elements)
  double external = 0;     // uplift force / bellows torque, aerodynamic force
  // Prescribed base motion: power of its time-dependent load on the lowest stage (lumped)
  // or of the moving frame's inertial load (no potential: a coupling adds it to the
  // external work as it is).
  double base = 0;
};

// Prescribed vertical motion of a pantograph's base (the vehicle roof): z_b(t) [m,
// upwards], v_b(t) = dz_b/dt [m/s] and a_b(t) = dv_b/dt [m/s²] (empty where z_b has no
// acceleration: a piecewise-linear file), defined for every t.
struct BaseMotion {
  std::function<double(double)> displacement, velocity, acceleration;
};

// z_b = A sin(2π f t), with its exact v_b and a_b (`base_motion: {type: harmonic}`).
BaseMotion harmonic_base_motion(double amplitude_m, double frequency_hz);

// The base motion of a model whose coordinates are measured in its base's frame
// (DSA-380 models): z_b, v_b, a_b, each 0 while no motion is set.
class MovingFrame {
 public:
  // Throws SolverError naming 'kind' unless the motion gives z_b, v_b and a_b.
  void set(BaseMotion motion, const std::string& kind);
  bool moves() const { return static_cast<bool>(motion_.acceleration); }
  double height(double t) const { return motion_.displacement ? motion_.displacement(t) : 0.0; }
  double velocity(double t) const { return motion_.velocity ? motion_.velocity(t) : 0.0; }
  double acceleration(double t) const {
    return motion_.acceleration ? motion_.acceleration(t) : 0.0;
  }

 private:
  BaseMotion motion_;
};

// The spring and damper that join coordinate `dof` to the base; dof < 0: the model has
// no such element (it does not take a base motion).
struct BaseSupport {
  int dof = -1;
  double stiffness = 0, damping = 0;
};

class PantographModel {
 public:
  virtual ~PantographModel();

  virtual std::string kind() const = 0;  // "lumped" | "dsa380" | "linearised" (for reports)
  virtual int dof_count() const = 0;
  virtual std::vector<std::string> dof_names() const = 0;
  // Index in q of the head's vertical coordinate.
  virtual int contact_dof() const = 0;
  // Contact point height = q[contact_dof()] + contact_offset().
  virtual double contact_offset() const = 0;

  virtual void residual(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                        const Eigen::VectorXd& qdd, Eigen::Ref<Eigen::VectorXd> R) const = 0;
  virtual void tangents(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                        const Eigen::VectorXd& qdd, Eigen::Ref<Eigen::MatrixXd> dR_dq,
                        Eigen::Ref<Eigen::MatrixXd> dR_dqd,
                        Eigen::Ref<Eigen::MatrixXd> dR_dqdd) const = 0;
  // The step tangent dR/dq + shift_v dR/dq̇ + shift_a dR/dq̈ as a sparse matrix (its
  // structural entries, some possibly 0), for a model with many coordinates and few
  // entries (the flexible DSA-380): no dense n x n matrix is formed. The entries are a
  // function of the state alone. False (J untouched): the model gives dense tangents only.
  virtual bool sparse_step_tangent(double /*t*/, const Eigen::VectorXd& /*q*/,
                                   const Eigen::VectorXd& /*qd*/, const Eigen::VectorXd& /*qdd*/,
                                   double /*shift_v*/, double /*shift_a*/,
                                   Eigen::SparseMatrix<double>& /*J*/) const {
    return false;
  }
  // mass() as a sparse matrix (its structural entries), for the same models (the HHT
  // α-term's inertia product at every step). False (M untouched): dense mass only.
  virtual bool sparse_mass(double /*t*/, const Eigen::VectorXd& /*q*/,
                           const Eigen::VectorXd& /*qd*/,
                           Eigen::SparseMatrix<double>& /*M*/) const {
    return false;
  }
  // dR/dq̈ at (t, q, q̇): every model's R is affine in q̈, R(q̈) = R(0) + M q̈ (the HHT
  // α-term's inertia product, solvers/hht.hpp). Default: the tangents' (at q̈ = 0).
  virtual void mass(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                    Eigen::Ref<Eigen::MatrixXd> M) const;
  // True if R is linear in (q, q̇, q̈) with constant tangents.
  virtual bool is_linear() const = 0;

  // Static equilibrium under a downward contact force F0 with the contact point at height
  // h0. Sets what the equilibrium fixes (DSA-380: bellows torque M0; lumped: the height
  // offset) and returns q0.
  virtual Eigen::VectorXd static_equilibrium(double contact_force, double working_height) = 0;
  // Working height [m] to use when a scene gives none. Models whose heights are measured
  // above their base (DSA-380) state their nominal height; models in absolute heights
  // (lumped) return 0: the coupling then takes the height of the point the head meets.
  virtual double default_working_height() const { return 0.0; }
  // The rounding floor of |R| at a static equilibrium [N]: Newton cannot go below it
  // (a coupled start in equilibrium to it is in equilibrium). 0: below any tolerance.
  virtual double static_residual_floor() const { return 0.0; }

  // Energies for the balance [T+V]_t − [T+V]_0 − W_dissipative − W_external = 0 (2.30–2.34).
  virtual double kinetic_energy(const Eigen::VectorXd& q, const Eigen::VectorXd& qd) const = 0;
  virtual double potential_energy(const Eigen::VectorXd& q) const = 0;
  virtual PowerSplit power(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd) const = 0;

  // Base motion (issue 25): the element joined to the base, and the prescribed motion of
  // the base (models with base_support().dof >= 0 only).
  virtual BaseSupport base_support() const { return {}; }
  virtual void set_base_motion(BaseMotion) {
    throw SolverError(kind() + " pantograph: no base motion");
  }
  // Models whose coordinates are measured in the frame of their base (DSA-380 models): a
  // base motion moves that frame, the residual gains the inertial load a_b(t) ·
  // base_inertia(q) (Σ m_i ∂z_i/∂q) and needs BaseMotion::acceleration.
  virtual bool moving_frame() const { return false; }
  virtual Eigen::VectorXd base_inertia(const Eigen::VectorXd& q) const {
    return Eigen::VectorXd::Zero(q.size());
  }
  // Moving frame with a base motion: z_b(t), v_b(t) (0 otherwise). The contact point's
  // absolute height is q[contact_dof()] + contact_offset() + frame_height(t).
  virtual double frame_height(double) const { return 0.0; }
  virtual double frame_velocity(double) const { return 0.0; }
};

}  // namespace pcsim::pantograph
