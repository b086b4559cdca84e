#include "pcsim/assembly/catenary_system.hpp"

#include <Eigen/Dense>

#include "pcsim/catenary/elements.hpp"
#include "pcsim/core/error.hpp"

namespace pcsim::assembly {

using namespace pcsim::catenary;
using RowMat12 = Eigen::Matrix<double, 12, 12, Eigen::RowMajor>;
using RowMat6 = Eigen::Matrix<double, 6, 6, Eigen::RowMajor>;

CatenarySystem::CatenarySystem(MPI_Comm comm, CatenaryMesh mesh, PetscInt extra_dofs,
                               const std::vector<int>* node_owner)
    : mesh_(std::move(mesh)) {
  layout_ = std::make_unique<DofLayout>(comm, mesh_, extra_dofs, node_owner);
  design_values_.resize(6 * mesh_.nodes.size());
  for (std::size_t n = 0; n < mesh_.nodes.size(); ++n)
    for (int c = 0; c < 3; ++c) {
      design_values_[6 * n + c] = mesh_.nodes[n].position[c];
      design_values_[6 * n + 3 + c] = mesh_.nodes[n].slope[c];
    }
  node_state_.assign(6 * layout_->needed_nodes().size(), 0.0);
  for (std::size_t i = 0; i < layout_->needed_nodes().size(); ++i)
    for (int c = 0; c < 6; ++c)
      node_state_[6 * i + c] = design_values_[6 * layout_->needed_nodes()[i] + c];
  gathered_ = layout_->create_gathered_vector();
  residual_gathered_ = layout_->create_gathered_vector();
}

CatenarySystem::~CatenarySystem() {
  VecDestroy(&gathered_);
  VecDestroy(&residual_gathered_);
}

void CatenarySystem::design_state(Vec x) const {
  PetscScalar* a;
  PCSIM_PETSC(VecGetArray(x, &a));
  const PetscInt first = layout_->first_owned();
  for (int n : layout_->owned_nodes())
    for (int c = 0; c < 6; ++c) {
      PetscInt g = layout_->global_dof(n, c);
      if (g >= 0) a[g - first] = design_values_[6 * n + c];
    }
  PCSIM_PETSC(VecRestoreArray(x, &a));
}

void CatenarySystem::load_state(Vec x) {
  // On one rank the copy into the gathered vector is a pass over the state
  // for nothing (four a step): the global array is read in its place.
  Vec source = layout_->gather_identity() ? x : gathered_;
  if (source != x) layout_->gather(x, gathered_);
  const PetscScalar* a;
  PCSIM_PETSC(VecGetArrayRead(source, &a));
  const auto& needed = layout_->needed_nodes();
  for (std::size_t i = 0; i < needed.size(); ++i)
    for (int c = 0; c < 6; ++c) {
      PetscInt p = layout_->gathered_position(static_cast<int>(i), c);
      if (p >= 0) node_state_[6 * i + c] = a[p];
    }
  PCSIM_PETSC(VecRestoreArrayRead(source, &a));
}

Eigen::Matrix<double, 6, 1> CatenarySystem::node_values(int node) const {
  int i = layout_->needed_index(node);
  if (i < 0) throw SolverError("node " + std::to_string(node) + " is not available on this rank");
  return Eigen::Map<const Eigen::Matrix<double, 6, 1>>(&node_state_[6 * i]);
}

void CatenarySystem::cable_indices(int element, PetscInt idx[12]) const {
  const auto& e = mesh_.cables[element];
  for (int a = 0; a < 2; ++a)
    for (int c = 0; c < 6; ++c) idx[6 * a + c] = layout_->global_dof(e.nodes[a], c);
}

void CatenarySystem::bar_indices(int bar, PetscInt idx[6]) const {
  const auto& b = mesh_.bars[bar];
  for (int a = 0; a < 2; ++a)
    for (int c = 0; c < 3; ++c) idx[3 * a + c] = layout_->global_dof(b.nodes[a], c);
}

void CatenarySystem::cable_values(int element, double q[12]) const {
  const auto& e = mesh_.cables[element];
  for (int a = 0; a < 2; ++a) {
    const double* v = &node_state_[6 * layout_->needed_index(e.nodes[a])];
    for (int c = 0; c < 6; ++c) q[6 * a + c] = v[c];
  }
}

void CatenarySystem::bar_values(int bar, double q[6]) const {
  const auto& b = mesh_.bars[bar];
  for (int a = 0; a < 2; ++a) {
    const double* v = &node_state_[6 * layout_->needed_index(b.nodes[a])];
    for (int c = 0; c < 3; ++c) q[3 * a + c] = v[c];
  }
}

double* CatenarySystem::begin_residual() {
  PCSIM_PETSC(VecSet(residual_gathered_, 0.0));
  PCSIM_PETSC(VecGetArray(residual_gathered_, &residual_array_));
  return residual_array_;
}

void CatenarySystem::end_residual(Vec R) {
  PCSIM_PETSC(VecRestoreArray(residual_gathered_, &residual_array_));
  residual_array_ = nullptr;
  layout_->scatter_add(residual_gathered_, R);
}

void CatenarySystem::add_node_residual(double* r, int node, int c, double value) const {
  PetscInt p = layout_->gathered_position(layout_->needed_index(node), c);
  if (p >= 0) r[p] += value;
}

void CatenarySystem::insert_element_pattern(Mat A) const {
  const auto& L = *layout_;
  PetscInt idx12[12], idx6[6];
  const double zeros[144] = {0};
  for (int e : L.local_cables()) {
    cable_indices(e, idx12);
    PCSIM_PETSC(MatSetValues(A, 12, idx12, 12, idx12, zeros, ADD_VALUES));
  }
  for (int b : L.local_bars()) {
    bar_indices(b, idx6);
    PCSIM_PETSC(MatSetValues(A, 6, idx6, 6, idx6, zeros, ADD_VALUES));
  }
  // Diagonal of every owned row (point masses, springs, extras).
  for (PetscInt i = L.first_owned(); i < L.first_owned() + L.local_size(); ++i)
    PCSIM_PETSC(MatSetValue(A, i, i, 0.0, ADD_VALUES));
}

void CatenarySystem::assemble_static(Vec R, Mat J, unsigned terms) {
  PCSIM_PETSC(VecSet(R, 0.0));
  add_forces(R, J, terms);
}

// Adds the element vector f (dofs_per_node per node) into the gathered
// residual array r.
void CatenarySystem::add_block(double* r, const int* nodes, int dofs_per_node,
                               const double* f) const {
  if (!r) return;
  for (int a = 0; a < 2; ++a) {
    const int i = layout_->needed_index(nodes[a]);
    for (int c = 0; c < dofs_per_node; ++c) {
      const PetscInt p = layout_->gathered_position(i, c);
      if (p >= 0) r[p] += f[dofs_per_node * a + c];
    }
  }
}

void CatenarySystem::add_cable_forces(double* r, Mat J, bool cables, bool loads) const {
  Vec12 q12, f12;
  Mat12 K12;
  RowMat12 K12r;
  PetscInt idx12[12];
  for (int e : layout_->local_cables()) {
    const auto& el = mesh_.cables[e];
    const auto section = cable_section(mesh_.wires[el.wire], el);
    f12.setZero();
    if (cables) {
      cable_values(e, q12.data());
      cable_internal_force(section, el.ref_length, el.unstressed_length, q12, f12,
                           J ? &K12 : nullptr, nullptr);
    }
    if (loads) f12 -= cable_gravity_force(section, el.ref_length, mesh_.gravity);
    if (loads && !el.wind_load.isZero())
      f12 -= cable_line_load(el.ref_length, el.unstressed_length, el.wind_load);
    add_block(r, el.nodes.data(), 6, f12.data());
    if (J && cables) {
      cable_indices(e, idx12);
      K12r = K12;
      PCSIM_PETSC(MatSetValues(J, 12, idx12, 12, idx12, K12r.data(), ADD_VALUES));
    }
  }
}

void CatenarySystem::add_bar_forces(double* r, Mat J, bool bars, bool loads, bool slack) const {
  Vec6 q6, f6;
  Mat6 K6;
  RowMat6 K6r;
  PetscInt idx6[6];
  for (int b : layout_->local_bars()) {
    const auto& bar = mesh_.bars[b];
    f6.setZero();
    if (bars) {
      bar_values(b, q6.data());
      bar_internal_force(bar_parameters(bar, slack), q6, f6, J ? &K6 : nullptr, nullptr);
    }
    if (loads) f6 -= bar_gravity_force(bar.mass, mesh_.gravity);
    add_block(r, bar.nodes.data(), 3, f6.data());  // bars act on position DOFs only
    if (J && bars) {
      bar_indices(b, idx6);
      K6r = K6;
      PCSIM_PETSC(MatSetValues(J, 6, idx6, 6, idx6, K6r.data(), ADD_VALUES));
    }
  }
}

// Gravity of point masses, point loads, node forces and support springs.
void CatenarySystem::add_point_forces(double* r, Mat J) const {
  const auto& L = *layout_;
  for (int i : L.local_point_masses()) {
    const auto& pm = mesh_.point_masses[i];
    if (r)
      for (int c = 0; c < 3; ++c) add_node_residual(r, pm.node, c, -pm.mass * mesh_.gravity[c]);
  }
  for (const auto& load : point_loads_) {
    const auto& el = mesh_.cables[load.element];
    if (!r || L.owner(el.nodes[0]) != L.rank()) continue;
    const HermiteValues h = hermite(load.chi, el.ref_length);
    for (int a = 0; a < 2; ++a)
      for (int c = 0; c < 3; ++c) {
        add_node_residual(r, el.nodes[a], c, -h.s[2 * a] * load.force[c]);
        add_node_residual(r, el.nodes[a], 3 + c, -h.s[2 * a + 1] * load.force[c]);
      }
  }
  for (const auto& nf : mesh_.node_forces)
    if (r && L.owner(nf.node) == L.rank())
      for (int c = 0; c < 3; ++c) add_node_residual(r, nf.node, c, -nf.force[c]);
  for (int i : L.local_springs()) add_spring(r, J, mesh_.springs[i]);
}

// A support spring: along its coordinate, or k (u . d) d along a direction.
void CatenarySystem::add_spring(double* r, Mat J, const SupportSpring& s) const {
  const auto& L = *layout_;
  const Eigen::Vector3d u = node_values(s.node).head<3>() - mesh_.nodes[s.node].position;
  if (s.direction.isZero()) {
    if (r) add_node_residual(r, s.node, s.dof, s.stiffness * u[s.dof]);
    const PetscInt g = L.global_dof(s.node, s.dof);
    if (J && g >= 0) PCSIM_PETSC(MatSetValue(J, g, g, s.stiffness, ADD_VALUES));
    return;
  }
  const Eigen::Vector3d& d = s.direction;
  const double f = s.stiffness * u.dot(d);
  if (r)
    for (int c = 0; c < 3; ++c) add_node_residual(r, s.node, c, f * d[c]);
  if (!J) return;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      const PetscInt ga = L.global_dof(s.node, a), gb = L.global_dof(s.node, b);
      if (ga >= 0 && gb >= 0 && d[a] * d[b] != 0)
        PCSIM_PETSC(MatSetValue(J, ga, gb, s.stiffness * d[a] * d[b], ADD_VALUES));
    }
}

