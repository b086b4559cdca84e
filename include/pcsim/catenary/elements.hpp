// Element kernels of the catenary model (thesis 3.1.1-3.1.2): the ANCF cable
// element (12 DOF, cubic Hermite in position and slope) and the axial bar
// element (6 DOF) used for droppers, steady arms and stitch wires.
//
// Pure functions, no PETSc, no heap allocation: they run millions of times in
// dynamics.
//
// Cable element DOFs q = [r_i, r'_i, r_j, r'_j] (3 each, thesis eq. 3.2),
// r' = dr/dchi, chi in [0, Lref]; Lref is the design (reference) length and
// never changes, L0 is the unstressed length (form-finding changes it).
//   r(chi) = s1 r_i + s2 r'_i + s3 r_j + s4 r'_j          (eq. 3.3)
//   lambda = |r_chi| Lref / L0,  eps = (lambda^2 - 1) / 2 (Green strain)
//   U = int_0^Lref [ 1/2 EA eps^2 (L0/Lref) + 1/2 EI |r_chichi|^2 ] dchi
//   axial force at a point: T = EA eps lambda
//
// Bar element DOFs q = [r_i, r_j]; l = |r_j - r_i|; axial force N(l) per the
// SlackCriterion of mesh.hpp.
#pragma once

#include <Eigen/Core>
#include <array>

#include "pcsim/catenary/mesh.hpp"

namespace pcsim::catenary {

using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;
using Vec12 = Eigen::Matrix<double, 12, 1>;
using Mat12 = Eigen::Matrix<double, 12, 12>;

// ---------------------------------------------------------------- cable ----

struct CableSection {
  double EA = 0;               // axial stiffness [N]
  double EI = 0;               // bending stiffness [N m^2]
  double mass_per_length = 0;  // per unit of chi (design length) [kg/m]
};

inline CableSection cable_section(const Wire& wire) {
  return {wire.EA, wire.EI, wire.mass_per_length};
}

// Section of one element of the wire: scaled by the element's section
// factor f (a worn wire: EA and the mass with the area, EI with its square).
// Wire::mass_per_length is per unstressed length (the wire as bought): the
// element's mass rho L0 spread over its design length Lref, so the mass per
// unit chi is rho L0 / Lref (depends on L0: form-finding differentiates it).
inline CableSection cable_section(const Wire& wire, const CableElement& element) {
  const double f = element.section_factor;
  return {wire.EA * f, wire.EI * f * f,
          wire.mass_per_length * f * element.unstressed_length / element.ref_length};
}

// Hermite shape functions (eq. 3.3) and their first and second derivatives
// with respect to chi, at chi in [0, Lref].
struct HermiteValues {
  std::array<double, 4> s{};    // s1..s4
  std::array<double, 4> ds{};   // ds_k/dchi
  std::array<double, 4> dds{};  // d2s_k/dchi2
};
HermiteValues hermite(double chi, double Lref);

// Position, slope and curvature vector of an element at chi.
struct CablePoint {
  Eigen::Vector3d r;         // r(chi)
  Eigen::Vector3d r_chi;     // dr/dchi
  Eigen::Vector3d r_chichi;  // d2r/dchi2
};
CablePoint cable_point(double Lref, const Vec12& q, double chi);

// Strain energy U (axial + bending) [J].
double cable_strain_energy(const CableSection& section, double Lref, double L0, const Vec12& q);

// Internal force f = dU/dq; optionally the tangent K = d2U/dq2 (symmetric)
// and df/dL0. K and df_dL0 may be null.
void cable_internal_force(const CableSection& section, double Lref, double L0, const Vec12& q,
                          Vec12& f, Mat12* K = nullptr, Vec12* df_dL0 = nullptr);

// Mean axial force Tbar = (1/Lref) int T dchi [N], optionally its exact
// gradients dTbar/dq and dTbar/dL0 (either may be null).
double cable_mean_axial_force(const CableSection& section, double Lref, double L0, const Vec12& q,
                              Vec12* dT_dq = nullptr, double* dT_dL0 = nullptr);

// Consistent mass matrix M = mass_per_length int S^T S dchi (constant).
Mat12 cable_mass_matrix(const CableSection& section, double Lref);

// Gravity force fg = mass_per_length int S^T g dchi for gravity vector g.
Vec12 cable_gravity_force(const CableSection& section, double Lref, const Eigen::Vector3d& g);

// Consistent force of a dead line load q per unstressed length (the mean
// wind's drag): f = (L0 / Lref) int S^T q dchi, as the weight; no tangent.
Vec12 cable_line_load(double Lref, double L0, const Eigen::Vector3d& q);

// ------------------------------------------------------------------ bar ----

struct BarParameters {
  double stiffness = 0;          // k [N/m]
  double unstressed_length = 0;  // L0 [m]
  SlackCriterion slack = SlackCriterion::none;
  double equilibrium_length = 0;  // l_eq [m] (criterion 'length')
  double equilibrium_force = 0;   // N_eq [N] (criterion 'length')
  // EA [N] of a bar given by it, 0 if not: then k = EA / L0 follows L0, and
  // the derivatives with respect to L0 include dk/dL0.
  double axial_rigidity = 0;
};

// With slack = false the bar's slack criterion is ignored: taut whatever its
// length (dropper slackening off; the static equilibrium is the same, since
// N_eq = k (l_eq - L0) there).
inline BarParameters bar_parameters(const BarElement& bar, bool slack = true) {
  const double k =
      bar.axial_rigidity > 0 ? bar.axial_rigidity / bar.unstressed_length : bar.stiffness;
  return {k,
          bar.unstressed_length,
          slack ? bar.slack : SlackCriterion::none,
          bar.equilibrium_length,
          bar.equilibrium_force,
          bar.axial_rigidity};
}

// Axial force N (tension positive) [N]; optionally dN/dl.
double bar_axial_force(const BarParameters& bar, const Vec6& q, double* dN_dl = nullptr);

// Internal force f = N [-e; e]; optionally the tangent K and df/dL0 (either
// may be null). Returns N.
double bar_internal_force(const BarParameters& bar, const Vec6& q, Vec6& f, Mat6* K = nullptr,
                          Vec6* df_dL0 = nullptr);

// Potential whose gradient is the internal force: 1/2 k (l - L0)^2 (none),
// 1/2 k max(l - L0, 0)^2 (force), N_eq (l - l_eq) + 1/2 k max(l - l_eq, 0)^2
// (length).
double bar_strain_energy(const BarParameters& bar, const Vec6& q);

// Lumped mass: half the bar mass at each node (diagonal of the 6x6 matrix).
Vec6 bar_lumped_mass(double mass);

// Gravity force: half the weight at each node.
Vec6 bar_gravity_force(double mass, const Eigen::Vector3d& g);

}  // namespace pcsim::catenary
