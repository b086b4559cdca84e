#include "pcsim/simulation/static_start.hpp"

#include <mpi.h>
#include <petscsnes.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "pcsim/assembly/fe_catenary.hpp"
#include "pcsim/assembly/static_problem.hpp"
#include "pcsim/core/error.hpp"
#include "pcsim/solvers/direct.hpp"
#include "pcsim/solvers/statics.hpp"

namespace pcsim::simulation {

namespace {

std::string start_key(std::size_t p) {
  return "pantographs[" + std::to_string(p) + "].start_x";
}

// The lowest contact wire at station x for the catenary state in U (its
// number and height, on every rank; -1 if x lies on no contact wire), and the
// residual flexibility there (a reduced catenary's, in series with the
// contact spring; 0 for FE).
std::pair<int, double> lowest_wire(assembly::CatenaryModel& catenary, Vec U, double x,
                                   double* flexibility = nullptr) {
  catenary.load_state(U);
  const int n = catenary.contact_wire_count();
  std::vector<char> on(n, 0);  // the same on every rank
  std::vector<double> z(n, 0.0), r(n, 0.0);
  for (int w = 0; w < n; ++w) {
    const auto point = catenary.wire_point(x, w);
    on[w] = point.on_wire;
    r[w] = point.residual_flexibility;  // every rank
    if (point.owned) z[w] = point.z;
  }
  MPI_Allreduce(MPI_IN_PLACE, z.data(), n, MPI_DOUBLE, MPI_SUM, catenary.comm());
  std::pair<int, double> lowest{-1, 0.0};
  for (int w = 0; w < n; ++w)
    if (on[w] && (lowest.first < 0 || z[w] < lowest.second)) lowest = {w, z[w]};
  if (flexibility) *flexibility = lowest.first < 0 ? 0.0 : r[lowest.first];
  return lowest;
}

// Contact-wire height at x for the catenary state in U0 (the lowest wire
// there) and its residual flexibility, on every rank.
double wire_height(assembly::CatenaryModel& catenary, Vec U0, double x, std::size_t p,
                   double& flexibility) {
  const auto lowest = lowest_wire(catenary, U0, x, &flexibility);
  if (lowest.first < 0)
    throw InputError("", start_key(p), "the pantograph starts outside the contact wire");
  return lowest.second;
}

bool any_static_start(assembly::CoupledSystem& system) {
  for (const auto& slot : system.pantographs())
    if (slot.run.static_start) return true;
  return false;
}

// The catenary part of U0: the static configuration, or with static starts the
// catenary under every such pantograph's static force F0 at its start point
// on the lowest contact wire there (a modal catenary's exact equilibrium, an
// FE catenary's guess for the coupled one).
PetscInt catenary_start(assembly::CoupledSystem& system, Vec U0) {
  auto& catenary = system.catenary();
  catenary.reference_state(U0);
  if (!any_static_start(system)) return 0;
  // A modal catenary: the static forces superposed, exact (slack ignored),
  // no guess needed.
  std::vector<assembly::CatenaryModel::PointForce> loads;
  std::vector<std::size_t> loaded_by;  // the pantograph of each load
  for (std::size_t p = 0; p < system.pantographs().size(); ++p) {
    const auto& run = system.pantographs()[p].run;
    if (!run.static_start) continue;
    const int wire = lowest_wire(catenary, U0, run.start_x).first;
    if (wire < 0)
      throw InputError("", start_key(p), "the pantograph starts outside the contact wire");
    loads.push_back({run.start_x, wire, run.static_force});
    loaded_by.push_back(p);
  }
  if (catenary.closed_form_point_loads(loads, U0)) return 0;
  auto* fe = dynamic_cast<assembly::FECatenary*>(&catenary);
  if (!fe) return 0;
  // Active pins (a moving window's end that is the line's) hold their DOF.
  catenary::CatenaryMesh held = fe->mesh();
  for (const auto& pin : held.pins)
    if (pin.active) held.nodes[pin.node].fixed[pin.dof] = true;
  assembly::CatenarySystem loaded(system.comm(), std::move(held), 0,
                                  &fe->system().layout().node_owner());
  for (std::size_t i = 0; i < loads.size(); ++i) {
    int element;
    double chi;
    if (!fe->locator(loads[i].wire).locate(loads[i].x, element, chi))
      throw InputError("", start_key(loaded_by[i]),
                       "the pantograph starts outside the contact wire");
    loaded.point_loads().push_back({element, chi, Eigen::Vector3d(0, 0, loads[i].force)});
  }
  Vec x = loaded.create_vector();
  assembly::set_state_from_node_values(loaded, fe->static_node_values(), x);
  const auto result = solvers::solve_static(loaded, x, false, "start_load_");
  PCSIM_PETSC(VecDestroy(&x));
  assembly::set_state_from_node_values(fe->system(), result.node_values, U0);
  return result.snes_iterations;
}

// The start is an equilibrium to round-off: 1e-6 N on small meshes, ~6e-5 N
// on the EN 50318 one, where Newton then stops on its step (stol).
constexpr double kStartTolerance = 1e-5;

// The coupled Newton's problem. The rows of the pantographs that do not start
// static (ramp and gap starts) are held at their start state, U_i - U0_i = 0:
// a ramp start is in its own equilibrium already, a gap start out of it on
// purpose, and a pantograph whose uplift force does not depend on its height
// (the DSA-380's uplift characteristic) has no stiffness of its own out of
// contact, so its rows would make J singular.
struct CoupledStatic {
  assembly::CoupledSystem* system;
  Vec zero;
  Vec start = nullptr;              // U0 before the Newton, for the held rows
  std::vector<PetscInt> held_rows;  // this rank's held rows
};

PetscErrorCode coupled_residual(SNES, Vec U, Vec F, void* ptr) {
  PCSIM_CALLBACK_BEGIN
  auto* c = static_cast<CoupledStatic*>(ptr);
  c->system->residual(0.0, U, c->zero, c->zero, F);
  if (!c->held_rows.empty()) {
    PetscInt lo, hi;
    PCSIM_PETSC(VecGetOwnershipRange(F, &lo, &hi));
    const PetscScalar *u, *u0;
    PetscScalar* f;
    PCSIM_PETSC(VecGetArrayRead(U, &u));
    PCSIM_PETSC(VecGetArrayRead(c->start, &u0));
    PCSIM_PETSC(VecGetArray(F, &f));
    for (PetscInt row : c->held_rows) f[row - lo] = u[row - lo] - u0[row - lo];
    PCSIM_PETSC(VecRestoreArray(F, &f));
    PCSIM_PETSC(VecRestoreArrayRead(c->start, &u0));
    PCSIM_PETSC(VecRestoreArrayRead(U, &u));
  }
  PCSIM_CALLBACK_END
}

PetscErrorCode coupled_jacobian(SNES, Vec U, Mat J, Mat P, void* ptr) {
  PCSIM_CALLBACK_BEGIN
  auto* c = static_cast<CoupledStatic*>(ptr);
  c->system->jacobian(0.0, U, c->zero, c->zero, {0.0, 0.0}, P);
  // The held rows: identity (collective; the pattern kept for the next assembly).
  PCSIM_PETSC(MatSetOption(P, MAT_KEEP_NONZERO_PATTERN, PETSC_TRUE));
  PCSIM_PETSC(MatZeroRows(P, static_cast<PetscInt>(c->held_rows.size()), c->held_rows.data(), 1.0,
                          nullptr, nullptr));
  if (J != P) {
    PCSIM_PETSC(MatAssemblyBegin(J, MAT_FINAL_ASSEMBLY));
    PCSIM_PETSC(MatAssemblyEnd(J, MAT_FINAL_ASSEMBLY));
  }
  PCSIM_CALLBACK_END
}

// A pantograph's rows of the start's residual are held to kStartTolerance,
// or to its own rounding floor where that is higher (the flexible DSA-380's
// stiff bars: ~2e-3 N, where Newton from the closed form measured 1.5e-4 N ->
// 8.3e-5 N, one dense LU of 25 s on the modal level, and stopped on its step).
double pantograph_tolerance(const assembly::PantographSlot& slot) {
  return std::max(kStartTolerance, slot.model->static_residual_floor());
}

// The coupled Newton's tolerance: the largest of them.
double start_tolerance(assembly::CoupledSystem& system) {
  double tolerance = kStartTolerance;
  for (const auto& slot : system.pantographs())
    tolerance = std::max(tolerance, pantograph_tolerance(slot));
  return tolerance;
}

// In equilibrium: each static start's rows of F within its tolerance, the
// catenary's rows within kStartTolerance (collective).
bool in_equilibrium(assembly::CoupledSystem& system, Vec F) {
  const auto& pantographs = system.pantographs();
  std::vector<double> squares(pantographs.size() + 1, 0.0);  // the pantographs', the rest's
  PetscInt lo, hi;
  const PetscScalar* f;
  PCSIM_PETSC(VecGetOwnershipRange(F, &lo, &hi));
  PCSIM_PETSC(VecGetArrayRead(F, &f));
  for (PetscInt i = lo; i < hi; ++i) {
    std::size_t part = pantographs.size();
    for (std::size_t p = 0; p < pantographs.size(); ++p)
      if (i >= pantographs[p].first_dof &&
          i < pantographs[p].first_dof + pantographs[p].dof_count())
        part = p;
    squares[part] += f[i - lo] * f[i - lo];
  }
  PCSIM_PETSC(VecRestoreArrayRead(F, &f));
  MPI_Allreduce(MPI_IN_PLACE, squares.data(), static_cast<int>(squares.size()), MPI_DOUBLE, MPI_SUM,
                system.comm());
  bool within = std::sqrt(squares.back()) < kStartTolerance;
  for (std::size_t p = 0; p < pantographs.size(); ++p)  // the others are held (a gap start is
    if (pantographs[p].run.static_start)                // out of equilibrium on purpose)
      within = within && std::sqrt(squares[p]) < pantograph_tolerance(pantographs[p]);
  return within;
}

// The Newton of the coupled start from U0 (its residual in F), with -start_.
PetscInt start_newton(assembly::CoupledSystem& system, CoupledStatic& ctx, Vec F, Vec U0) {
  Mat J = system.create_matrix();
  SNES snes;
  PCSIM_PETSC(SNESCreate(system.comm(), &snes));
  PCSIM_PETSC(SNESSetOptionsPrefix(snes, "start_"));
  PCSIM_PETSC(SNESSetFunction(snes, F, coupled_residual, &ctx));
  PCSIM_PETSC(SNESSetJacobian(snes, J, J, coupled_jacobian, &ctx));
  PCSIM_PETSC(SNESSetTolerances(snes, start_tolerance(system), 1e-12, 1e-12, 50, 100000));
  SNESLineSearch line_search;
  PCSIM_PETSC(SNESGetLineSearch(snes, &line_search));
  PCSIM_PETSC(SNESLineSearchSetType(line_search, SNESLINESEARCHBASIC));
  KSP ksp;
  PCSIM_PETSC(SNESGetKSP(snes, &ksp));
  // Exact, as -pcsim_step_solver chooses (dd: no fill from the stored zero
  // couplings of the pantographs with the whole contact wire).
  solvers::use_step_lu(ksp);
  PCSIM_PETSC(SNESSetFromOptions(snes));
  PCSIM_PETSC(SNESSolve(snes, nullptr, U0));
  SNESConvergedReason reason;
  PetscInt iterations = 0;
  PCSIM_PETSC(SNESGetConvergedReason(snes, &reason));
  PCSIM_PETSC(SNESGetIterationNumber(snes, &iterations));
  PCSIM_PETSC(SNESDestroy(&snes));
  PCSIM_PETSC(MatDestroy(&J));
  if (reason <= 0)
    throw SolverError(std::string("static start (coupled equilibrium) did not converge: ") +
                      SNESConvergedReasons[reason]);
  return iterations;
}

// Clear of the wire by this much while held (the largest gap start).
constexpr double kHeldClearance = 0.5;

// Holds the pantographs that do not start static at their state in U0, clear
// of the wire (no contact force while the catenary finds its equilibrium
// under the others); returns the wire's height at each of them (NaN for the
// others).
std::vector<double> hold_other_starts(assembly::CoupledSystem& system, CoupledStatic& ctx, Vec U0) {
  auto& pantographs = system.pantographs();
  std::vector<double> wire_z(pantographs.size(), std::nan(""));
  PetscInt lo, hi;
  PCSIM_PETSC(VecGetOwnershipRange(U0, &lo, &hi));
  for (std::size_t p = 0; p < pantographs.size(); ++p) {
    auto& slot = pantographs[p];
    if (slot.run.static_start) continue;
    double flexibility = 0;
    wire_z[p] = wire_height(system.catenary(), U0, slot.run.start_x, p, flexibility);
    slot.head_offset -= kHeldClearance;
    for (PetscInt i = slot.first_dof; i < slot.first_dof + slot.dof_count(); ++i)
      if (i >= lo && i < hi) ctx.held_rows.push_back(i);
  }
  PCSIM_PETSC(VecDuplicate(U0, &ctx.start));
  PCSIM_PETSC(VecCopy(U0, ctx.start));
  return wire_z;
}

// The held pantographs follow the solved wire: each moves with the wire under
// it, touching it (ramp) or its gap below it, as before the Newton.
void follow_solved_wire(assembly::CoupledSystem& system, const std::vector<double>& wire_z,
                        Vec U0) {
  auto& pantographs = system.pantographs();
  for (std::size_t p = 0; p < pantographs.size(); ++p) {
    if (std::isnan(wire_z[p])) continue;
    double flexibility = 0;
    const double solved_z =
        wire_height(system.catenary(), U0, pantographs[p].run.start_x, p, flexibility);
    pantographs[p].head_offset += kHeldClearance + (solved_z - wire_z[p]);
  }
}

PetscInt solve_coupled_static(assembly::CoupledSystem& system, Vec U0) {
  CoupledStatic ctx{&system, system.create_vector(), nullptr, {}};
  Vec F = system.create_vector();
  const auto destroy = [&] {
    VecDestroy(&F);
    VecDestroy(&ctx.zero);
    VecDestroy(&ctx.start);
  };
  PetscInt iterations = 0;
  try {
    PCSIM_PETSC(VecSet(ctx.zero, 0.0));
    // A start already in equilibrium (a modal catenary's closed form) needs no
    // Newton matrix (a modal one is dense).
    system.residual(0.0, U0, ctx.zero, ctx.zero, F);
    if (!in_equilibrium(system, F)) {
      const std::vector<double> wire_z = hold_other_starts(system, ctx, U0);
      iterations = start_newton(system, ctx, F, U0);
      follow_solved_wire(system, wire_z, U0);
    }
  } catch (...) {
    destroy();
    throw;
  }
  destroy();
  return iterations;
}

}  // namespace

StartInfo initial_state(assembly::CoupledSystem& system, Vec U0, Vec V0) {
  StartInfo info;
  auto& pantographs = system.pantographs();
  PCSIM_PETSC(VecSet(V0, 0.0));
  PCSIM_PETSC(VecSet(U0, 0.0));
  if (pantographs.empty()) return info;
  info.guess_iterations = catenary_start(system, U0);
  // Pantographs in static equilibrium: touching the wire (ramp, zero contact
  // force at t = 0) or pressing it with F0 (static start).
  for (std::size_t p = 0; p < pantographs.size(); ++p) {
    auto& slot = pantographs[p];
    double flexibility = 0;
    const double wire_z = wire_height(system.catenary(), U0, slot.run.start_x, p, flexibility);
    // Static start: pressed by F0 on the contact spring in series with the
    // wire's residual flexibility (a reduced catenary's); gap start: below
    // the wire (an initial state out of equilibrium).
    const double penetration =
        slot.run.static_start
            ? slot.run.static_force * (1.0 / system.contact_stiffness() + flexibility)
            : -slot.run.start_gap;
    const double contact_height = wire_z + penetration;
    const Eigen::VectorXd q0 = slot.model->static_equilibrium(
        slot.run.static_force,
        slot.run.working_height > 0 ? slot.run.working_height : contact_height);
    // Base of the pantograph: its contact point sits at the wire (thesis 3.3.1).
    slot.head_offset =
        contact_height - (q0[slot.model->contact_dof()] + slot.model->contact_offset());
    PetscInt lo, hi;
    PCSIM_PETSC(VecGetOwnershipRange(U0, &lo, &hi));
    for (int i = 0; i < slot.dof_count(); ++i)
      if (slot.first_dof + i >= lo && slot.first_dof + i < hi)
        PCSIM_PETSC(VecSetValue(U0, slot.first_dof + i, q0[i], INSERT_VALUES));
  }
  PCSIM_PETSC(VecAssemblyBegin(U0));
  PCSIM_PETSC(VecAssemblyEnd(U0));
  if (any_static_start(system)) info.coupled_iterations = solve_coupled_static(system, U0);
  return info;
}

}  // namespace pcsim::simulation
