#include "pcsim/solvers/statics.hpp"

#include <petscsnes.h>
#include <petsctime.h>

#include "pcsim/assembly/static_problem.hpp"
#include "pcsim/catenary/reactions.hpp"
#include "pcsim/core/error.hpp"
#include "pcsim/solvers/direct.hpp"

namespace pcsim::solvers {

namespace {

PetscErrorCode static_residual(SNES, Vec x, Vec R, void* ctx) {
  PCSIM_CALLBACK_BEGIN
  static_cast<assembly::StaticProblem*>(ctx)->residual(x, R);
  PCSIM_CALLBACK_END
}

PetscErrorCode static_jacobian(SNES, Vec x, Mat J, Mat P, void* ctx) {
  PCSIM_CALLBACK_BEGIN
  static_cast<assembly::StaticProblem*>(ctx)->jacobian(x, P);
  if (J != P) {
    PCSIM_PETSC(MatAssemblyBegin(J, MAT_FINAL_ASSEMBLY));
    PCSIM_PETSC(MatAssemblyEnd(J, MAT_FINAL_ASSEMBLY));
  }
  PCSIM_CALLBACK_END
}

}  // namespace

catenary::StaticResult solve_static(assembly::CatenarySystem& system, Vec x, bool form_finding,
                                    const char* options_prefix, double abs_tolerance) {
  PetscLogDouble t0;
  PetscTime(&t0);
  assembly::StaticProblem problem(system, form_finding);
  Mat J = problem.create_matrix();
  Vec R;
  PCSIM_PETSC(VecDuplicate(x, &R));
  problem.initial_guess(x);
  SNES snes;
  PCSIM_PETSC(SNESCreate(system.comm(), &snes));
  if (options_prefix) PCSIM_PETSC(SNESSetOptionsPrefix(snes, options_prefix));
  PCSIM_PETSC(SNESSetFunction(snes, R, static_residual, &problem));
  PCSIM_PETSC(SNESSetJacobian(snes, J, J, static_jacobian, &problem));
  PCSIM_PETSC(SNESSetType(snes, SNESNEWTONLS));
  PCSIM_PETSC(SNESSetTolerances(snes, abs_tolerance, 1e-12, 1e-14, 50, 10000));
  KSP ksp;
  PCSIM_PETSC(SNESGetKSP(snes, &ksp));
  use_direct_lu(ksp, MATSOLVERMUMPS);
  std::vector<PetscReal> history(60, 0.0);
  PCSIM_PETSC(SNESSetConvergenceHistory(snes, history.data(), nullptr,
                                        static_cast<PetscInt>(history.size()), PETSC_TRUE));
  PCSIM_PETSC(SNESSetFromOptions(snes));
  PCSIM_PETSC(SNESSolve(snes, nullptr, x));

  SNESConvergedReason reason;
  PCSIM_PETSC(SNESGetConvergedReason(snes, &reason));
  PetscInt its = 0, lits = 0, n_hist = 0;
  PCSIM_PETSC(SNESGetIterationNumber(snes, &its));
  PCSIM_PETSC(SNESGetLinearSolveIterations(snes, &lits));
  PetscReal* hist_ptr = nullptr;
  PCSIM_PETSC(SNESGetConvergenceHistory(snes, &hist_ptr, nullptr, &n_hist));
  std::vector<double> residual_history(hist_ptr, hist_ptr + n_hist);
  PCSIM_PETSC(SNESDestroy(&snes));
  PCSIM_PETSC(MatDestroy(&J));
  PCSIM_PETSC(VecDestroy(&R));
  if (reason <= 0)
    throw SolverError(std::string("static solution did not converge (") +
                      SNESConvergedReasons[reason] + " after " + std::to_string(its) +
                      " Newton iterations); try -snes_monitor -snes_linesearch_type bt");
  catenary::StaticResult result = problem.finish(x);
  result.converged = true;
  result.converged_reason = SNESConvergedReasons[reason];
  result.snes_iterations = static_cast<int>(its);
  result.linear_iterations = static_cast<int>(lits);
  result.residual_history = std::move(residual_history);
  PetscLogDouble t1;
  PetscTime(&t1);
  result.wall_time_s = t1 - t0;
  return result;
}

StaticConfiguration static_configuration(MPI_Comm comm, const catenary::CatenaryMesh& design,
                                         bool form_finding, const char* options_prefix) {
  const PetscInt extra = form_finding ? assembly::form_finding_unknowns(design) : 0;
  assembly::CatenarySystem system(comm, design, extra);
  Vec x = system.create_vector();
  system.design_state(x);
  StaticConfiguration config;
  try {
    config.result = solve_static(system, x, form_finding, options_prefix);
  } catch (...) {
    VecDestroy(&x);
    throw;
  }
  PCSIM_PETSC(VecDestroy(&x));
  config.mesh = system.mesh();
  // Pull-off forces, and the tensioning devices released with the anchors'
  // forces: later systems (modes, dynamics) see the devices.
  config.result.registration_forces =
      catenary::registration_forces(config.mesh, config.result.node_values);
  catenary::release_tensioning_devices(config.mesh, config.result.node_values);
  config.node_owner = system.layout().node_owner();
  config.catenary_dofs = system.layout().catenary_dofs();
  return config;
}

}  // namespace pcsim::solvers
