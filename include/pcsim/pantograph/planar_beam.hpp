// Two-node co-rotational planar beam (Euler–Bernoulli), for the flexible-bar DSA-380
// (thesis 2.2). Nodal coordinates are absolute: qe = {x1, y1, φ1, x2, y2, φ2}, φ the
// rotation of the cross-section (equal to the bar's angle while the bar is straight).
//
// Why co-rotational: the pantograph's bars turn through tens of degrees as the frame rises
// but deform by millimetres. The co-rotational split (Crisfield 1991, vol. 1 ch. 7;
// Battini 2002) moves each element rigidly with its chord, so any rigid motion is exact
// and strain-free however large the rotation, and it keeps the deformation in three
// small scalars with the linear beam law. Its nodal unknowns (x, y, φ) make a revolute
// joint simply a shared (x, y) pair with independent φ's, as the thesis couples the
// nodes. (A 2D ANCF element would carry slopes instead of φ, and would make torques on
// a node, such as the bellows torque and the drive spring, a constraint on the slopes.)
//
// Strains (chord length l, chord angle β = atan2(Δy, Δx), offsets c_i = φ_i − β in the
// stress-free state):
//   ε = {u, θ̄1, θ̄2} = {l − l0, φ1 − β − c1, φ2 − β − c2}   (θ̄ wrapped to (−π, π])
// Energy V = ½ εᵀ D ε, D = diag(EA/l0, (EI/l0) [4 2; 2 4]); a hinge at end 2 (moment
// released, φ2 unused) gives the statically condensed D = diag(EA/l0, 3EI/l0, 0), exact for
// the linear local law. Internal force dV/dqe = Bᵀ D ε, B = dε/dqe, and its exact Hessian
// Bᵀ D B + N ∂²l + (M1 + M2) ∂²(−β) (the second terms are the geometric stiffness that
// carries the prestress).
//
// Mass (constant in global axes): translations interpolated linearly along the chord
// (ρA l0/6 [2 1; 1 2] per direction) and the section's rotary inertia ρI l0/2 lumped on
// each φ. For any rigid motion of the element this kinetic energy is exact,
// ½ m v_G² + ½ (m l0²/12 + ρ I l0) ω², i.e. the rigid model's bar inertia.
#pragma once

#include <Eigen/Dense>

namespace pcsim::pantograph {

using Vector6 = Eigen::Matrix<double, 6, 1>;
using Matrix6 = Eigen::Matrix<double, 6, 6>;
using Matrix36 = Eigen::Matrix<double, 3, 6>;

struct PlanarBeamSection {
  double EA = 0, EI = 0;                 // axial and bending stiffness (N, N m²)
  double mass_per_length = 0;            // ρA (kg/m)
  double rotary_inertia_per_length = 0;  // ρI (kg m)
};

struct PlanarBeamElement {
  PlanarBeamSection section;
  double length0 = 0;               // stress-free chord length
  double offset1 = 0, offset2 = 0;  // c1, c2: φ_i − β in the stress-free state
  bool hinge_end2 = false;          // moment released at node 2
};

struct PlanarBeamState {
  double energy = 0;
  Eigen::Vector3d strain = Eigen::Vector3d::Zero();  // u, θ̄1, θ̄2
  Eigen::Vector3d stress = Eigen::Vector3d::Zero();  // N, M1, M2 = D ε
  Vector6 force = Vector6::Zero();                   // dV/dqe
  Matrix6 stiffness = Matrix6::Zero();               // d²V/dqe² (if requested)
};

// Angle wrapped to (−π, π].
double wrap_angle(double a);

// D of the element (3×3).
Eigen::Matrix3d planar_beam_constitutive(const PlanarBeamElement& e);
// B = dε/dqe at qe.
Matrix36 planar_beam_strain_gradient(const PlanarBeamElement& e, const Vector6& qe);
// Energy, internal force and (with_stiffness) exact tangent at qe.
PlanarBeamState planar_beam_evaluate(const PlanarBeamElement& e, const Vector6& qe,
                                     bool with_stiffness);
// Constant mass matrix (see above) and the weight dVg/dqe for gravity g along −y.
Matrix6 planar_beam_mass(const PlanarBeamElement& e);
Vector6 planar_beam_weight(const PlanarBeamElement& e, double g);

}  // namespace pcsim::pantograph
