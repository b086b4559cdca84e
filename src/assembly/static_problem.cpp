#include "pcsim/assembly/static_problem.hpp"

#include <mpi.h>

#include <algorithm>
#include <cmath>

#include "pcsim/catenary/elements.hpp"
#include "pcsim/core/error.hpp"

namespace pcsim::assembly {

using namespace pcsim::catenary;

PetscInt form_finding_unknowns(const CatenaryMesh& mesh) {
  return static_cast<PetscInt>(mesh.height_targets.size() + mesh.tension_segments.size());
}

void set_state_from_node_values(const CatenarySystem& system,
                                const std::vector<double>& node_values, Vec x) {
  const auto& L = system.layout();
  PetscScalar* a;
  PCSIM_PETSC(VecGetArray(x, &a));
  for (int n : L.owned_nodes())
    for (int c = 0; c < 6; ++c) {
      PetscInt g = L.global_dof(n, c);
      if (g >= 0) a[g - L.first_owned()] = node_values[6 * n + c];
    }
  PCSIM_PETSC(VecRestoreArray(x, &a));
}

namespace {

// Statics hold every bar taut: a bar's slack criterion needs the equilibrium
// (length, force) that statics find (finish() records it).
constexpr unsigned kStaticTerms = CatenarySystem::kAllTerms | CatenarySystem::kTautBars;
double bar_design_length(const CatenaryMesh& mesh, int b) {
  return (mesh.nodes[mesh.bars[b].nodes[1]].position - mesh.nodes[mesh.bars[b].nodes[0]].position)
      .norm();
}

// Sum over ranks of per-item values computed by the item's owner.
void allreduce_sum(MPI_Comm comm, std::vector<double>& v) {
  MPI_Allreduce(MPI_IN_PLACE, v.data(), static_cast<int>(v.size()), MPI_DOUBLE, MPI_SUM, comm);
}
}  // namespace

StaticProblem::StaticProblem(CatenarySystem& system, bool form_finding)
    : system_(system), form_finding_(form_finding) {
  const auto& mesh = system.mesh();
  if (form_finding && system.layout().extra_dofs() != form_finding_unknowns(mesh))
    throw SolverError("form-finding needs a system built with its extra unknowns");
  if (form_finding && mesh.height_targets.empty() && mesh.tension_segments.empty())
    throw InputError(mesh.source_file, "form_finding",
                     "form-finding is on but the design has no height targets or tension segments");
  target_of_bar_.assign(mesh.bars.size(), -1);
  for (std::size_t k = 0; k < mesh.height_targets.size(); ++k) {
    const auto& t = mesh.height_targets[k];
    if (t.bar < 0 || t.bar >= static_cast<int>(mesh.bars.size()))
      throw InputError(mesh.source_file, "targets", "height target without a dropper");
    target_of_bar_[t.bar] = static_cast<int>(k);
    height_scale_.push_back(mesh.bars[t.bar].stiffness);
  }
  segment_of_bar_.assign(mesh.bars.size(), -1);
  for (std::size_t k = 0; k < mesh.tension_segments.size(); ++k) {
    const auto& s = mesh.tension_segments[k];
    segment_count_.push_back(static_cast<int>(s.elements.size() + s.bars.size()));
    for (int b : s.bars) segment_of_bar_[b] = static_cast<int>(k);
  }
}

Mat StaticProblem::create_matrix() const {
  const auto& mesh = system_.mesh();
  std::vector<std::vector<int>> couplings;
  if (form_finding_) {
    for (const auto& t : mesh.height_targets)
      couplings.push_back({mesh.bars[t.bar].nodes[0], mesh.bars[t.bar].nodes[1], t.node});
    for (const auto& s : mesh.tension_segments) {
      std::vector<int> nodes;
      for (int e : s.elements) {
        nodes.push_back(mesh.cables[e].nodes[0]);
        nodes.push_back(mesh.cables[e].nodes[1]);
      }
      for (int b : s.bars) {
        nodes.push_back(mesh.bars[b].nodes[0]);
        nodes.push_back(mesh.bars[b].nodes[1]);
      }
      couplings.push_back(nodes);
    }
  }
  return system_.layout().create_matrix(couplings);
}

// Reads the extra unknowns (owned by the last rank) on every rank and writes
// them into the mesh: dropper unstressed lengths (and the stiffness EA / L0
// of a dropper given by its EA) and segment length scales.
void StaticProblem::apply_unknowns(Vec x) {
  auto& mesh = system_.mutable_mesh();
  const auto& L = system_.layout();
  const PetscInt n_extra = L.extra_dofs();
  std::vector<double> extra(n_extra, 0.0);
  if (L.rank() == L.size() - 1) {
    const PetscScalar* a;
    PCSIM_PETSC(VecGetArrayRead(x, &a));
    for (PetscInt k = 0; k < n_extra; ++k) extra[k] = a[L.extra_global(k) - L.first_owned()];
    PCSIM_PETSC(VecRestoreArrayRead(x, &a));
  }
  MPI_Bcast(extra.data(), static_cast<int>(n_extra), MPI_DOUBLE, L.size() - 1, L.comm());
  const std::size_t n_targets = mesh.height_targets.size();
  for (std::size_t k = 0; k < n_targets; ++k)
    set_bar_unstressed_length(mesh.bars[mesh.height_targets[k].bar], extra[k]);  // k = EA/L0
  for (std::size_t s = 0; s < mesh.tension_segments.size(); ++s) {
    for (int e : mesh.tension_segments[s].elements)
      mesh.cables[e].unstressed_length = extra[n_targets + s] * mesh.cables[e].ref_length;
    for (int b : mesh.tension_segments[s].bars)
      set_bar_unstressed_length(mesh.bars[b], extra[n_targets + s] * bar_design_length(mesh, b));
  }
}

void StaticProblem::initial_guess(Vec x) const {
  const auto& mesh = system_.mesh();
  const auto& L = system_.layout();
  if (!form_finding_ || L.rank() != L.size() - 1) return;
  PetscScalar* a;
  PCSIM_PETSC(VecGetArray(x, &a));
  const std::size_t n_targets = mesh.height_targets.size();
  for (std::size_t k = 0; k < n_targets; ++k)
    a[L.extra_global(k) - L.first_owned()] =
        mesh.bars[mesh.height_targets[k].bar].unstressed_length;
  for (std::size_t s = 0; s < mesh.tension_segments.size(); ++s) {
    double ratio = 0;
    for (int e : mesh.tension_segments[s].elements)
      ratio += mesh.cables[e].unstressed_length / mesh.cables[e].ref_length;
    for (int b : mesh.tension_segments[s].bars)
      ratio += mesh.bars[b].unstressed_length / bar_design_length(mesh, b);
    a[L.extra_global(n_targets + s) - L.first_owned()] = ratio / segment_count_[s];
  }
  PCSIM_PETSC(VecRestoreArray(x, &a));
}

// Residual and tangent of the form-finding rows and columns (added to the
// static residual R and tangent J assembled before).
void StaticProblem::add_form_finding_terms(Vec R, Mat J) {
  const auto& mesh = system_.mesh();
  const auto& L = system_.layout();
  const std::size_t n_targets = mesh.height_targets.size();
  // Height rows: scale * (z - z_target); owner of the node assembles them.
  for (std::size_t k = 0; k < n_targets; ++k) {
    const auto& t = mesh.height_targets[k];
    if (L.owner(t.node) != L.rank()) continue;
    const PetscInt row = L.extra_global(static_cast<PetscInt>(k));
    const double z = system_.node_values(t.node)[2];
    PCSIM_PETSC(VecSetValue(R, row, height_scale_[k] * (z - t.z), ADD_VALUES));
    const PetscInt col = L.global_dof(t.node, 2);
    if (J && col >= 0) PCSIM_PETSC(MatSetValue(J, row, col, height_scale_[k], ADD_VALUES));
  }
  // Dropper unstressed-length columns: d f_bar / d L0.
  Vec6 q6, f6, df6;
  PetscInt idx6[6];
  for (int b : L.local_bars()) {
    const int k = target_of_bar_[b];
    if (k < 0 || !J) continue;
    system_.bar_values(b, q6.data());
    bar_internal_force(bar_parameters(mesh.bars[b], false), q6, f6, nullptr, &df6);
    system_.bar_indices(b, idx6);
    const PetscInt col = L.extra_global(k);
    for (int i = 0; i < 6; ++i)
      if (idx6[i] >= 0) PCSIM_PETSC(MatSetValue(J, idx6[i], col, df6[i], ADD_VALUES));
  }
  // Tension rows and segment-scale columns.
  Vec12 q12, f12, df12, dT12;
  PetscInt idx12[12];
  for (int e : L.local_cables()) {
    const auto& el = mesh.cables[e];
    if (el.tension_segment < 0) continue;
    const int s = el.tension_segment;
    const CableSection section = cable_section(mesh.wires[el.wire], el);
    system_.cable_values(e, q12.data());
    double dT_dL0 = 0;
    const double T = cable_mean_axial_force(section, el.ref_length, el.unstressed_length, q12,
                                            J ? &dT12 : nullptr, J ? &dT_dL0 : nullptr);
    const PetscInt row = L.extra_global(static_cast<PetscInt>(n_targets + s));
    const double weight = 1.0 / segment_count_[s];
    PCSIM_PETSC(VecSetValue(R, row, weight * T, ADD_VALUES));
    if (!J) continue;
    cable_internal_force(section, el.ref_length, el.unstressed_length, q12, f12, nullptr, &df12);
    // Gravity rho (L0 / Lref) int S^T g: d/dL0 = gravity / L0 (mass per
    // unstressed length).
    df12 -= cable_gravity_force(section, el.ref_length, mesh.gravity) / el.unstressed_length;
    if (!el.wind_load.isZero())  // the same for the wind's drag (per unstressed length)
      df12 -=
          cable_line_load(el.ref_length, el.unstressed_length, el.wind_load) / el.unstressed_length;
    system_.cable_indices(e, idx12);
    for (int i = 0; i < 12; ++i) {
      if (idx12[i] < 0) continue;
      PCSIM_PETSC(MatSetValue(J, idx12[i], row, df12[i] * el.ref_length, ADD_VALUES));
      PCSIM_PETSC(MatSetValue(J, row, idx12[i], weight * dT12[i], ADD_VALUES));
    }
    PCSIM_PETSC(MatSetValue(J, row, row, weight * dT_dL0 * el.ref_length, ADD_VALUES));
  }
  add_bar_segment_terms(R, J);
  if (L.rank() == L.size() - 1)
    for (std::size_t s = 0; s < mesh.tension_segments.size(); ++s)
      PCSIM_PETSC(VecSetValue(R, L.extra_global(static_cast<PetscInt>(n_targets + s)),
                              -mesh.tension_segments[s].tension, ADD_VALUES));
}

// Tension rows and scale columns of the segments made of bars (stitch
// wires): mean axial force N of the bars, L0 = scale x design length.
void StaticProblem::add_bar_segment_terms(Vec R, Mat J) {
  const auto& mesh = system_.mesh();
  const auto& L = system_.layout();
  const std::size_t n_targets = mesh.height_targets.size();
  Vec6 q6, f6, df6;
  PetscInt idx6[6];
  for (int b : L.local_bars()) {
    const int s = segment_of_bar_[b];
    if (s < 0) continue;
    const auto params = bar_parameters(mesh.bars[b], false);
    system_.bar_values(b, q6.data());
    const double N = bar_internal_force(params, q6, f6, nullptr, &df6);
    const PetscInt row = L.extra_global(static_cast<PetscInt>(n_targets + s));
    const double weight = 1.0 / segment_count_[s], design = bar_design_length(mesh, b);
    PCSIM_PETSC(VecSetValue(R, row, weight * N, ADD_VALUES));
    if (!J) continue;
    // f = N [-e; e]: dN/dq = dN/dl [-e; e], dN/dL0 = df/dL0 . [-e; e] / 2.
    const Eigen::Vector3d d = q6.tail<3>() - q6.head<3>(), e = d / d.norm();
    double dN_dl = 0;
    bar_axial_force(params, q6, &dN_dl);
    const double dN_dL0 = 0.5 * (df6.tail<3>() - df6.head<3>()).dot(e);
    system_.bar_indices(b, idx6);
    for (int i = 0; i < 6; ++i) {
      if (idx6[i] < 0) continue;
      const double dN_dqi = dN_dl * (i < 3 ? -e[i] : e[i - 3]);
      PCSIM_PETSC(MatSetValue(J, idx6[i], row, df6[i] * design, ADD_VALUES));
      PCSIM_PETSC(MatSetValue(J, row, idx6[i], weight * dN_dqi, ADD_VALUES));
    }
    PCSIM_PETSC(MatSetValue(J, row, row, weight * dN_dL0 * design, ADD_VALUES));
  }
}

void StaticProblem::residual(Vec x, Vec R) {
  if (form_finding_) apply_unknowns(x);
  system_.load_state(x);
  system_.assemble_static(R, nullptr, kStaticTerms);
  if (form_finding_) add_form_finding_terms(R, nullptr);
  PCSIM_PETSC(VecAssemblyBegin(R));
  PCSIM_PETSC(VecAssemblyEnd(R));
}

void StaticProblem::jacobian(Vec x, Mat J) {
  if (form_finding_) apply_unknowns(x);
  system_.load_state(x);
  PCSIM_PETSC(MatZeroEntries(J));
  Vec scratch;
  PCSIM_PETSC(VecDuplicate(x, &scratch));
  system_.add_forces(nullptr, J, kStaticTerms);
  if (form_finding_) add_form_finding_terms(scratch, J);
  PCSIM_PETSC(VecAssemblyBegin(scratch));
  PCSIM_PETSC(VecAssemblyEnd(scratch));
  PCSIM_PETSC(VecDestroy(&scratch));
  PCSIM_PETSC(MatAssemblyBegin(J, MAT_FINAL_ASSEMBLY));
  PCSIM_PETSC(MatAssemblyEnd(J, MAT_FINAL_ASSEMBLY));
}

StaticResult StaticProblem::finish(Vec x) {
  StaticResult result;
  if (form_finding_) apply_unknowns(x);
  system_.load_state(x);
  auto& mesh = system_.mutable_mesh();
  const auto& L = system_.layout();
  result.bar_forces.assign(mesh.bars.size(), 0.0);
  result.bar_lengths.assign(mesh.bars.size(), 0.0);
  for (int b : L.local_bars()) {
    Vec6 q6;
    system_.bar_values(b, q6.data());
    result.bar_lengths[b] = (q6.tail<3>() - q6.head<3>()).norm();
    result.bar_forces[b] = system_.bar_force(b, false);
  }
  allreduce_sum(L.comm(), result.bar_forces);
  allreduce_sum(L.comm(), result.bar_lengths);
  for (std::size_t b = 0; b < mesh.bars.size(); ++b) {
    mesh.bars[b].equilibrium_length = result.bar_lengths[b];
    mesh.bars[b].equilibrium_force = result.bar_forces[b];
  }
  result.segment_tensions.assign(mesh.tension_segments.size(), 0.0);
  for (int e : L.local_cables()) {
    const int s = mesh.cables[e].tension_segment;
    if (s >= 0) result.segment_tensions[s] += system_.cable_mean_tension(e) / segment_count_[s];
  }
  allreduce_sum(L.comm(), result.segment_tensions);
  for (std::size_t b = 0; b < mesh.bars.size(); ++b)  // bar forces: on every rank
    if (segment_of_bar_[b] >= 0)
      result.segment_tensions[segment_of_bar_[b]] +=
          result.bar_forces[b] / segment_count_[segment_of_bar_[b]];
  for (std::size_t s = 0; s < mesh.tension_segments.size(); ++s)
    result.max_tension_error_rel =
        std::max(result.max_tension_error_rel,
                 std::abs(result.segment_tensions[s] / mesh.tension_segments[s].tension - 1.0));
  result.node_values = system_.all_node_values(x);
  for (const auto& t : mesh.height_targets) {
    const double z = result.node_values[6 * t.node + 2];
    result.target_heights.push_back(z);
    result.max_height_error_m = std::max(result.max_height_error_m, std::abs(z - t.z));
  }
  return result;
}

}  // namespace pcsim::assembly