void CatenarySystem::add_forces(Vec R, Mat J, unsigned terms) {
  double* r = R ? begin_residual() : nullptr;
  const bool cables = terms & kCables, bars = terms & kBars, loads = terms & kLoads;
  if (cables || loads) add_cable_forces(r, J, cables, loads);
  if (bars || loads) add_bar_forces(r, J, bars, loads, !(terms & kTautBars));
  if (loads) add_point_forces(r, J);
  if (R) end_residual(R);
}

double CatenarySystem::local_potential_energy(unsigned terms) const {
  const auto& L = *layout_;
  const bool cables = terms & kCables, bars = terms & kBars, loads = terms & kLoads;
  double energy = 0;
  Vec12 q12;
  for (int e : L.local_cables()) {
    const auto& el = mesh_.cables[e];
    const auto section = cable_section(mesh_.wires[el.wire], el);
    cable_values(e, q12.data());
    if (cables) energy += cable_strain_energy(section, el.ref_length, el.unstressed_length, q12);
    if (loads) energy -= cable_gravity_force(section, el.ref_length, mesh_.gravity).dot(q12);
    if (loads && !el.wind_load.isZero())
      energy -= cable_line_load(el.ref_length, el.unstressed_length, el.wind_load).dot(q12);
  }
  Vec6 q6;
  for (int b : L.local_bars()) {
    const auto& bar = mesh_.bars[b];
    bar_values(b, q6.data());
    if (bars) energy += bar_strain_energy(bar_parameters(bar, !(terms & kTautBars)), q6);
    if (loads) energy -= bar_gravity_force(bar.mass, mesh_.gravity).dot(q6);
  }
  if (!loads) return energy;
  for (int i : L.local_point_masses()) {
    const auto& pm = mesh_.point_masses[i];
    energy -= pm.mass * mesh_.gravity.dot(node_values(pm.node).head<3>());
  }
  for (const auto& load : point_loads_) {
    const auto& el = mesh_.cables[load.element];
    if (L.owner(el.nodes[0]) != L.rank()) continue;
    cable_values(load.element, q12.data());
    energy -= load.force.dot(cable_point(el.ref_length, q12, load.chi).r);
  }
  for (const auto& nf : mesh_.node_forces)
    if (L.owner(nf.node) == L.rank()) energy -= nf.force.dot(node_values(nf.node).head<3>());
  for (int i : L.local_springs()) {
    const auto& s = mesh_.springs[i];
    const Eigen::Vector3d u = node_values(s.node).head<3>() - mesh_.nodes[s.node].position;
    const double e = s.direction.isZero() ? u[s.dof] : u.dot(s.direction);
    energy += 0.5 * s.stiffness * e * e;
  }
  return energy;
}

