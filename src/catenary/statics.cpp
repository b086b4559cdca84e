#include "pcsim/catenary/statics.hpp"

#include <petsctime.h>

#include <Eigen/Core>
#include <cmath>

#include "pcsim/catenary/elements.hpp"
#include "pcsim/error.hpp"
#include "pcsim/solvers/direct.hpp"

namespace pcsim::catenary {

using assembly::CatenarySystem;

PetscInt form_finding_unknowns(const CatenaryMesh& mesh) {
  return static_cast<PetscInt>(mesh.height_targets.size() + mesh.tension_segments.size());
}

namespace {

struct StaticContext {
  CatenarySystem* system = nullptr;
  bool form_finding = false;
  std::vector<int> target_of_bar;    // bar -> target index or -1
  std::vector<int> segment_count;    // elements per segment
  std::vector<double> height_scale;  // residual scale of each height row [N/m]
};

// Reads the extra unknowns (owned by the last rank) on every rank and writes
// them into the mesh: dropper unstressed lengths and segment length scales.
void apply_form_finding_unknowns(StaticContext& ctx, Vec x) {
  auto& system = *ctx.system;
  auto& mesh = system.mutable_mesh();
  const auto& L = system.layout();
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
    mesh.bars[mesh.height_targets[k].bar].unstressed_length = extra[k];
  for (std::size_t s = 0; s < mesh.tension_segments.size(); ++s)
    for (int e : mesh.tension_segments[s].elements)
      mesh.cables[e].unstressed_length = extra[n_targets + s] * mesh.cables[e].ref_length;
}

void initial_form_finding_unknowns(StaticContext& ctx, Vec x) {
  auto& system = *ctx.system;
  const auto& mesh = system.mesh();
  const auto& L = system.layout();
  if (L.rank() != L.size() - 1) return;
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
    a[L.extra_global(n_targets + s) - L.first_owned()] =
        ratio / mesh.tension_segments[s].elements.size();
  }
  PCSIM_PETSC(VecRestoreArray(x, &a));
}

// Residual and tangent of the form-finding rows and columns (added to the
// static residual R and tangent J assembled before).
void add_form_finding_terms(StaticContext& ctx, Vec R, Mat J) {
  auto& system = *ctx.system;
  const auto& mesh = system.mesh();
  const auto& L = system.layout();
  const std::size_t n_targets = mesh.height_targets.size();
  // Height rows: scale * (z - z_target); owner of the node assembles them.
  for (std::size_t k = 0; k < n_targets; ++k) {
    const auto& t = mesh.height_targets[k];
    if (L.owner(t.node) != L.rank()) continue;
    const PetscInt row = L.extra_global(static_cast<PetscInt>(k));
    const double z = system.node_values(t.node)[2];
    PCSIM_PETSC(VecSetValue(R, row, ctx.height_scale[k] * (z - t.z), ADD_VALUES));
    if (J) {
      PetscInt col = L.global_dof(t.node, 2);
      if (col >= 0) PCSIM_PETSC(MatSetValue(J, row, col, ctx.height_scale[k], ADD_VALUES));
    }
  }
  // Dropper unstressed-length columns: d f_bar / d L0.
  Vec6 q6, f6, df6;
  PetscInt idx6[6];
  for (int b : L.local_bars()) {
    const int k = ctx.target_of_bar[b];
    if (k < 0 || !J) continue;
    const auto& bar = mesh.bars[b];
    const BarParameters p = bar_parameters(bar);
    system.bar_values(b, q6.data());
    bar_internal_force(p, q6, f6, nullptr, &df6);
    system.bar_indices(b, idx6);
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
    const auto& wire = mesh.wires[el.wire];
    const CableSection section = cable_section(wire);
    system.cable_values(e, q12.data());
    double dT_dL0 = 0;
    const double T = cable_mean_axial_force(section, el.ref_length, el.unstressed_length, q12,
                                            J ? &dT12 : nullptr, J ? &dT_dL0 : nullptr);
    const PetscInt row = L.extra_global(static_cast<PetscInt>(n_targets + s));
    const double weight = 1.0 / ctx.segment_count[s];
    PCSIM_PETSC(VecSetValue(R, row, weight * T, ADD_VALUES));
    if (!J) continue;
    cable_internal_force(section, el.ref_length, el.unstressed_length, q12, f12, nullptr, &df12);
    system.cable_indices(e, idx12);
    for (int i = 0; i < 12; ++i) {
      if (idx12[i] < 0) continue;
      PCSIM_PETSC(MatSetValue(J, idx12[i], row, df12[i] * el.ref_length, ADD_VALUES));
      PCSIM_PETSC(MatSetValue(J, row, idx12[i], weight * dT12[i], ADD_VALUES));
    }
    PCSIM_PETSC(MatSetValue(J, row, row, weight * dT_dL0 * el.ref_length, ADD_VALUES));
  }
  if (L.rank() == L.size() - 1)
    for (std::size_t s = 0; s < mesh.tension_segments.size(); ++s)
      PCSIM_PETSC(VecSetValue(R, L.extra_global(static_cast<PetscInt>(n_targets + s)),
                              -mesh.tension_segments[s].tension, ADD_VALUES));
}

PetscErrorCode form_residual(SNES, Vec x, Vec R, void* ptr) {
  PCSIM_CALLBACK_BEGIN
  auto& ctx = *static_cast<StaticContext*>(ptr);
  if (ctx.form_finding) apply_form_finding_unknowns(ctx, x);
  ctx.system->load_state(x);
  ctx.system->assemble_static(R, nullptr);
  if (ctx.form_finding) add_form_finding_terms(ctx, R, nullptr);
  PCSIM_PETSC(VecAssemblyBegin(R));
  PCSIM_PETSC(VecAssemblyEnd(R));
  PCSIM_CALLBACK_END
}

PetscErrorCode form_jacobian(SNES, Vec x, Mat J, Mat P, void* ptr) {
  PCSIM_CALLBACK_BEGIN
  auto& ctx = *static_cast<StaticContext*>(ptr);
  if (ctx.form_finding) apply_form_finding_unknowns(ctx, x);
  ctx.system->load_state(x);
  PCSIM_PETSC(MatZeroEntries(P));
  Vec scratch;
  PCSIM_PETSC(VecDuplicate(x, &scratch));
  ctx.system->assemble_static(scratch, P);
  if (ctx.form_finding) add_form_finding_terms(ctx, scratch, P);
  PCSIM_PETSC(VecAssemblyBegin(scratch));
  PCSIM_PETSC(VecAssemblyEnd(scratch));
  PCSIM_PETSC(VecDestroy(&scratch));
  PCSIM_PETSC(MatAssemblyBegin(P, MAT_FINAL_ASSEMBLY));
  PCSIM_PETSC(MatAssemblyEnd(P, MAT_FINAL_ASSEMBLY));
  if (J != P) {
    PCSIM_PETSC(MatAssemblyBegin(J, MAT_FINAL_ASSEMBLY));
    PCSIM_PETSC(MatAssemblyEnd(J, MAT_FINAL_ASSEMBLY));
  }
  PCSIM_CALLBACK_END
}

// Sum over ranks of per-item values computed by the item's owner.
void allreduce_sum(MPI_Comm comm, std::vector<double>& v) {
  MPI_Allreduce(MPI_IN_PLACE, v.data(), static_cast<int>(v.size()), MPI_DOUBLE, MPI_SUM, comm);
}

}  // namespace

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