namespace pcsim::assembly {

double StaticProblem::force_scale() const {
  const auto& mesh = system_.mesh();
  double mass = 0, tension = 0;
  for (const auto& e : mesh.cables) mass += mesh.wires[e.wire].mass_per_length * e.ref_length;
  for (const auto& b : mesh.bars) mass += b.mass;
  for (const auto& m : mesh.point_masses) mass += m.mass;
  for (const auto& w : mesh.wires) tension = std::max(tension, w.tension);
  for (const auto& s : mesh.tension_segments) tension = std::max(tension, s.tension);
  return std::max({mass * mesh.gravity.norm(), tension, 1.0});
}

void StaticProblem::static_tangent(Vec x, Mat K) {
  if (form_finding_) apply_unknowns(x);
  system_.load_state(x);
  PCSIM_PETSC(MatZeroEntries(K));
  system_.add_forces(nullptr, K, kStaticTerms);
  const auto& L = system_.layout();
  if (L.rank() == L.size() - 1)
    for (PetscInt k = 0; k < L.extra_dofs(); ++k)
      PCSIM_PETSC(MatSetValue(K, L.extra_global(k), L.extra_global(k), 1.0, ADD_VALUES));
  PCSIM_PETSC(MatAssemblyBegin(K, MAT_FINAL_ASSEMBLY));
  PCSIM_PETSC(MatAssemblyEnd(K, MAT_FINAL_ASSEMBLY));
}

std::vector<StaticProblem::Compressed> StaticProblem::compressed_elements(double tolerance) const {
  const auto& mesh = system_.mesh();
  const auto& L = system_.layout();
  // Element force of each local element (0 elsewhere), summed over the ranks.
  std::vector<double> cable_force(mesh.cables.size(), 0.0);
  for (int e : L.local_cables()) cable_force[e] = system_.cable_mean_tension(e);
  allreduce_sum(L.comm(), cable_force);
  std::vector<Compressed> list;
  auto middle_x = [&](int a, int b) {
    return 0.5 * (mesh.nodes[a].position.x() + mesh.nodes[b].position.x());
  };
  for (std::size_t e = 0; e < mesh.cables.size(); ++e)
    if (cable_force[e] < -tolerance)
      list.push_back({true, static_cast<int>(e), cable_force[e],
                      middle_x(mesh.cables[e].nodes[0], mesh.cables[e].nodes[1])});
  // Bars that stand for wires (droppers, stitch wires) cannot push.
  for (std::size_t b = 0; b < mesh.bars.size(); ++b) {
    const auto& bar = mesh.bars[b];
    const bool wire_like = bar.kind == BarKind::dropper || bar.kind == BarKind::stitch;
    if (wire_like && bar.equilibrium_force < -tolerance)
      list.push_back({false, static_cast<int>(b), bar.equilibrium_force,
                      middle_x(bar.nodes[0], bar.nodes[1])});
  }
  return list;
}

}  // namespace pcsim::assembly
