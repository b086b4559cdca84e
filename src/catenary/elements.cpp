// Catenary element kernels (thesis 3.1.1-3.1.2); see elements.hpp for the
// formulation.
#include "pcsim/catenary/elements.hpp"

#include <algorithm>
#include <cmath>

namespace pcsim::catenary {
namespace {

// 5-point Gauss-Legendre rule on xi in [0, 1] (exact to degree 9: the axial
// energy integrand eps^2 is of degree 8 in xi).
constexpr int kGaussPoints = 5;
constexpr double kGaussXi[kGaussPoints] = {0.046910077030668004, 0.23076534494715845, 0.5,
                                           0.76923465505284155, 0.95308992296933200};
constexpr double kGaussWeight[kGaussPoints] = {0.11846344252809454, 0.23931433524968324,
                                               0.28444444444444444, 0.23931433524968324,
                                               0.11846344252809454};

// First derivatives of the Hermite functions with respect to chi at xi.
inline void hermite_ds(double xi, double Lref, double ds[4]) {
  const double xi2 = xi * xi;
  ds[0] = (-6.0 * xi + 6.0 * xi2) / Lref;
  ds[1] = 1.0 - 4.0 * xi + 3.0 * xi2;
  ds[2] = (6.0 * xi - 6.0 * xi2) / Lref;
  ds[3] = -2.0 * xi + 3.0 * xi2;
}

// Second derivatives with respect to chi at xi.
inline void hermite_dds(double xi, double Lref, double dds[4]) {
  dds[0] = (-6.0 + 12.0 * xi) / (Lref * Lref);
  dds[1] = (-4.0 + 6.0 * xi) / Lref;
  dds[2] = (6.0 - 12.0 * xi) / (Lref * Lref);
  dds[3] = (-2.0 + 6.0 * xi) / Lref;
}

// Sum_k coef[k] * (3-block k of q).
inline Eigen::Vector3d combine(const double coef[4], const Vec12& q) {
  return coef[0] * q.segment<3>(0) + coef[1] * q.segment<3>(3) + coef[2] * q.segment<3>(6) +
         coef[3] * q.segment<3>(9);
}

// Scalar 4x4 matrix EI int s''_k s''_m dchi of the Euler-Bernoulli beam.
inline Eigen::Matrix4d bending_matrix4(double EI, double L) {
  Eigen::Matrix4d k;
  const double L2 = L * L;
  k << 12.0, 6.0 * L, -12.0, 6.0 * L,         //
      6.0 * L, 4.0 * L2, -6.0 * L, 2.0 * L2,  //
      -12.0, -6.0 * L, 12.0, -6.0 * L,        //
      6.0 * L, 2.0 * L2, -6.0 * L, 4.0 * L2;
  return (EI / (L2 * L)) * k;
}

}  // namespace

HermiteValues hermite(double chi, double Lref) {
  HermiteValues h;
  const double xi = chi / Lref;
  const double xi2 = xi * xi;
  const double xi3 = xi2 * xi;
  h.s = {1.0 - 3.0 * xi2 + 2.0 * xi3, Lref * (xi - 2.0 * xi2 + xi3), 3.0 * xi2 - 2.0 * xi3,
         Lref * (-xi2 + xi3)};
  hermite_ds(xi, Lref, h.ds.data());
  hermite_dds(xi, Lref, h.dds.data());
  return h;
}

CablePoint cable_point(double Lref, const Vec12& q, double chi) {
  const HermiteValues h = hermite(chi, Lref);
  return {combine(h.s.data(), q), combine(h.ds.data(), q), combine(h.dds.data(), q)};
}

double cable_strain_energy(const CableSection& section, double Lref, double L0, const Vec12& q) {
  // Evaluated pointwise (not through the matrices of cable_internal_force) so
  // that finite differences of it check those matrices independently.
  const double c = Lref / L0;
  double energy = 0;
  for (int g = 0; g < kGaussPoints; ++g) {
    double ds[4], dds[4];
    hermite_ds(kGaussXi[g], Lref, ds);
    hermite_dds(kGaussXi[g], Lref, dds);
    const Eigen::Vector3d a = combine(ds, q);
    const Eigen::Vector3d kappa = combine(dds, q);
    const double eps = 0.5 * (c * c * a.squaredNorm() - 1.0);
    energy += kGaussWeight[g] * Lref *
              (0.5 * section.EA * eps * eps / c + 0.5 * section.EI * kappa.squaredNorm());
  }
  return energy;
}

void cable_internal_force(const CableSection& section, double Lref, double L0, const Vec12& q,
                          Vec12& f, Mat12* K, Vec12* df_dL0) {
  const double c = Lref / L0;
  const double EA = section.EA;
  f.setZero();
  if (K) K->setZero();
  if (df_dL0) df_dL0->setZero();
  // Scalar 4x4 matrix multiplying I3 blockwise: bending + geometric axial part.
  Eigen::Matrix4d block_scalar = bending_matrix4(section.EI, Lref);
  for (int k = 0; k < 4; ++k)
    for (int m = 0; m < 4; ++m) f.segment<3>(3 * k) += block_scalar(k, m) * q.segment<3>(3 * m);

  for (int g = 0; g < kGaussPoints; ++g) {
    double ds[4];
    hermite_ds(kGaussXi[g], Lref, ds);
    const Eigen::Vector3d a = combine(ds, q);  // r_chi
    const double a2 = a.squaredNorm();
    const double eps = 0.5 * (c * c * a2 - 1.0);
    const double w = kGaussWeight[g] * Lref;
    Vec12 b;  // b = S'^T r_chi = d(|r_chi|^2 / 2)/dq
    for (int k = 0; k < 4; ++k) b.segment<3>(3 * k) = ds[k] * a;
    // dU/dq = int EA eps c S'^T r_chi dchi
    f.noalias() += (w * EA * eps * c) * b;
    if (K) {
      K->noalias() += (w * EA * c * c * c) * (b * b.transpose());
      const double geo = w * EA * c * eps;
      for (int k = 0; k < 4; ++k)
        for (int m = 0; m < 4; ++m) block_scalar(k, m) += geo * ds[k] * ds[m];
    }
    // d(eps c)/dc = c^2 |r_chi|^2 + eps, dc/dL0 = -c/L0
    if (df_dL0) df_dL0->noalias() += (w * EA * (c * c * a2 + eps) * (-c / L0)) * b;
  }
  if (K) {
    for (int k = 0; k < 4; ++k)
      for (int m = 0; m < 4; ++m)
        K->block<3, 3>(3 * k, 3 * m).diagonal().array() += block_scalar(k, m);
  }
}

double cable_mean_axial_force(const CableSection& section, double Lref, double L0, const Vec12& q,
                              Vec12* dT_dq, double* dT_dL0) {
  const double c = Lref / L0;
  const double EA = section.EA;
  double mean = 0;
  if (dT_dq) dT_dq->setZero();
  if (dT_dL0) *dT_dL0 = 0;
  for (int g = 0; g < kGaussPoints; ++g) {
    double ds[4];
    hermite_ds(kGaussXi[g], Lref, ds);
    const Eigen::Vector3d a = combine(ds, q);
    const double a2 = a.squaredNorm();
    const double norm_a = std::sqrt(a2);
    const double eps = 0.5 * (c * c * a2 - 1.0);
    const double w = kGaussWeight[g];   // (1/Lref) int dchi = sum of xi weights
    mean += w * EA * eps * c * norm_a;  // T = EA eps lambda
    if (dT_dq && norm_a > 0) {
      // dT/dq = EA c (c^2 |a| + eps / |a|) S'^T a
      const double coef = w * EA * c * (c * c * norm_a + eps / norm_a);
      for (int k = 0; k < 4; ++k) dT_dq->segment<3>(3 * k) += (coef * ds[k]) * a;
    }
    // dT/dc = EA |a| (eps + c^2 |a|^2), dc/dL0 = -c/L0
    if (dT_dL0) *dT_dL0 += w * EA * norm_a * (eps + c * c * a2) * (-c / L0);
  }
  return mean;
}

Mat12 cable_mass_matrix(const CableSection& section, double Lref) {
  // mu int s_k s_m dchi: the classical consistent mass of the Hermite beam.
  const double L = Lref;
  Eigen::Matrix4d m;
  m << 156.0, 22.0 * L, 54.0, -13.0 * L,              //
      22.0 * L, 4.0 * L * L, 13.0 * L, -3.0 * L * L,  //
      54.0, 13.0 * L, 156.0, -22.0 * L,               //
      -13.0 * L, -3.0 * L * L, -22.0 * L, 4.0 * L * L;
  m *= section.mass_per_length * L / 420.0;
  Mat12 M = Mat12::Zero();
  for (int k = 0; k < 4; ++k)
    for (int j = 0; j < 4; ++j) M.block<3, 3>(3 * k, 3 * j).diagonal().array() = m(k, j);
  return M;
}

Vec12 cable_line_load(double Lref, double L0, const Eigen::Vector3d& q) {
  // (L0 / Lref) int s dchi = L0 [1/2, Lref/12, 1/2, -Lref/12]
  Vec12 f;
  f.segment<3>(0) = (L0 / 2.0) * q;
  f.segment<3>(3) = (L0 * Lref / 12.0) * q;
  f.segment<3>(6) = (L0 / 2.0) * q;
  f.segment<3>(9) = (-L0 * Lref / 12.0) * q;
  return f;
}

// The weight mu g per reference length: the line load with L0 -> mu Lref
// (the same products, in the same order, as the gravity load had of its own).
Vec12 cable_gravity_force(const CableSection& section, double Lref, const Eigen::Vector3d& g) {
  return cable_line_load(Lref, section.mass_per_length * Lref, g);
}

// ------------------------------------------------------------------ bar ----

namespace {

// Axial force N(l) and dN/dl, dN/dL0 (thesis 3.1.2 slack criteria).
inline double bar_force_of_length(const BarParameters& bar, double l, double* dN_dl,
                                  double* dN_dL0) {
  const double k = bar.stiffness;
  // dN/dL0 of N = k (l - L0): -k; with k = EA / L0 also (l - L0) dk/dL0,
  // together -k l / L0.
  const double stiff_dL0 = bar.axial_rigidity > 0 ? -k * l / bar.unstressed_length : -k;
  double N = 0, dl = 0, dL0 = 0;
  switch (bar.slack) {
    case SlackCriterion::none:
      N = k * (l - bar.unstressed_length);
      dl = k;
      dL0 = stiff_dL0;
      break;
    case SlackCriterion::force: {
      const double stretch = l - bar.unstressed_length;
      if (stretch > 0) {
        N = k * stretch;
        dl = k;
        dL0 = stiff_dL0;
      }
      break;
    }
    case SlackCriterion::length: {
      const double stretch = l - bar.equilibrium_length;
      N = bar.equilibrium_force;
      if (stretch > 0) {
        N += k * stretch;
        dl = k;
      }
      break;
    }
  }
  if (dN_dl) *dN_dl = dl;
  if (dN_dL0) *dN_dL0 = dL0;
  return N;
}

}  // namespace

double bar_axial_force(const BarParameters& bar, const Vec6& q, double* dN_dl) {
  const double l = (q.segment<3>(3) - q.segment<3>(0)).norm();
  return bar_force_of_length(bar, l, dN_dl, nullptr);
}

double bar_internal_force(const BarParameters& bar, const Vec6& q, Vec6& f, Mat6* K, Vec6* df_dL0) {
  const Eigen::Vector3d d = q.segment<3>(3) - q.segment<3>(0);
  const double l = d.norm();
  const Eigen::Vector3d e = l > 0 ? Eigen::Vector3d(d / l) : Eigen::Vector3d::Zero();
  double dN_dl = 0, dN_dL0 = 0;
  const double N = bar_force_of_length(bar, l, &dN_dl, &dN_dL0);
  f.segment<3>(0) = -N * e;
  f.segment<3>(3) = N * e;
  if (K) {
    Eigen::Matrix3d block = dN_dl * (e * e.transpose());
    if (l > 0) block += (N / l) * (Eigen::Matrix3d::Identity() - e * e.transpose());
    K->block<3, 3>(0, 0) = block;
    K->block<3, 3>(3, 3) = block;
    K->block<3, 3>(0, 3) = -block;
    K->block<3, 3>(3, 0) = -block;
  }
  if (df_dL0) {
    df_dL0->segment<3>(0) = -dN_dL0 * e;
    df_dL0->segment<3>(3) = dN_dL0 * e;
  }
  return N;
}

double bar_strain_energy(const BarParameters& bar, const Vec6& q) {
  const double l = (q.segment<3>(3) - q.segment<3>(0)).norm();
  const double k = bar.stiffness;
  switch (bar.slack) {
    case SlackCriterion::none: {
      const double s = l - bar.unstressed_length;
      return 0.5 * k * s * s;
    }
    case SlackCriterion::force: {
      const double s = std::max(l - bar.unstressed_length, 0.0);
      return 0.5 * k * s * s;
    }
    case SlackCriterion::length: {
      const double s = l - bar.equilibrium_length;
      const double active = std::max(s, 0.0);
      return bar.equilibrium_force * s + 0.5 * k * active * active;
    }
  }
  return 0;
}

Vec6 bar_lumped_mass(double mass) {
  return Vec6::Constant(0.5 * mass);
}

Vec6 bar_gravity_force(double mass, const Eigen::Vector3d& g) {
  Vec6 fg;
  fg.segment<3>(0) = (0.5 * mass) * g;
  fg.segment<3>(3) = (0.5 * mass) * g;
  return fg;
}

}  // namespace pcsim::catenary