void CatenarySystem::assemble_mass(Mat M) {
  const auto& L = *layout_;
  RowMat12 M12;
  PetscInt idx12[12];
  // A cable's consistent mass is m_kj (x) I3 (cable_mass_matrix): two thirds of its 12x12
  // entries couple different components and are exact zeros. Not stored, they
  // cost a product nothing (2.58 M to 0.79 M entries at 100 spans,
  // docs/scaling.md); the sums of the others are unchanged.
  PCSIM_PETSC(MatSetOption(M, MAT_IGNORE_ZERO_ENTRIES, PETSC_TRUE));
  for (int e : L.local_cables()) {
    const auto& el = mesh_.cables[e];
    M12 = cable_mass_matrix(cable_section(mesh_.wires[el.wire], el), el.ref_length);
    cable_indices(e, idx12);
    PCSIM_PETSC(MatSetValues(M, 12, idx12, 12, idx12, M12.data(), ADD_VALUES));
  }
  for (int b : L.local_bars()) {
    const auto& bar = mesh_.bars[b];
    for (int a = 0; a < 2; ++a)
      for (int c = 0; c < 3; ++c) {
        PetscInt g = L.global_dof(bar.nodes[a], c);
        if (g >= 0) PCSIM_PETSC(MatSetValue(M, g, g, 0.5 * bar.mass, ADD_VALUES));
      }
  }
  for (int i : L.local_point_masses()) {
    const auto& pm = mesh_.point_masses[i];
    for (int c = 0; c < 3; ++c) {
      PetscInt g = L.global_dof(pm.node, c);
      if (g >= 0) PCSIM_PETSC(MatSetValue(M, g, g, pm.mass, ADD_VALUES));
    }
  }
  PCSIM_PETSC(MatAssemblyBegin(M, MAT_FINAL_ASSEMBLY));
  PCSIM_PETSC(MatAssemblyEnd(M, MAT_FINAL_ASSEMBLY));
}

