#include "pcsim/assembly/wind_terms.hpp"

#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "pcsim/assembly/coupled_state.hpp"
#include "pcsim/catenary/elements.hpp"
#include "pcsim/catenary/wind.hpp"
#include "pcsim/core/error.hpp"

namespace pcsim::assembly {

Eigen::Matrix3d aerodynamic_damping(const DragSection& section, const Eigen::Vector3d& tangent,
                                    const Eigen::Vector3d& velocity, double air_density) {
  const Eigen::Vector3d t = tangent.normalized();
  const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - t * t.transpose();
  const Eigen::Vector3d vn = P * velocity;
  const double speed = vn.norm();
  if (speed == 0) return Eigen::Matrix3d::Zero();  // wind along the member: no drag
  const double k = 0.5 * air_density * section.drag_coefficient * section.diameter;
  return k * (speed * Eigen::Matrix3d::Identity() + vn * vn.transpose() / speed) * P;
}

DragSection wire_section(const catenary::Wire& wire) {
  return {catenary::wire_diameter(wire), catenary::wire_drag_coefficient(wire)};
}

DragSection bar_section(const catenary::BarElement& bar) {
  return {catenary::bar_diameter(bar), catenary::bar_drag_coefficient(bar)};
}

void turbulent_drag_gradients(const DragSection& section, const Eigen::Vector3d& tangent,
                              const Eigen::Vector3d& velocity, double air_density,
                              Eigen::Vector3d& a, Eigen::Vector3d& b) {
  const Eigen::Matrix3d DP = aerodynamic_damping(section, tangent, velocity, air_density);
  a = velocity.norm() > 0 ? Eigen::Vector3d(DP * velocity.normalized()) : Eigen::Vector3d::Zero();
  b = DP * Eigen::Vector3d::UnitZ();
}

std::vector<WindBar> wind_bars(const CatenarySystem& system) {
  const auto& mesh = system.mesh();
  const auto& wind = mesh.conditions.wind;
  std::vector<WindBar> out;
  for (int b : system.layout().local_bars()) {
    const auto& bar = mesh.bars[b];
    if (catenary::bar_diameter(bar) <= 0) continue;
    const Eigen::Vector3d p0 = mesh.nodes[bar.nodes[0]].position,
                          p1 = mesh.nodes[bar.nodes[1]].position;
    const double half = 0.5 * (p1 - p0).norm();
    WindBar w;
    system.bar_indices(b, w.idx.data());
    w.damping =
        half * aerodynamic_damping(bar_section(bar), p1 - p0, wind.velocity(), wind.air_density);
    turbulent_drag_gradients(bar_section(bar), p1 - p0, wind.velocity(), wind.air_density, w.a,
                             w.b);
    w.a *= half, w.b *= half;
    w.x = 0.5 * (p0.x() + p1.x());
    out.push_back(w);
  }
  return out;
}

Mat aerodynamic_damping_matrix(const CatenarySystem& system) {
  const auto& mesh = system.mesh();
  const auto& wind = mesh.conditions.wind;
  Mat C = system.layout().create_matrix();  // the catenary's pattern: element blocks
  PetscInt idx[12];
  for (int e : system.layout().local_cables()) {
    const auto& el = mesh.cables[e];
    const Eigen::Matrix3d DP =
        aerodynamic_damping(wire_section(mesh.wires[el.wire]),
                            mesh.nodes[el.nodes[1]].position - mesh.nodes[el.nodes[0]].position,
                            wind.velocity(), wind.air_density);
    // (L0 / Lref) int S^T S dchi: the mass matrix of a unit mass per unstressed length.
    const catenary::Mat12 m = catenary::cable_mass_matrix(
        {1.0, 1.0, el.unstressed_length / el.ref_length}, el.ref_length);
    Eigen::Matrix<double, 12, 12, Eigen::RowMajor> c;
    for (int k = 0; k < 4; ++k)
      for (int j = 0; j < 4; ++j) c.block<3, 3>(3 * k, 3 * j) = m(3 * k, 3 * j) * DP;
    system.cable_indices(e, idx);  // negative (fixed) rows and columns are ignored
    PCSIM_PETSC(MatSetValues(C, 12, idx, 12, idx, c.data(), ADD_VALUES));
  }
  for (const WindBar& bar : wind_bars(system))  // half of each bar's on each end node
    for (int end = 0; end < 2; ++end) {
      const Eigen::Matrix<double, 3, 3, Eigen::RowMajor> c = bar.damping;
      PCSIM_PETSC(
          MatSetValues(C, 3, &bar.idx[3 * end], 3, &bar.idx[3 * end], c.data(), ADD_VALUES));
    }
  PCSIM_PETSC(MatAssemblyBegin(C, MAT_FINAL_ASSEMBLY));
  PCSIM_PETSC(MatAssemblyEnd(C, MAT_FINAL_ASSEMBLY));
  return C;
}

AerodynamicDamping::AerodynamicDamping(FECatenary& catenary)
    : C_(aerodynamic_damping_matrix(catenary.system())) {}

AerodynamicDamping::~AerodynamicDamping() {
  MatDestroy(&C_);
}

TermPower AerodynamicDamping::power(const CoupledState& state) const {
  TermPower p;
  if (state.V) p.dissipative = -quadratic_form(C_, state.V);
  return p;
}

// u' with sigma_u = I_u V; w' with sigma_w = vertical_ratio sigma_u, its length
// scale vertical_length_ratio L_u and an independent seed.
LineTurbulence::LineTurbulence(const catenary::CatenaryMesh& mesh) {
  const auto& wind = mesh.conditions.wind;
  const auto& s = wind.turbulence;
  const catenary::TurbulenceGrid grid = catenary::turbulence_grid(mesh);
  const double sigma_u = s.intensity * wind.speed;
  const catenary::TurbulenceSpec spec_u{wind.speed, sigma_u, s.length_scale, s.coherence_decay,
                                        s.seed};
  const catenary::TurbulenceSpec spec_w{wind.speed, s.vertical_ratio * sigma_u,
                                        s.vertical_length_ratio * s.length_scale, s.coherence_decay,
                                        s.seed + 0x9e3779b97f4a7c15ULL};
  u_line_ = std::make_unique<catenary::TurbulenceGenerator>(spec_u, grid.spacing, s.time_step,
                                                            s.time_points);
  w_line_ = std::make_unique<catenary::TurbulenceGenerator>(spec_w, grid.spacing, s.time_step,
                                                            s.time_points);
  const std::vector<double> zeros(static_cast<std::size_t>(grid.count) * s.time_points, 0.0);
  u = w = {grid.x0, grid.spacing, s.time_step, grid.count, s.time_points, zeros};
  follow(0.0);  // the line's own first stations
}

void LineTurbulence::follow(double offset) {
  catenary::take_line_field(*u_line_, offset, u);
  catenary::take_line_field(*w_line_, offset, w);
}

Mat turbulence_load_matrix(const CatenarySystem& system) {
  const auto& mesh = system.mesh();
  const auto& wind = mesh.conditions.wind;
  const catenary::TurbulenceGrid grid = catenary::turbulence_grid(mesh);
  const PetscInt columns = 2 * grid.count;
  Vec like = system.create_vector();
  PetscInt local = 0;
  PCSIM_PETSC(VecGetLocalSize(like, &local));
  PCSIM_PETSC(VecDestroy(&like));
  Mat L;
  // A row has at most 4 entries: two stations, two components.
  PCSIM_PETSC(MatCreateAIJ(system.comm(), local, PETSC_DECIDE, PETSC_DETERMINE, columns, 4, nullptr,
                           4, nullptr, &L));
  PCSIM_PETSC(MatSetOption(L, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_FALSE));
  for (int e : system.layout().local_cables()) {
    const auto& el = mesh.cables[e];
    const Eigen::Vector3d p0 = mesh.nodes[el.nodes[0]].position,
                          p1 = mesh.nodes[el.nodes[1]].position;
    Eigen::Vector3d a, b;
    turbulent_drag_gradients(wire_section(mesh.wires[el.wire]), p1 - p0, wind.velocity(),
                             wind.air_density, a, b);
    // The field at the element's middle, linear between two stations (WindSeries::interpolate).
    const catenary::Bracket s =
        catenary::station_bracket(0.5 * (p0.x() + p1.x()), grid.x0, grid.spacing, grid.count);
    const int station[2] = {s.lo, s.hi};
    const double weights[2] = {1 - s.w, s.w};
    PetscInt idx[12];
    system.cable_indices(e, idx);
    for (int c = 0; c < 2; ++c) {
      const catenary::Vec12 f =
          catenary::cable_line_load(el.ref_length, el.unstressed_length, c == 0 ? a : b);
      for (int k = 0; k < 2; ++k) {
        const PetscInt column = c * grid.count + station[k];
        for (int r = 0; r < 12; ++r)
          if (idx[r] >= 0)
            PCSIM_PETSC(MatSetValue(L, idx[r], column, weights[k] * f[r], ADD_VALUES));
      }
    }
  }
  for (const WindBar& bar : wind_bars(system)) {
    const catenary::Bracket s = catenary::station_bracket(bar.x, grid.x0, grid.spacing, grid.count);
    for (int c = 0; c < 2; ++c)
      for (int k = 0; k < 2; ++k) {
        const PetscInt column = c * grid.count + (k == 0 ? s.lo : s.hi);
        const double weight = k == 0 ? 1 - s.w : s.w;
        const Eigen::Vector3d& f = c == 0 ? bar.a : bar.b;
        for (int r = 0; r < 6; ++r)
          if (bar.idx[r] >= 0)
            PCSIM_PETSC(MatSetValue(L, bar.idx[r], column, weight * f[r % 3], ADD_VALUES));
      }
  }
  PCSIM_PETSC(MatAssemblyBegin(L, MAT_FINAL_ASSEMBLY));
  PCSIM_PETSC(MatAssemblyEnd(L, MAT_FINAL_ASSEMBLY));
  return L;
}

WindTurbulence::WindTurbulence(FECatenary& catenary) : field_(catenary.mesh()) {
  const auto& mesh = catenary.mesh();
  const auto& wind = mesh.conditions.wind;
  const auto& system = catenary.system();
  for (int e : system.layout().local_cables()) {
    const auto& el = mesh.cables[e];
    const Eigen::Vector3d p0 = mesh.nodes[el.nodes[0]].position,
                          p1 = mesh.nodes[el.nodes[1]].position;
    Element out;
    system.cable_indices(e, out.idx.data());
    turbulent_drag_gradients(wire_section(mesh.wires[el.wire]), p1 - p0, wind.velocity(),
                             wind.air_density, out.a, out.b);
    out.x = 0.5 * (p0.x() + p1.x());
    out.ref_length = el.ref_length, out.unstressed_length = el.unstressed_length;
    elements_.push_back(out);
  }
  bars_ = wind_bars(system);
}

void WindTurbulence::follow(double offset) {
  field_.follow(offset);
}

WindTurbulence::~WindTurbulence() {
  if (work_) VecDestroy(&work_);
}

void WindTurbulence::add_loads(double t, Vec F, double sign) const {
  for (const auto& el : elements_) {
    const Eigen::Vector3d q =
        field_.u.interpolate(el.x, t) * el.a + field_.w.interpolate(el.x, t) * el.b;
    const catenary::Vec12 f =
        sign * catenary::cable_line_load(el.ref_length, el.unstressed_length, q);
    PetscInt idx[12];
    double values[12];
    int n = 0;
    for (int i = 0; i < 12; ++i)
      if (el.idx[i] >= 0) idx[n] = el.idx[i], values[n++] = f[i];  // -1: a fixed DOF
    PCSIM_PETSC(VecSetValues(F, n, idx, values, ADD_VALUES));
  }
  for (const auto& bar : bars_) {  // half of the bar's load on each end node
    const Eigen::Vector3d q =
        sign * (field_.u.interpolate(bar.x, t) * bar.a + field_.w.interpolate(bar.x, t) * bar.b);
    PetscInt idx[6];
    double values[6];
    int n = 0;
    for (int i = 0; i < 6; ++i)
      if (bar.idx[i] >= 0) idx[n] = bar.idx[i], values[n++] = q[i % 3];
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
