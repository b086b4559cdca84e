// Linearised pantograph about a static equilibrium (thesis 2.1.2, Annex B), its modes
// (2.21–2.28) with Eigen (the SLEPc solves, cross-checked against these, are in
// solvers/pantograph_modes.hpp), and receptance FRFs: direct (2.36) and by modal
// superposition of the damped state-space modes (2.37–2.40).
#pragma once

#include <complex>
#include <string>
#include <vector>

#include "pcsim/pantograph/model.hpp"

namespace pcsim::pantograph {

// M Δq̈ + C Δq̇ + K Δq = 0 (2.20): the tangents of R at (q0, 0, 0).
struct LinearModel {
  Eigen::MatrixXd M, C, K;
  Eigen::VectorXd q0;
  std::vector<std::string> dof_names;
};
LinearModel linearise(const PantographModel& model, const Eigen::VectorXd& q0);

// The linearised model as a PantographModel (for linear vs nonlinear time responses):
//   R = M q̈ + C q̇ + K (q − q0) − F0 e_c,
// in equilibrium at q0 under the contact force F0 used to build it.
class LinearisedPantograph : public PantographModel {
 public:
  LinearisedPantograph(LinearModel lin, int contact_dof, double contact_offset,
                       double contact_force);
  std::string kind() const override { return "linearised"; }
  int dof_count() const override { return static_cast<int>(lin_.M.rows()); }
  std::vector<std::string> dof_names() const override { return lin_.dof_names; }
  int contact_dof() const override { return c_; }
  double contact_offset() const override { return offset_; }
  void residual(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                const Eigen::VectorXd& qdd, Eigen::Ref<Eigen::VectorXd> R) const override;
  void tangents(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                const Eigen::VectorXd& qdd, Eigen::Ref<Eigen::MatrixXd> dR_dq,
                Eigen::Ref<Eigen::MatrixXd> dR_dqd,
                Eigen::Ref<Eigen::MatrixXd> dR_dqdd) const override;
  bool is_linear() const override { return true; }
  // Returns q0 (the linearisation point; F0 and h0 are fixed at construction).
  Eigen::VectorXd static_equilibrium(double, double) override { return lin_.q0; }
  double kinetic_energy(const Eigen::VectorXd& q, const Eigen::VectorXd& qd) const override;
  double potential_energy(const Eigen::VectorXd& q) const override;
  PowerSplit power(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd) const override;

 private:
  LinearModel lin_;
  int c_;
  double offset_, F0_;
};

struct Mode {
  std::complex<double> eigenvalue;  // λ = ω(−ζ + i√(1−ζ²)) (damped); iω (undamped)
  double frequency_hz = 0;          // ω / 2π (undamped natural frequency for damped modes)
  double damping_ratio = 0;
  Eigen::VectorXcd shape;         // Δq part, scaled to unit max modulus
  Eigen::VectorXcd state_vector;  // damped: full state eigenvector Y = {Δq, Δq̇} (2.26)
  int dominant_dof = -1;          // coordinate with the largest share of M_ii |φ_i|²
  bool real_root = false;         // damped: overdamped (real λ, no conjugate)
};

// Restrained rows: rows that a restraint replaced by an acceleration constraint
// m_r · Δq̈ = 0 (A.37, A.38), recognised by their K and C rows being exactly zero.
std::vector<int> restrained_rows(const LinearModel& lin);
// Every mode with λ ≠ 0 satisfies the restrained rows' m_r · φ = 0 (each such row would
// add a zero eigenvalue, a defective double one in the state-space form). The modes are
// those of the other rows on the null space of the constraints, Δq = T ψ:
//   reduced.K = K_F T, reduced.C = C_F T, reduced.M = M_F T  (F: the other rows),
// square, with M_F T invertible. Without restraints T = I and reduced = lin.
struct RestraintReduction {
  LinearModel reduced;
  Eigen::MatrixXd T;
};
RestraintReduction reduce_restraints(const LinearModel& lin);
// State vectors {ψ, λψ} of the reduced pencil as {Tψ, λTψ}.
Eigen::MatrixXcd expand_state(const Eigen::MatrixXd& T, const Eigen::MatrixXcd& Y);

// Undamped: (K − ω² M) φ = 0 (2.23) on the restraints' null space; modes with ω > 0,
// ascending. Nothing is dropped by the size of ω, so the 0.66 Hz modes of a model whose
// beams reach 1e5 Hz stay.
std::vector<Mode> undamped_modes_eigen(const LinearModel& lin);
// Damped: state-space form [C M; M 0] Ẏ + [K 0; 0 −M] Y = 0 (2.27); one mode per
// complex-conjugate pair (Im λ > 0), ascending in ω.
std::vector<Mode> damped_modes_eigen(const LinearModel& lin);

// State-space matrices A = [C M; M 0], B = [K 0; 0 −M] of (2.27): (λ A + B) Y = 0.
void state_space(const LinearModel& lin, Eigen::MatrixXd* A, Eigen::MatrixXd* B);
// Modes from all eigenpairs of K φ = λ M φ (λ = ω²), whichever solver found them, with the
// vectors in the full coordinates (T times those of the reduced pencil).
std::vector<Mode> undamped_modes_from_eigenpairs(const LinearModel& lin,
                                                 const Eigen::VectorXcd& lambda,
                                                 const Eigen::MatrixXcd& vectors);
// Modes from all eigenpairs of (λ A + B) Y = 0 (2.27), whichever solver found them, with
// Y in the full coordinates (diag(T, T) times those of the reduced pencil).
std::vector<Mode> damped_modes_from_eigenpairs(const LinearModel& lin,
                                               const Eigen::VectorXcd& lambda,
                                               const Eigen::MatrixXcd& vectors);

// The dynamic stiffness K + iωC − ω²M.
Eigen::MatrixXcd dynamic_stiffness(const LinearModel& lin, double omega);
// Receptance H_ij(ω) = [K + iωC − ω²M]⁻¹_ij (2.36).
std::complex<double> frf_direct(const LinearModel& lin, int i, int j, double omega);
// Base-to-coordinate-i transmissibility z_i / z_b = H_i,d(ω) (k + iωc) (issue 25): a base
// motion z_b e^{iωt} loads the coordinate d joined to the base by (k, c) with (k + iωc) z_b.
std::complex<double> transmissibility_direct(const LinearModel& lin, const BaseSupport& base, int i,
                                             double omega);
// The same for a model in the moving frame of its base (vertical coordinate i measured
// above the base): z_b e^{iωt} loads it with −a_b b = ω² z_b b, b = ∂R/∂a_b =
// PantographModel::base_inertia(q0), so z_i / z_b = 1 + [K + iωC − ω²M]⁻¹_i· ω² b.
std::complex<double> transmissibility_frame(const LinearModel& lin, const Eigen::VectorXd& inertia,
                                            int i, double omega);
// H_ij(ω) = Σ_r φ_r,i φ_r,j / (a_r (iω − λ_r)) + conj. (2.40), a_r = φ_rᵀ A φ_r, with the
// damped state-space modes, at each ω of `omegas` (a_r computed once); requires symmetric
// M, C, K.
std::vector<std::complex<double>> frf_modal(const LinearModel& lin, const std::vector<Mode>& damped,
                                            int i, int j, const std::vector<double>& omegas);
std::complex<double> frf_modal(const LinearModel& lin, const std::vector<Mode>& damped, int i,
                               int j, double omega);

}  // namespace pcsim::pantograph
