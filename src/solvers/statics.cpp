#include "pcsim/solvers/statics.hpp"

#include <petscsnes.h>
#include <petsctime.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "pcsim/assembly/static_problem.hpp"
#include "pcsim/core/error.hpp"
#include "pcsim/solvers/direct.hpp"
#include "pcsim/solvers/spectrum.hpp"

namespace pcsim::solvers {

namespace {

// Newton stops when ||R||_2 < kTargetTolerance x the loads (force_scale: the
// total weight or the largest design tension): 2e-4 N on EN 50318, where the
// rounding floor of the residual is 8e-5 N (measured: Newton stalls there).
// The element forces are sums of terms ~EA x coordinates / element length, so
// the floor grows with EA and the line's length (1.8e-4 N on two spans with EA
// 1e9); where it is above the target Newton stagnates (line search fails,
// steps vanish), and counts as converged when ||R||_inf < kStagnationTolerance
// x the loads: 1 ppm of the load per DOF, far below any physical effect
// (contact forces ~100 N) and far above rounding.
constexpr double kTargetTolerance = 1e-8;
constexpr double kStagnationTolerance = 1e-6;
// Elements whose axial force is below -kCompressionTolerance x the loads are
// reported (cables and droppers cannot push).
constexpr double kCompressionTolerance = 1e-6;

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

std::string sci(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2e", v);
  return text;
}

// Number of negative eigenvalues of the symmetric matrix K: the inertia of its
// MUMPS LDL^T factors (ICNTL(13) = 1: no ScaLAPACK root, so that a parallel
// factorisation reports it, as modes.cpp does for slicing; ICNTL(24) = 1:
// null pivots detected); -1 if K is singular.
int negative_eigenvalues(Mat K) {
  PCSIM_PETSC(MatSetOption(K, MAT_SYMMETRIC, PETSC_TRUE));
  KSP ksp;
  PC pc;
  Mat F;
  PCSIM_PETSC(KSPCreate(PetscObjectComm(reinterpret_cast<PetscObject>(K)), &ksp));
  PCSIM_PETSC(KSPSetOperators(ksp, K, K));
  PCSIM_PETSC(KSPSetType(ksp, KSPPREONLY));
  PCSIM_PETSC(KSPGetPC(ksp, &pc));
  PCSIM_PETSC(PCSetType(pc, PCCHOLESKY));
  PCSIM_PETSC(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
  PCSIM_PETSC(PCFactorSetUpMatSolverType(pc));
  PCSIM_PETSC(PCFactorGetMatrix(pc, &F));
  PCSIM_PETSC(MatMumpsSetIcntl(F, 13, 1));
  PCSIM_PETSC(MatMumpsSetIcntl(F, 24, 1));
  PCSIM_PETSC(KSPSetUp(ksp));
  PCFailedReason failed;
  PCSIM_PETSC(PCGetFailedReason(pc, &failed));
  PetscInt negative = -1, zero = 0, positive = 0;
  if (failed == PC_NOERROR) PCSIM_PETSC(MatGetInertia(F, &negative, &zero, &positive));
  PCSIM_PETSC(KSPDestroy(&ksp));
  return zero > 0 ? -1 : static_cast<int>(negative);
}

// Warns about a tangent that is not positive definite (an unstable or
// singular equilibrium: a compressed cable that would buckle, a loose part).
void check_tangent(assembly::StaticProblem& problem, Vec x, catenary::StaticResult& result) {
  Mat K = problem.create_matrix();
  problem.static_tangent(x, K);
  result.negative_eigenvalues = negative_eigenvalues(K);
  PCSIM_PETSC(MatDestroy(&K));
  if (result.negative_eigenvalues < 0)
    result.warnings.push_back(
        "the tangent stiffness at the static configuration is singular (a part of the structure "
        "is held by nothing): the equilibrium is not unique");
  else if (result.negative_eigenvalues > 0)
    result.warnings.push_back(
        "the tangent stiffness at the static configuration has " +
        std::to_string(result.negative_eigenvalues) +
        " negative eigenvalue(s) (MUMPS LDL^T inertia): the equilibrium is unstable (a wire in "
        "compression that would buckle?)");
}

// "wire 'contact': 3 cable elements (4, 5, 9) between x = 1 and 9 m, down to -2e+03 N".
std::string describe(const std::string& what,
                     const std::vector<assembly::StaticProblem::Compressed>& group) {
  std::string indices;
  double x0 = group.front().x, x1 = x0, least = 0;
  for (std::size_t k = 0; k < group.size(); ++k) {
    if (k < 5) indices += (k ? ", " : "") + std::to_string(group[k].index);
    x0 = std::min(x0, group[k].x);
    x1 = std::max(x1, group[k].x);
    least = std::min(least, group[k].force);
  }
  if (group.size() > 5) indices += ", ...";
  return what + ": " + std::to_string(group.size()) + " (" + indices + ") between x = " + sci(x0) +
         " and " + sci(x1) + " m, down to " + sci(least) + " N";
}

// Cables and droppers in compression: a warning naming them; at form-finding
// a compressed cable is an error (no tension distribution of the design).
void check_compression(const assembly::StaticProblem& problem, const catenary::CatenaryMesh& mesh,
                       bool form_finding, catenary::StaticResult& result) {
  const double tolerance = kCompressionTolerance * result.force_scale;
  const auto list = problem.compressed_elements(tolerance);
  if (list.empty()) return;
  std::vector<std::vector<assembly::StaticProblem::Compressed>> by_wire(mesh.wires.size());
  std::vector<assembly::StaticProblem::Compressed> bars;
  for (const auto& c : list) (c.cable ? by_wire[mesh.cables[c.index].wire] : bars).push_back(c);
  std::string text;
  bool cables = false;
  for (std::size_t w = 0; w < by_wire.size(); ++w) {
    if (by_wire[w].empty()) continue;
    cables = true;
    text += (text.empty() ? "" : "; ") +
            describe("wire '" + mesh.wires[w].name + "', cable elements", by_wire[w]);
  }
  if (!bars.empty())
    text += (text.empty() ? "" : "; ") + describe("droppers and stitch-wire bars", bars);
  text = "elements in compression (beyond " + sci(tolerance) +
         " N) at the static configuration: " + text;
  if (form_finding && cables)
    throw InputError(mesh.source_file, "wires",
                     "form-finding found no tension distribution: " + text +
                         "; check the design tensions, heights and dropper positions");
  result.warnings.push_back(text + "; wires and droppers cannot carry compression");
}

// Converged: by the SNES tests, or stagnated at rounding below the
// stagnation tolerance. Throws SolverError otherwise.
std::string judge_convergence(SNESConvergedReason reason, double residual_inf, double scale,
                              PetscInt its) {
  if (reason == SNES_CONVERGED_FNORM_ABS || reason == SNES_CONVERGED_FNORM_RELATIVE)
    return SNESConvergedReasons[reason];
  if (residual_inf <= kStagnationTolerance * scale)
    return std::string("stagnated at rounding (") + SNESConvergedReasons[reason] + ", max |R| " +
           sci(residual_inf) + " N below " + sci(kStagnationTolerance * scale) + " N)";
  throw SolverError(
      std::string("static solution did not converge (") + SNESConvergedReasons[reason] + " after " +
      std::to_string(its) + " Newton iterations, max |R| " + sci(residual_inf) + " N, tolerance " +
      sci(kStagnationTolerance * scale) + " N); try -snes_monitor -snes_linesearch_type bt");
}

// The tangent without form-finding is symmetric (a potential's Hessian):
// Cholesky, on one rank PETSc's with RCM ordering (the line's band), as the
// modes (spectrum.hpp); the elasticity of stitched.yaml took 75 s with MUMPS's
// LU and 7 s so (docs/catenary.md). Form-finding's rows make it unsymmetric
// and put zeros on its diagonal: an LU with pivots, on one rank SuiteSparse's
// KLU (no BLAS: MUMPS's solves are slow with BLIS; 1000 spans: SNESSolve
// 19.3 s against 45.1 s, docs/catenary.md), in parallel MUMPS's.
void use_static_factorisation(KSP ksp, Mat J, bool form_finding) {
  if (form_finding) {
    PetscMPIInt ranks;
    PCSIM_PETSC(MPI_Comm_size(PetscObjectComm(reinterpret_cast<PetscObject>(J)), &ranks));
    use_direct_lu(ksp, ranks > 1 ? MATSOLVERMUMPS : MATSOLVERKLU);
    return;
  }
  PCSIM_PETSC(MatSetOption(J, MAT_SYMMETRIC, PETSC_TRUE));
  PCSIM_PETSC(MatSetOption(J, MAT_SYMMETRY_ETERNAL, PETSC_TRUE));
  PCSIM_PETSC(KSPSetType(ksp, KSPPREONLY));
  PC pc;
  PCSIM_PETSC(KSPGetPC(ksp, &pc));
  use_line_cholesky(pc);
}

}  // namespace

catenary::StaticResult solve_static(assembly::CatenarySystem& system, Vec x, bool form_finding,
                                    const char* options_prefix, double abs_tolerance,
                                    bool equilibrium_checks) {
  PetscLogDouble t0;
  PetscTime(&t0);
  assembly::StaticProblem problem(system, form_finding);
  const double scale = problem.force_scale();
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
  const double target = abs_tolerance > 0 ? abs_tolerance : kTargetTolerance * scale;
  PCSIM_PETSC(SNESSetTolerances(snes, target, 1e-12, 1e-14, 50, 10000));
  KSP ksp;
  PCSIM_PETSC(SNESGetKSP(snes, &ksp));
  use_static_factorisation(ksp, J, form_finding);
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
  problem.residual(x, R);  // at the final iterate, whatever stopped Newton
  PetscReal residual_inf = 0, residual_2 = 0;
  PCSIM_PETSC(VecNorm(R, NORM_INFINITY, &residual_inf));
  PCSIM_PETSC(VecNorm(R, NORM_2, &residual_2));
  PCSIM_PETSC(VecDestroy(&R));
  const std::string verdict = judge_convergence(reason, residual_inf, scale, its);
  catenary::StaticResult checks;
  checks.force_scale = scale;
  if (equilibrium_checks) check_tangent(problem, x, checks);
  catenary::StaticResult result = problem.finish(x);
  result.force_scale = scale;
  result.negative_eigenvalues = checks.negative_eigenvalues;
  result.warnings = std::move(checks.warnings);
  if (equilibrium_checks) check_compression(problem, system.mesh(), form_finding, result);
  result.converged = true;
  result.converged_reason = verdict;
  result.residual_norm = residual_2;
  result.snes_iterations = static_cast<int>(its);
  result.linear_iterations = static_cast<int>(lits);
  result.residual_history = std::move(residual_history);
  PetscLogDouble t1;
  PetscTime(&t1);
  result.wall_time_s = t1 - t0;
  return result;
}

}  // namespace pcsim::solvers
