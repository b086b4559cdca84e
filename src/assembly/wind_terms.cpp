#include "pcsim/assembly/wind_terms.hpp"

#include <mpi.h>

#include <algorithm>
#include <cmath>

#include "pcsim/assembly/coupled_state.hpp"
#include "pcsim/catenary/elements.hpp"
#include "pcsim/core/error.hpp"

namespace pcsim::assembly {

Eigen::Matrix3d aerodynamic_damping(const catenary::Wire& wire, const Eigen::Vector3d& tangent,
                                    const Eigen::Vector3d& velocity, double air_density) {
  const Eigen::Vector3d t = tangent.normalized();
  const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - t * t.transpose();
  const Eigen::Vector3d vn = P * velocity;
  const double speed = vn.norm();
  if (speed == 0) return Eigen::Matrix3d::Zero();  // wind along the wire: no drag
  const double k =
      0.5 * air_density * catenary::wire_drag_coefficient(wire) * catenary::wire_diameter(wire);
  return k * (speed * Eigen::Matrix3d::Identity() + vn * vn.transpose() / speed) * P;
}

void turbulent_drag_gradients(const catenary::Wire& wire, const Eigen::Vector3d& tangent,
                              const Eigen::Vector3d& velocity, double air_density,
                              Eigen::Vector3d& a, Eigen::Vector3d& b) {
  const Eigen::Matrix3d DP = aerodynamic_damping(wire, tangent, velocity, air_density);
  a = velocity.norm() > 0 ? Eigen::Vector3d(DP * velocity.normalized()) : Eigen::Vector3d::Zero();
  b = DP * Eigen::Vector3d::UnitZ();
}

AerodynamicDamping::AerodynamicDamping(FECatenary& catenary) {
  const auto& system = catenary.system();
  const auto& mesh = catenary.mesh();
  const auto& wind = mesh.conditions.wind;
  C_ = system.layout().create_matrix();  // the catenary's pattern: element blocks in the Jacobian's
  PetscInt idx[12];
  for (int e : system.layout().local_cables()) {
    const auto& el = mesh.cables[e];
    const Eigen::Matrix3d DP = aerodynamic_damping(
        mesh.wires[el.wire], mesh.nodes[el.nodes[1]].position - mesh.nodes[el.nodes[0]].position,
        wind.velocity(), wind.air_density);
    // (L0 / Lref) int S^T S dchi: the mass matrix of a unit mass per unstressed length.
    const catenary::Mat12 m = catenary::cable_mass_matrix(
        {1.0, 1.0, el.unstressed_length / el.ref_length}, el.ref_length);
    Eigen::Matrix<double, 12, 12, Eigen::RowMajor> c;
    for (int k = 0; k < 4; ++k)
      for (int j = 0; j < 4; ++j) c.block<3, 3>(3 * k, 3 * j) = m(3 * k, 3 * j) * DP;
    system.cable_indices(e, idx);  // negative (fixed) rows and columns are ignored
    PCSIM_PETSC(MatSetValues(C_, 12, idx, 12, idx, c.data(), ADD_VALUES));
  }
  PCSIM_PETSC(MatAssemblyBegin(C_, MAT_FINAL_ASSEMBLY));
  PCSIM_PETSC(MatAssemblyEnd(C_, MAT_FINAL_ASSEMBLY));
}

AerodynamicDamping::~AerodynamicDamping() {
  MatDestroy(&C_);
}

TermPower AerodynamicDamping::power(const CoupledState& state) const {
  TermPower p;
  if (state.V) p.dissipative = -quadratic_form(C_, state.V);
  return p;
}

namespace {

// The field's stations cover the line's cable nodes (design x).
catenary::WindSeries series(const catenary::CatenaryMesh& mesh, double sigma, double length,
                            std::uint64_t seed) {
  const auto& wind = mesh.conditions.wind;
  const auto& s = wind.turbulence;
  double lo = 1e300, hi = -1e300;
  for (const auto& el : mesh.cables)
    for (int n : el.nodes)
      lo = std::min(lo, mesh.nodes[n].position.x()), hi = std::max(hi, mesh.nodes[n].position.x());
  const int nx = std::max(2, static_cast<int>(std::ceil((hi - lo) / s.grid_spacing)) + 1);
  catenary::TurbulenceSpec spec{wind.speed, sigma, length, s.coherence_decay, seed};
  return catenary::generate_turbulence(spec, lo, s.grid_spacing, nx, s.time_step, s.time_points);
}

}  // namespace

WindTurbulence::WindTurbulence(FECatenary& catenary) {
  const auto& mesh = catenary.mesh();
  const auto& wind = mesh.conditions.wind;
  const auto& s = wind.turbulence;
  const double sigma_u = s.intensity * wind.speed;
  u_ = series(mesh, sigma_u, s.length_scale, s.seed);
  w_ = series(mesh, s.vertical_ratio * sigma_u, s.vertical_length_ratio * s.length_scale,
              s.seed + 0x9e3779b97f4a7c15ULL);  // an independent stream for w'
  const auto& system = catenary.system();
  for (int e : system.layout().local_cables()) {
    const auto& el = mesh.cables[e];
    const Eigen::Vector3d p0 = mesh.nodes[el.nodes[0]].position,
                          p1 = mesh.nodes[el.nodes[1]].position;
    Element out;
    system.cable_indices(e, out.idx.data());
    turbulent_drag_gradients(mesh.wires[el.wire], p1 - p0, wind.velocity(), wind.air_density, out.a,
                             out.b);
    out.x = 0.5 * (p0.x() + p1.x());
    out.ref_length = el.ref_length, out.unstressed_length = el.unstressed_length;
    elements_.push_back(out);
  }
}

WindTurbulence::~WindTurbulence() {
  if (work_) VecDestroy(&work_);
}

void WindTurbulence::add_loads(double t, Vec F, double sign) const {
  for (const auto& el : elements_) {
    const Eigen::Vector3d q = u_.interpolate(el.x, t) * el.a + w_.interpolate(el.x, t) * el.b;
    const catenary::Vec12 f =
        sign * catenary::cable_line_load(el.ref_length, el.unstressed_length, q);
    PetscInt idx[12];
    double values[12];
    int n = 0;
    for (int i = 0; i < 12; ++i)
      if (el.idx[i] >= 0) idx[n] = el.idx[i], values[n++] = f[i];  // -1: a fixed DOF
    PCSIM_PETSC(VecSetValues(F, n, idx, values, ADD_VALUES));
  }
}

void WindTurbulence::add_residual(const CoupledState& state, Vec F) {
  add_loads(state.t, F, -1.0);  // a load lowers the residual (R = M a + ... - f)
}

TermPower WindTurbulence::power(const CoupledState& state) const {
  TermPower p;
  if (!state.V) return p;
  if (!work_) PCSIM_PETSC(VecDuplicate(state.V, &work_));
  PCSIM_PETSC(VecSet(work_, 0.0));
  add_loads(state.t, work_, 1.0);
  PCSIM_PETSC(VecAssemblyBegin(work_));
  PCSIM_PETSC(VecAssemblyEnd(work_));
  PCSIM_PETSC(VecDot(work_, state.V, &p.external));
  return p;
}

}  // namespace pcsim::assembly