double CatenarySystem::cable_mean_tension(int element) const {
  const auto& el = mesh_.cables[element];
  Vec12 q12;
  cable_values(element, q12.data());
  return cable_mean_axial_force(cable_section(mesh_.wires[el.wire], el), el.ref_length,
                                el.unstressed_length, q12, nullptr, nullptr);
}

double CatenarySystem::bar_force(int bar, bool slack) const {
  Vec6 q6;
  bar_values(bar, q6.data());
  return bar_axial_force(bar_parameters(mesh_.bars[bar], slack), q6, nullptr);
}

static std::vector<double> node_values_from(const CatenaryMesh& mesh, const DofLayout& L,
                                            const std::vector<double>& design,
                                            const PetscScalar* all_free) {
  std::vector<double> out(design);
  for (std::size_t n = 0; n < mesh.nodes.size(); ++n)
    for (int c = 0; c < 6; ++c) {
      PetscInt g = L.global_dof(static_cast<int>(n), c);
      if (g >= 0) out[6 * n + c] = all_free[g];
    }
  return out;
}

// Node values (6 per node; design values for constrained DOFs) of state x,
// on every rank (to_root false) or on rank 0 only (empty elsewhere).
std::vector<double> CatenarySystem::gather_node_values(Vec x, bool to_root) const {
  VecScatter scatter;
  Vec all;
  if (to_root)
    PCSIM_PETSC(VecScatterCreateToZero(x, &scatter, &all));
  else
    PCSIM_PETSC(VecScatterCreateToAll(x, &scatter, &all));
  PCSIM_PETSC(VecScatterBegin(scatter, x, all, INSERT_VALUES, SCATTER_FORWARD));
  PCSIM_PETSC(VecScatterEnd(scatter, x, all, INSERT_VALUES, SCATTER_FORWARD));
  std::vector<double> values;
  if (!to_root || layout_->rank() == 0) {
    const PetscScalar* a;
    PCSIM_PETSC(VecGetArrayRead(all, &a));
    values = node_values_from(mesh_, *layout_, design_values_, a);
    PCSIM_PETSC(VecRestoreArrayRead(all, &a));
  }
  PCSIM_PETSC(VecScatterDestroy(&scatter));
  PCSIM_PETSC(VecDestroy(&all));
  return values;
}

std::vector<double> CatenarySystem::gather_positions_to_root(Vec x) const {
  return positions_from_node_values(gather_node_values(x, true));
}

std::vector<double> CatenarySystem::all_node_values(Vec x) const {
  return gather_node_values(x, false);
}

}  // namespace pcsim::assembly
