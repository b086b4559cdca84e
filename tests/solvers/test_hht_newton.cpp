// The HHT type's own Newton iteration (src/solvers/hht_newton.cpp) is the
// SNES's (newtonls, basic line search, SNESConvergedDefault) written out: on a
// nonlinear model (a Duffing chain with damping and a forcing) both give the
// same iterates, so every step's state is equal bit for bit, with the
// default tolerances and with a step-length test (-snes_stol, which the own
// iteration honours). An -snes_ option other than a tolerance selects the SNES.
#include <gtest/gtest.h>
#include <petscts.h>

#include <Eigen/Dense>
#include <cmath>
#include <string>
#include <vector>

#include "hht_test_models.hpp"
#include "pcsim/core/error.hpp"
#include "pcsim/solvers/hht.hpp"

namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;
using hht_models::from_eigen;
using hht_models::to_eigen;

constexpr int kDofs = 3;

// M a + C v + K u + k3 u^3 = f(t): three masses in a chain, cubic springs.
VectorXd residual(double t, const VectorXd& u, const VectorXd& v, const VectorXd& a) {
  VectorXd f(kDofs);
  for (int i = 0; i < kDofs; ++i) {
    const double left = i > 0 ? u[i - 1] : 0.0, right = i + 1 < kDofs ? u[i + 1] : 0.0;
    f[i] = (1.0 + i) * a[i] + 0.3 * v[i] + 40.0 * (2 * u[i] - left - right) +
           25.0 * u[i] * u[i] * u[i] - (i == 0 ? 10.0 * std::sin(7.0 * t) : 0.0);
  }
  return f;
}

MatrixXd tangent(const VectorXd& u, double sv, double sa) {
  MatrixXd J = MatrixXd::Zero(kDofs, kDofs);
  for (int i = 0; i < kDofs; ++i) {
    J(i, i) = 80.0 + 75.0 * u[i] * u[i] + 0.3 * sv + (1.0 + i) * sa;
    if (i > 0) J(i, i - 1) = -40.0;
    if (i + 1 < kDofs) J(i, i + 1) = -40.0;
  }
  return J;
}

PetscErrorCode i2function(TS, PetscReal t, Vec U, Vec V, Vec A, Vec F, void*) {
  PCSIM_CALLBACK_BEGIN
  from_eigen(residual(t, to_eigen(U), to_eigen(V), to_eigen(A)), F);
  PCSIM_CALLBACK_END
}

PetscErrorCode i2jacobian(TS, PetscReal, Vec U, Vec, Vec, PetscReal sv, PetscReal sa, Mat, Mat P,
                          void*) {
  PCSIM_CALLBACK_BEGIN
  const MatrixXd J = tangent(to_eigen(U), sv, sa);
  for (int i = 0; i < kDofs; ++i)
    for (int j = 0; j < kDofs; ++j) PCSIM_PETSC(MatSetValue(P, i, j, J(i, j), INSERT_VALUES));
  PCSIM_PETSC(MatAssemblyBegin(P, MAT_FINAL_ASSEMBLY));
  PCSIM_PETSC(MatAssemblyEnd(P, MAT_FINAL_ASSEMBLY));
  PCSIM_CALLBACK_END
}

struct Trajectory {
  std::vector<VectorXd> u, v;
  PetscInt newton_iterations = 0;
  bool own_newton = false;
};

