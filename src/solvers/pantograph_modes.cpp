#include "pcsim/solvers/pantograph_modes.hpp"

#include <slepceps.h>

#include "pcsim/core/error.hpp"

namespace pcsim::solvers {

namespace {

Mat dense(const Eigen::MatrixXd& A) {
  Mat m;
  const int n = static_cast<int>(A.rows());
  PCSIM_PETSC(MatCreateSeqDense(PETSC_COMM_SELF, n, n, nullptr, &m));
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) PCSIM_PETSC(MatSetValue(m, i, j, A(i, j), INSERT_VALUES));
  PCSIM_PETSC(MatAssemblyBegin(m, MAT_FINAL_ASSEMBLY));
  PCSIM_PETSC(MatAssemblyEnd(m, MAT_FINAL_ASSEMBLY));
  return m;
}

// All eigenpairs of A x = λ B x with SLEPc's dense (LAPACK) solver, applied to the
// shift-and-invert operator (A − σB)⁻¹B about a target σ away from the spectrum (its
// eigenvalues 1/(λ − σ)): the modes near σ, the ones of interest, come out as the
// largest and best conditioned. Without it the QZ reordering of the pencil fails
// (LAPACK tgexc) on the flexible model's state-space form, whose |λ| span 0.6 Hz to 4e5 Hz.
void slepc_all_eigenpairs(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, double target,
                          Eigen::VectorXcd* values, Eigen::MatrixXcd* vectors) {
  const int n = static_cast<int>(A.rows());
  Mat a = dense(A), b = dense(B);
  EPS eps;
  PCSIM_PETSC(EPSCreate(PETSC_COMM_SELF, &eps));
  PCSIM_PETSC(EPSSetOperators(eps, a, b));
  PCSIM_PETSC(EPSSetProblemType(eps, EPS_GNHEP));
  PCSIM_PETSC(EPSSetType(eps, EPSLAPACK));
  ST st;
  PCSIM_PETSC(EPSGetST(eps, &st));
  PCSIM_PETSC(STSetType(st, STSINVERT));
  PCSIM_PETSC(EPSSetTarget(eps, target));
  PCSIM_PETSC(EPSSetWhichEigenpairs(eps, EPS_TARGET_MAGNITUDE));
  PCSIM_PETSC(EPSSetDimensions(eps, n, PETSC_DEFAULT, PETSC_DEFAULT));
  PCSIM_PETSC(EPSSolve(eps));
  PetscInt nconv = 0;
  PCSIM_PETSC(EPSGetConverged(eps, &nconv));
  if (nconv < n) throw SolverError("pantograph modes: SLEPc converged fewer eigenpairs than DOFs");
  Vec xr, xi;
  PCSIM_PETSC(MatCreateVecs(a, &xr, nullptr));
  PCSIM_PETSC(VecDuplicate(xr, &xi));
  values->resize(n);
  vectors->resize(n, n);
  for (int k = 0; k < n; ++k) {
    PetscScalar kr, ki;
    PCSIM_PETSC(EPSGetEigenpair(eps, k, &kr, &ki, xr, xi));
    (*values)[k] = {kr, ki};
    const PetscScalar *pr, *pi;
    PCSIM_PETSC(VecGetArrayRead(xr, &pr));
    PCSIM_PETSC(VecGetArrayRead(xi, &pi));
    for (int i = 0; i < n; ++i) (*vectors)(i, k) = {pr[i], pi[i]};
    PCSIM_PETSC(VecRestoreArrayRead(xr, &pr));
    PCSIM_PETSC(VecRestoreArrayRead(xi, &pi));
  }
  PCSIM_PETSC(VecDestroy(&xr));
  PCSIM_PETSC(VecDestroy(&xi));
  PCSIM_PETSC(EPSDestroy(&eps));
  PCSIM_PETSC(MatDestroy(&a));
  PCSIM_PETSC(MatDestroy(&b));
}

}  // namespace

std::vector<pantograph::Mode> undamped_modes_slepc(const pantograph::LinearModel& lin) {
  const pantograph::RestraintReduction r = pantograph::reduce_restraints(lin);
  Eigen::VectorXcd lambda;
  Eigen::MatrixXcd vec;
  // σ = −1 rad²/s²: below the spectrum of a stable model (restrained rows add λ = 0).
  slepc_all_eigenpairs(r.reduced.K, r.reduced.M, -1.0, &lambda, &vec);
  const Eigen::MatrixXcd vectors = r.T * vec;
  return pantograph::undamped_modes_from_eigenpairs(lin, lambda, vectors);
}

std::vector<pantograph::Mode> damped_modes_slepc(const pantograph::LinearModel& lin) {
  const pantograph::RestraintReduction r = pantograph::reduce_restraints(lin);
  Eigen::MatrixXd A, B;
  pantograph::state_space(r.reduced, &A, &B);
  Eigen::VectorXcd lambda;
  Eigen::MatrixXcd vec;
  // σ = 0.1 s⁻¹: right of the spectrum of a stable model (Re λ ≤ 0).
  slepc_all_eigenpairs(-B, A, 0.1, &lambda, &vec);  // (λ A + B) Y = 0
  return pantograph::damped_modes_from_eigenpairs(lin, lambda, pantograph::expand_state(r.T, vec));
}

}  // namespace pcsim::solvers