StaticResult solve_static(CatenarySystem& system, Vec x, bool form_finding,
                          const char* options_prefix) {
  PetscLogDouble t0;
  PetscTime(&t0);
  const auto& L = system.layout();
  const auto& mesh0 = system.mesh();
  if (form_finding && L.extra_dofs() != form_finding_unknowns(mesh0))
    throw SolverError("form-finding needs a system built with its extra unknowns");
  if (form_finding && mesh0.height_targets.empty() && mesh0.tension_segments.empty())
    throw InputError(mesh0.source_file, "form_finding",
                     "form-finding is on but the design has no height targets or tension segments");

  StaticContext ctx;
  ctx.system = &system;
  ctx.form_finding = form_finding;
  ctx.target_of_bar.assign(mesh0.bars.size(), -1);
  for (std::size_t k = 0; k < mesh0.height_targets.size(); ++k) {
    const auto& t = mesh0.height_targets[k];
    if (t.bar < 0 || t.bar >= static_cast<int>(mesh0.bars.size()))
      throw InputError(mesh0.source_file, "targets", "height target without a dropper");
    ctx.target_of_bar[t.bar] = static_cast<int>(k);
    ctx.height_scale.push_back(mesh0.bars[t.bar].stiffness);
  }
  for (const auto& s : mesh0.tension_segments)
    ctx.segment_count.push_back(static_cast<int>(s.elements.size()));

  // Matrix with the couplings of the extra unknowns.
  std::vector<std::vector<int>> couplings;
  if (form_finding) {
    for (const auto& t : mesh0.height_targets)
      couplings.push_back({mesh0.bars[t.bar].nodes[0], mesh0.bars[t.bar].nodes[1], t.node});
    for (const auto& s : mesh0.tension_segments) {
      std::vector<int> nodes;
      for (int e : s.elements) {
        nodes.push_back(mesh0.cables[e].nodes[0]);
        nodes.push_back(mesh0.cables[e].nodes[1]);
      }
      couplings.push_back(nodes);
    }
  }
  Mat J = L.create_matrix(couplings);
  // Slack criteria are defined relative to the static equilibrium (thesis
  // 3.1.2): during the static solution every bar is a plain linear bar.
  std::vector<SlackCriterion> slack_criteria;
  for (auto& bar : system.mutable_mesh().bars) {
    slack_criteria.push_back(bar.slack);
    bar.slack = SlackCriterion::none;
  }
  Vec R;
  PCSIM_PETSC(VecDuplicate(x, &R));
  if (form_finding) initial_form_finding_unknowns(ctx, x);

  SNES snes;
  PCSIM_PETSC(SNESCreate(L.comm(), &snes));
  if (options_prefix) PCSIM_PETSC(SNESSetOptionsPrefix(snes, options_prefix));
  PCSIM_PETSC(SNESSetFunction(snes, R, form_residual, &ctx));
  PCSIM_PETSC(SNESSetJacobian(snes, J, J, form_jacobian, &ctx));
  PCSIM_PETSC(SNESSetType(snes, SNESNEWTONLS));
  PCSIM_PETSC(SNESSetTolerances(snes, 1e-8, 1e-12, 1e-14, 50, 10000));
  KSP ksp;
  PCSIM_PETSC(SNESGetKSP(snes, &ksp));
  // MUMPS pivots: the form-finding system has zero diagonal entries.
  solvers::use_direct_lu(ksp, MATSOLVERMUMPS);
  std::vector<PetscReal> history(60, 0.0);
  PCSIM_PETSC(SNESSetConvergenceHistory(snes, history.data(), nullptr,
                                        static_cast<PetscInt>(history.size()), PETSC_TRUE));
  PCSIM_PETSC(SNESSetFromOptions(snes));
  PCSIM_PETSC(SNESSolve(snes, nullptr, x));

  StaticResult result;
  SNESConvergedReason reason;
  PCSIM_PETSC(SNESGetConvergedReason(snes, &reason));
  result.converged = reason > 0;
  result.converged_reason = SNESConvergedReasons[reason];
  PetscInt its = 0, lits = 0, n_hist = 0;
  PCSIM_PETSC(SNESGetIterationNumber(snes, &its));
  PCSIM_PETSC(SNESGetLinearSolveIterations(snes, &lits));
  PetscReal* hist_ptr = nullptr;
  PCSIM_PETSC(SNESGetConvergenceHistory(snes, &hist_ptr, nullptr, &n_hist));
  result.snes_iterations = static_cast<int>(its);
  result.linear_iterations = static_cast<int>(lits);
  result.residual_history.assign(hist_ptr, hist_ptr + n_hist);
  PCSIM_PETSC(SNESDestroy(&snes));
  PCSIM_PETSC(MatDestroy(&J));
  PCSIM_PETSC(VecDestroy(&R));
  auto restore_slack_criteria = [&] {
    for (std::size_t b = 0; b < slack_criteria.size(); ++b)
      system.mutable_mesh().bars[b].slack = slack_criteria[b];
  };
  if (!result.converged) restore_slack_criteria();
  if (!result.converged)
    throw SolverError(std::string("static solution did not converge (") + result.converged_reason +
                      " after " + std::to_string(its) +
                      " Newton iterations); try -snes_monitor -snes_linesearch_type bt");

  // Final state: unstressed lengths in the mesh, equilibrium of every bar.
  if (form_finding) apply_form_finding_unknowns(ctx, x);
  system.load_state(x);
  auto& mesh = system.mutable_mesh();
  result.bar_forces.assign(mesh.bars.size(), 0.0);
  result.bar_lengths.assign(mesh.bars.size(), 0.0);
  for (int b : L.local_bars()) {
    Vec6 q6;
    system.bar_values(b, q6.data());
    result.bar_lengths[b] = (q6.tail<3>() - q6.head<3>()).norm();
    result.bar_forces[b] = system.bar_force(b);
  }
  allreduce_sum(L.comm(), result.bar_forces);
  allreduce_sum(L.comm(), result.bar_lengths);
  for (std::size_t b = 0; b < mesh.bars.size(); ++b) {
    mesh.bars[b].equilibrium_length = result.bar_lengths[b];
    mesh.bars[b].equilibrium_force = result.bar_forces[b];
  }
  restore_slack_criteria();
  result.segment_tensions.assign(mesh.tension_segments.size(), 0.0);
  for (int e : L.local_cables()) {
    const int s = mesh.cables[e].tension_segment;
    if (s >= 0) result.segment_tensions[s] += system.cable_mean_tension(e) / ctx.segment_count[s];
  }
  allreduce_sum(L.comm(), result.segment_tensions);
  for (std::size_t s = 0; s < mesh.tension_segments.size(); ++s)
    result.max_tension_error_rel =
        std::max(result.max_tension_error_rel,
                 std::abs(result.segment_tensions[s] / mesh.tension_segments[s].tension - 1.0));
  result.node_values = system.all_node_values(x);
  for (const auto& t : mesh.height_targets) {
    const double z = result.node_values[6 * t.node + 2];
    result.target_heights.push_back(z);
    result.max_height_error_m = std::max(result.max_height_error_m, std::abs(z - t.z));
  }
  PetscLogDouble t1;
  PetscTime(&t1);
  result.wall_time_s = t1 - t0;
  return result;
}

}  // namespace pcsim::catenary