// 200 steps of 5 ms from u = (0.3, 0, -0.2), the TS's options under 'prefix'.
Trajectory integrate(const std::string& prefix, double stol) {
  pcsim::solvers::register_hht_ts();
  TS ts;
  Vec U, V, R;
  Mat J;
  PCSIM_PETSC(TSCreate(PETSC_COMM_SELF, &ts));
  PCSIM_PETSC(TSSetOptionsPrefix(ts, prefix.c_str()));
  PCSIM_PETSC(TSSetType(ts, pcsim::solvers::kTSHHT));
  PCSIM_PETSC(VecCreateSeq(PETSC_COMM_SELF, kDofs, &U));
  PCSIM_PETSC(VecDuplicate(U, &V));
  PCSIM_PETSC(VecDuplicate(U, &R));
  PCSIM_PETSC(VecSet(V, 0.0));
  PCSIM_PETSC(VecSetValue(U, 0, 0.3, INSERT_VALUES));
  PCSIM_PETSC(VecSetValue(U, 1, 0.0, INSERT_VALUES));
  PCSIM_PETSC(VecSetValue(U, 2, -0.2, INSERT_VALUES));
  PCSIM_PETSC(MatCreateSeqDense(PETSC_COMM_SELF, kDofs, kDofs, nullptr, &J));
  PCSIM_PETSC(TSSetI2Function(ts, R, i2function, nullptr));
  PCSIM_PETSC(TSSetI2Jacobian(ts, J, J, i2jacobian, nullptr));
  PCSIM_PETSC(TS2SetSolution(ts, U, V));
  PCSIM_PETSC(TSSetTimeStep(ts, 5e-3));
  PCSIM_PETSC(TSSetMaxTime(ts, 1e30));
  SNES snes;
  KSP ksp;
  PC pc;
  PCSIM_PETSC(TSGetSNES(ts, &snes));
  SNESLineSearch line_search;
  PCSIM_PETSC(SNESGetLineSearch(snes, &line_search));
  PCSIM_PETSC(SNESLineSearchSetType(line_search, SNESLINESEARCHBASIC));
  PCSIM_PETSC(SNESSetTolerances(snes, 1e-10, 1e-9, stol, 25, 100000));
  PCSIM_PETSC(SNESGetKSP(snes, &ksp));
  PCSIM_PETSC(KSPSetType(ksp, KSPPREONLY));
  PCSIM_PETSC(KSPGetPC(ksp, &pc));
  PCSIM_PETSC(PCSetType(pc, PCLU));
  PCSIM_PETSC(TSSetFromOptions(ts));
  Trajectory out;
  for (int step = 0; step < 200; ++step) {
    PCSIM_PETSC(TSStep(ts));
    PetscInt its;
    PCSIM_PETSC(SNESGetIterationNumber(snes, &its));
    out.newton_iterations += its;
    Vec u, v;
    PCSIM_PETSC(TS2GetSolution(ts, &u, &v));
    out.u.push_back(to_eigen(u));
    out.v.push_back(to_eigen(v));
  }
  out.own_newton = pcsim::solvers::hht_get_info(ts).own_newton;
  TSDestroy(&ts);
  VecDestroy(&U);
  VecDestroy(&V);
  VecDestroy(&R);
  MatDestroy(&J);
  return out;
}

void expect_equal(const Trajectory& a, const Trajectory& b) {
  ASSERT_EQ(a.u.size(), b.u.size());
  EXPECT_EQ(a.newton_iterations, b.newton_iterations);
  for (std::size_t s = 0; s < a.u.size(); ++s)
    for (int i = 0; i < kDofs; ++i) {
      ASSERT_EQ(a.u[s][i], b.u[s][i]) << "step " << s << ", dof " << i;
      ASSERT_EQ(a.v[s][i], b.v[s][i]) << "step " << s << ", dof " << i;
    }
}

TEST(HHTNewton, OwnIterationEqualsTheSNES) {
  PCSIM_PETSC(PetscOptionsSetValue(nullptr, "-snes_ts_hht_use_snes", "1"));
  for (double stol : {0.0, 1e-3}) {
    const Trajectory own = integrate("own_", stol), snes = integrate("snes_", stol);
    EXPECT_TRUE(own.own_newton);
    EXPECT_FALSE(snes.own_newton);
    // A nonlinear problem: Newton iterates (more than one per step on average).
    EXPECT_GT(own.newton_iterations, 200);
    expect_equal(own, snes);
  }
}

TEST(HHTNewton, AnSnesOptionSelectsTheSNES) {
  PCSIM_PETSC(PetscOptionsSetValue(nullptr, "-monitored_snes_max_linear_solve_fail", "2"));
  PCSIM_PETSC(PetscOptionsSetValue(nullptr, "-tolerance_snes_atol", "1e-10"));
  EXPECT_FALSE(integrate("monitored_", 0.0).own_newton);
  EXPECT_TRUE(integrate("tolerance_", 0.0).own_newton);  // tolerances are read, not a reason
}

}  // namespace
