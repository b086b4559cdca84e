#include "pcsim/solvers/dynamics.hpp"

#include <cstring>
#include <string>

#include "choice_option.hpp"
#include "pc_types.hpp"
#include "pcsim/assembly/initial_acceleration.hpp"
#include "pcsim/core/error.hpp"
#include "pcsim/solvers/direct.hpp"
#include "pcsim/solvers/hht.hpp"
#include "pcsim/solvers/low_rank.hpp"
#include "pcsim/solvers/schur_dd.hpp"

namespace pcsim::solvers {

namespace {

// The step's -pc_type, if given: checked against the registered PC types
// (pcsim's included) before any work; "" when not given.
std::string step_pc_type() {
  LowRankStepSolver::register_pc();
  register_schur_pc();
  char type[256] = "";
  PetscBool given = PETSC_FALSE;
  PCSIM_PETSC(PetscOptionsGetString(nullptr, nullptr, "-pc_type", type, sizeof type, &given));
  if (!given) return "";
  PetscErrorCode (*create)(PC) = nullptr;
  PCSIM_PETSC(PetscFunctionListFind(PCList, type, &create));
  if (!create)
    throw InputError("command line", "-pc_type",
                     "unknown preconditioner '" + std::string(type) +
                         "' (pcsim's own: " + kPCWoodbury + ", the cheap path's step solver; " +
                         kPCSchur + ", the exact domain decomposition)");
  return type;
}

}  // namespace

// -pc_type pcsimwoodbury asks for the cheap path as -pcsim_path cheap does.
bool choose_cheap_path(MPI_Comm comm, bool possible) {
  const std::string path = read_choice_option(
      comm, {"-pcsim_path",
             "pcsim dynamic run",
             "Jacobian path: auto (cheap when every term allows it), full (exact Newton at every "
             "iteration), cheap (J0 factored once + exact low-rank terms + nonlinear "
             "pantographs' blocks refactored per iteration; its step solver is the PC type "
             "pcsimwoodbury)",
             "auto",
             {"auto", "full", "cheap"}});
  const bool woodbury = step_pc_type() == kPCWoodbury;
  if (woodbury && path == "full")
    throw InputError("command line", "-pc_type",
                     std::string(kPCWoodbury) +
                         " is the cheap path's step solver, and -pcsim_path full asks for the "
                         "full Newton path");
  if ((path == "cheap" || woodbury) && !possible)
    throw InputError("command line", woodbury ? "-pc_type" : "-pcsim_path",
                     "the cheap path needs a linearised or modal catenary (a term of this scene "
                     "changes its tangent with the state)");
  return path == "auto" ? possible : path == "cheap" || woodbury;
}

DynamicSolver::DynamicSolver(assembly::CoupledSystem& system, double dt, double duration,
                             double hht_alpha)
    : system_(system) {
  const bool cheap = choose_cheap_path(system.comm(), system.cheap_path_possible());
  register_hht_ts();
  PCSIM_PETSC(TSCreate(system.comm(), &ts_));
  PCSIM_PETSC(TSSetType(ts_, kTSHHT));
  Vec F = system.create_vector();
  PCSIM_PETSC(TSSetI2Function(ts_, F, residual, this));
  PCSIM_PETSC(VecDestroy(&F));
  P_ = cheap ? system.create_reference_matrix() : system.create_matrix();
  if (cheap) low_rank_ = std::make_unique<LowRankStepSolver>(P_, "cheap_");
  PCSIM_PETSC(TSSetI2Jacobian(ts_, cheap ? low_rank_->op() : P_, P_, jacobian, this));
  PCSIM_PETSC(TSSetTimeStep(ts_, dt));
  PCSIM_PETSC(TSSetMaxTime(ts_, duration));
  PCSIM_PETSC(TSSetMaxSteps(ts_, 100000000));
  PCSIM_PETSC(TSSetExactFinalTime(ts_, TS_EXACTFINALTIME_MATCHSTEP));
  SNES snes;
  PCSIM_PETSC(TSGetSNES(ts_, &snes));
  // Residuals are forces [N]. The step matrix is dominated by M/(beta dt^2)
  // (~2e6 N/m per wire node at dt = 1 ms), so a residual r leaves position
  // errors ~r/2e6 m and contact-force errors ~kH r/2e6 = 0.025 r N. Measured on
  // the EN 50318 case: atol 5e-2 N changes the contact force by at most 6e-3 N
  // against atol 1e-2 N (statistics by <= 0.01 N) and saves 40 % of the
  // Newton iterations. -snes_atol tightens it.
  PCSIM_PETSC(SNESSetTolerances(snes, 5e-2, 1e-9, 0.0, 25, 100000));
  SNESLineSearch line_search;
  PCSIM_PETSC(SNESGetLineSearch(snes, &line_search));
  PCSIM_PETSC(SNESLineSearchSetType(line_search, SNESLINESEARCHBASIC));
  KSP ksp;
  PC pc;
  PCSIM_PETSC(SNESGetKSP(snes, &ksp));
  PCSIM_PETSC(KSPSetType(ksp, KSPPREONLY));
  PCSIM_PETSC(KSPGetPC(ksp, &pc));
  if (cheap) {
    use_step_lu(low_rank_->inner());
    PCSIM_PETSC(KSPSetFromOptions(low_rank_->inner()));
    low_rank_->install(pc);
  } else {
    use_step_lu(ksp);
  }
  hht_set_alpha(ts_, hht_alpha);  // before the options: -ts_hht_alpha wins
  // F affine in A (M constant or the pantographs' configuration-dependent mass,
  // assembly/term.hpp): each step's alpha-term from the last residual.
  hht_set_inertia_product(ts_, inertia_product, this);
  // The cheap path's exact solves give the residual after an update without the
  // linear parts' products (two of the three largest products of a step).
  if (cheap && system.enable_residual_update()) hht_set_residual_update(ts_, residual_update, this);
  PCSIM_PETSC(TSSetFromOptions(ts_));
  configure_direct_solvers();
}

DynamicSolver::~DynamicSolver() {
  VecDestroy(&reference_U_);
  VecDestroy(&reference_V_);
  VecDestroy(&reference_A_);
  TSDestroy(&ts_);
  low_rank_.reset();
  MatDestroy(&P_);
}

KSP DynamicSolver::step_ksp() const {
  if (low_rank_) return low_rank_->inner();
  SNES snes;
  KSP ksp;
  PCSIM_PETSC(TSGetSNES(ts_, &snes));
  PCSIM_PETSC(SNESGetKSP(snes, &ksp));
  return ksp;
}

// MUMPS's ordering is set on its factor object, which exists once the KSP
// has its operators (the ones the TS will give it).
void DynamicSolver::configure_direct_solvers() {
  KSP ksp = step_ksp();
  PCSIM_PETSC(KSPSetOperators(ksp, P_, P_));
  set_mumps_metis_ordering(ksp);
}

PetscErrorCode DynamicSolver::residual(TS, PetscReal t, Vec U, Vec V, Vec A, Vec F, void* ctx) {
  PCSIM_CALLBACK_BEGIN
  static_cast<DynamicSolver*>(ctx)->system_.residual(t, U, V, A, F);
  PCSIM_CALLBACK_END
}

PetscErrorCode DynamicSolver::inertia_product(TS, PetscReal t, Vec U, Vec V, Vec A, Vec MA,
                                              void* ctx) {
  PCSIM_CALLBACK_BEGIN
  static_cast<DynamicSolver*>(ctx)->system_.inertia_product(t, U, V, A, MA);
  PCSIM_CALLBACK_END
}

// The SNES's KSP applies the Woodbury solver once (preonly) and J0's solve is
// exact: an update Y then solves (J0 + D) Y = R to round-off.
bool DynamicSolver::step_solve_exact() const {
  SNES snes;
  KSP ksp;
  PCSIM_PETSC(TSGetSNES(ts_, &snes));
  PCSIM_PETSC(SNESGetKSP(snes, &ksp));
  return low_rank_ && preonly_with(ksp, {kPCWoodbury}) && low_rank_->solves_exactly();
}

PetscErrorCode DynamicSolver::residual_update(TS, PetscReal t, Vec X, Vec V, Vec A, Vec Y, Vec F,
                                              PetscBool* done, void* ctx) {
  PCSIM_CALLBACK_BEGIN
  auto* self = static_cast<DynamicSolver*>(ctx);
  *done = PETSC_FALSE;
  if (!self->step_solve_exact() || !self->system_.residual_update(t, X, V, A, Y, F)) return 0;
  self->low_rank_->add_change_product(Y, F);
  *done = PETSC_TRUE;
  PCSIM_CALLBACK_END
}

void DynamicSolver::residual_changed() {
  TSType type;
  PCSIM_PETSC(TSGetType(ts_, &type));
  if (std::string(type) == kTSHHT) hht_invalidate_alpha_term(ts_);
}

PetscErrorCode DynamicSolver::jacobian(TS, PetscReal t, Vec U, Vec V, Vec A, PetscReal shift_v,
                                       PetscReal shift_a, Mat J, Mat P, void* ctx) {
  PCSIM_CALLBACK_BEGIN
  auto* self = static_cast<DynamicSolver*>(ctx);
  const assembly::Shifts shifts{shift_v, shift_a};
  if (self->low_rank_)
    self->cheap_jacobian(t, U, V, A, shifts, P);
  else
    self->system_.jacobian(t, U, V, A, shifts, P);
  if (J != P) {  // the low-rank operator changed with its terms
    PCSIM_PETSC(MatAssemblyBegin(J, MAT_FINAL_ASSEMBLY));
    PCSIM_PETSC(MatAssemblyEnd(J, MAT_FINAL_ASSEMBLY));
  }
  PCSIM_CALLBACK_END
}

// J0 is kept while the shifts (the time step) stay and no term asks for a
// new one; the low-rank terms and the varying blocks (nonlinear pantographs)
// follow the state at every Newton iteration.
void DynamicSolver::cheap_jacobian(PetscReal t, Vec U, Vec V, Vec A, assembly::Shifts shifts,
                                   Mat P) {
  const bool same_shifts = shifts.v == cached_shift_v_ && shifts.a == cached_shift_a_;
  if (same_shifts && system_.low_rank_change(t, U, V, A, terms_, shifts, &blocks_)) {
    low_rank_->set_terms(terms_, blocks_);
    return;
  }
  system_.reference_jacobian(t, U, V, A, shifts, P);
  ++reference_builds_;
  cached_shift_v_ = shifts.v;
  cached_shift_a_ = shifts.a;
  reference_t_ = t;
  const std::pair<Vec, Vec*> copies[] = {
      {U, &reference_U_}, {V, &reference_V_}, {A, &reference_A_}};
  for (const auto& [from, to] : copies) {
    if (!*to) PCSIM_PETSC(VecDuplicate(from, to));
    PCSIM_PETSC(VecCopy(from, *to));
  }
  low_rank_->invalidate();
  system_.low_rank_change(t, U, V, A, terms_, shifts, &blocks_);
  low_rank_->set_terms(terms_, blocks_);
}

void DynamicSolver::silence_monitors() {
  SNES snes;
  KSP ksp;
  PCSIM_PETSC(TSMonitorCancel(ts_));
  PCSIM_PETSC(TSGetSNES(ts_, &snes));
  PCSIM_PETSC(SNESMonitorCancel(snes));
  PCSIM_PETSC(SNESGetKSP(snes, &ksp));
  PCSIM_PETSC(KSPMonitorCancel(ksp));
  if (low_rank_) PCSIM_PETSC(KSPMonitorCancel(low_rank_->inner()));
}

void DynamicSolver::set_initial_state(Vec U0, Vec V0) {
  PCSIM_PETSC(TS2SetSolution(ts_, U0, V0));
  TSType ts_type;
  PCSIM_PETSC(TSGetType(ts_, &ts_type));
  if (std::string(ts_type) != kTSHHT) return;
  // Static and ramp starts are equilibria (A0 = 0); a gap start is not.
  Vec A0 = system_.create_vector();
  assembly::initial_acceleration(system_, U0, V0, A0);
  hht_set_initial_acceleration(ts_, A0);
  PCSIM_PETSC(VecDestroy(&A0));
}

}  // namespace pcsim::solvers
