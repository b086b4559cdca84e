// HHT TS on a distributed problem: a chain of masses with springs to its neighbours, cubic
// springs to ground and Rayleigh damping, on a 1-D DMDA (MPIAIJ Jacobian). The trajectory must
// not depend on the number of ranks: it is compared with a serial dense HHT written out here.
// pcsim-test-ranks: 1 2 3
#include <gtest/gtest.h>
#include <petscdmda.h>
#include <petscts.h>

#include <Eigen/Dense>
#include <cmath>
#include <iostream>
#include <vector>

#include "pcsim/core/error.hpp"
#include "pcsim/solvers/hht.hpp"

namespace {

constexpr int kN = 24;
constexpr double kSpring = 800.0, kCubic = 5e4, kA0 = 0.3, kA1 = 2e-3;
double mass(int i) {
  return 1.0 + 0.1 * i;
}
double load(double t) {
  return 5.0 + 20.0 * t;
}  // on the last mass

struct Chain {
  DM da = nullptr;
};

// F = M a + C v + K u + k3 u³ - f(t), C = a0 M + a1 K.
PetscErrorCode i2function(TS, PetscReal t, Vec U, Vec V, Vec A, Vec F, void* ctx) {
  DM da = static_cast<Chain*>(ctx)->da;
  Vec Ul, Vl;
  const PetscScalar *u, *v, *a;
  PetscScalar* f;
  PetscInt xs, xm;
  PetscFunctionBeginUser;
  PetscCall(DMGetLocalVector(da, &Ul));
  PetscCall(DMGetLocalVector(da, &Vl));
  PetscCall(DMGlobalToLocal(da, U, INSERT_VALUES, Ul));
  PetscCall(DMGlobalToLocal(da, V, INSERT_VALUES, Vl));
  PetscCall(DMDAVecGetArrayRead(da, Ul, &u));
  PetscCall(DMDAVecGetArrayRead(da, Vl, &v));
  PetscCall(DMDAVecGetArrayRead(da, A, &a));
  PetscCall(DMDAVecGetArray(da, F, &f));
  PetscCall(DMDAGetCorners(da, &xs, nullptr, nullptr, &xm, nullptr, nullptr));
  auto k_times = [&](const PetscScalar* x, PetscInt i) {
    double r = kSpring * x[i];  // spring to the left (wall at i = 0)
    if (i > 0) r -= kSpring * x[i - 1];
    if (i < kN - 1) r += kSpring * (x[i] - x[i + 1]);  // spring to the right
    return r;
  };
  for (PetscInt i = xs; i < xs + xm; ++i) {
    f[i] = mass(i) * a[i] + kA0 * mass(i) * v[i] + kA1 * k_times(v, i) + k_times(u, i) +
           kCubic * u[i] * u[i] * u[i] - (i == kN - 1 ? load(t) : 0.0);
  }
  PetscCall(DMDAVecRestoreArrayRead(da, Ul, &u));
  PetscCall(DMDAVecRestoreArrayRead(da, Vl, &v));
  PetscCall(DMDAVecRestoreArrayRead(da, A, &a));
  PetscCall(DMDAVecRestoreArray(da, F, &f));
  PetscCall(DMRestoreLocalVector(da, &Ul));
  PetscCall(DMRestoreLocalVector(da, &Vl));
  PetscFunctionReturn(0);
}

PetscErrorCode i2jacobian(TS, PetscReal, Vec U, Vec, Vec, PetscReal sv, PetscReal sa, Mat J, Mat P,
                          void* ctx) {
  DM da = static_cast<Chain*>(ctx)->da;
  const PetscScalar* u;
  PetscInt xs, xm;
  PetscFunctionBeginUser;
  PetscCall(DMDAVecGetArrayRead(da, U, &u));
  PetscCall(DMDAGetCorners(da, &xs, nullptr, nullptr, &xm, nullptr, nullptr));
  const double kscale = 1 + sv * kA1;  // K + sv a1 K
  for (PetscInt i = xs; i < xs + xm; ++i) {
    const double diag_k = kSpring * (i < kN - 1 ? 2 : 1);
    const double d = kscale * diag_k + 3 * kCubic * u[i] * u[i] + (sv * kA0 + sa) * mass(i);
    PetscCall(MatSetValue(P, i, i, d, INSERT_VALUES));
    if (i > 0) PetscCall(MatSetValue(P, i, i - 1, -kscale * kSpring, INSERT_VALUES));
    if (i < kN - 1) PetscCall(MatSetValue(P, i, i + 1, -kscale * kSpring, INSERT_VALUES));
  }
  PetscCall(DMDAVecRestoreArrayRead(da, U, &u));
  PetscCall(MatAssemblyBegin(P, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(P, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

double initial_u(int i) {
  return 0.02 * std::sin(0.3 * i);
}
double initial_v(int i) {
  return 0.1 * std::cos(0.2 * i);
}

// Serial dense HHT with Newton on positions, same method and initial acceleration.
std::vector<Eigen::VectorXd> reference(double dt, int steps, double alpha) {
  using Eigen::MatrixXd;
  using Eigen::VectorXd;
  MatrixXd M = MatrixXd::Zero(kN, kN), K = MatrixXd::Zero(kN, kN);
  for (int i = 0; i < kN; ++i) {
    M(i, i) = mass(i);
    K(i, i) = kSpring * (i < kN - 1 ? 2 : 1);
    if (i > 0) K(i, i - 1) = -kSpring;
    if (i < kN - 1) K(i, i + 1) = -kSpring;
  }
  const MatrixXd C = kA0 * M + kA1 * K;
  auto f = [&](double t, const VectorXd& u, const VectorXd& v) -> VectorXd {
    VectorXd r = C * v + K * u + kCubic * u.array().cube().matrix();
    r(kN - 1) -= load(t);
    return r;
  };
  const double g = 0.5 + alpha, b = 0.25 * (1 + alpha) * (1 + alpha);
  VectorXd u(kN), v(kN);
  for (int i = 0; i < kN; ++i) {
    u(i) = initial_u(i);
    v(i) = initial_v(i);
  }
  VectorXd a = M.ldlt().solve(-f(0, u, v));
  std::vector<VectorXd> out{u};
  for (int n = 0; n < steps; ++n) {
    const double t0 = n * dt, t1 = t0 + dt;
    const VectorXd f0 = f(t0, u, v);
    VectorXd u1 = u + dt * v + dt * dt * (0.5 - b) * a;
    for (int it = 0; it < 30; ++it) {
      const VectorXd a1 = (u1 - u - dt * v - dt * dt * (0.5 - b) * a) / (b * dt * dt);
      const VectorXd v1 = v + dt * ((1 - g) * a + g * a1);
      const VectorXd r = M * a1 + (1 - alpha) * f(t1, u1, v1) + alpha * f0;
      MatrixXd jac = M / (b * dt * dt) + (1 - alpha) * (K + g / (b * dt) * C);
      jac.diagonal() += (1 - alpha) * 3 * kCubic * u1.array().square().matrix();
      const VectorXd du = jac.lu().solve(-r);
      u1 += du;
      if (du.norm() < 1e-15 * (1 + u1.norm())) break;
    }
    const VectorXd a_new = (u1 - u - dt * v - dt * dt * (0.5 - b) * a) / (b * dt * dt);
    v += dt * ((1 - g) * a + g * a_new);
    a = a_new;
    u = u1;
    out.push_back(u);
  }
  return out;
}

}  // namespace

TEST(HHTParallel, DistributedChainMatchesSerialReference) {
  pcsim::solvers::register_hht_ts();
  const double dt = 2e-3, alpha = 0.1;
  const int steps = 150;
  Chain chain;
  PCSIM_PETSC(DMDACreate1d(PETSC_COMM_WORLD, DM_BOUNDARY_NONE, kN, 1, 1, nullptr, &chain.da));
  PCSIM_PETSC(DMSetUp(chain.da));
  Vec U, V, R;
  Mat J;
  PCSIM_PETSC(DMCreateGlobalVector(chain.da, &U));
  PCSIM_PETSC(VecDuplicate(U, &V));
  PCSIM_PETSC(VecDuplicate(U, &R));
  PCSIM_PETSC(DMCreateMatrix(chain.da, &J));
  PetscInt lo, hi;
  PCSIM_PETSC(VecGetOwnershipRange(U, &lo, &hi));
  for (PetscInt i = lo; i < hi; ++i) {
    PCSIM_PETSC(VecSetValue(U, i, initial_u(i), INSERT_VALUES));
    PCSIM_PETSC(VecSetValue(V, i, initial_v(i), INSERT_VALUES));
  }
  for (Vec x : {U, V}) {
    PCSIM_PETSC(VecAssemblyBegin(x));
    PCSIM_PETSC(VecAssemblyEnd(x));
  }
  TS ts;
  PCSIM_PETSC(TSCreate(PETSC_COMM_WORLD, &ts));
  PCSIM_PETSC(TSSetType(ts, pcsim::solvers::kTSHHT));
  PCSIM_PETSC(TSSetI2Function(ts, R, i2function, &chain));
  PCSIM_PETSC(TSSetI2Jacobian(ts, J, J, i2jacobian, &chain));
  PCSIM_PETSC(TS2SetSolution(ts, U, V));
  PCSIM_PETSC(TSSetTimeStep(ts, dt));
  PCSIM_PETSC(TSSetMaxSteps(ts, steps));
  PCSIM_PETSC(TSSetMaxTime(ts, 1e9));
  PCSIM_PETSC(TSSetExactFinalTime(ts, TS_EXACTFINALTIME_STEPOVER));
  pcsim::solvers::hht_set_alpha(ts, alpha);
  SNES snes;
  KSP ksp;
  PCSIM_PETSC(TSGetSNES(ts, &snes));
  PCSIM_PETSC(SNESSetTolerances(snes, 1e-12, 1e-13, 1e-15, 30, 100000));
  PCSIM_PETSC(SNESGetKSP(snes, &ksp));
  PCSIM_PETSC(KSPSetType(ksp, KSPGMRES));
  PCSIM_PETSC(KSPSetTolerances(ksp, 1e-15, 1e-14, PETSC_DEFAULT, 500));
  PCSIM_PETSC(TSSolve(ts, U));

  PetscInt done;
  PCSIM_PETSC(TSGetStepNumber(ts, &done));
  EXPECT_EQ(done, steps);
  const auto ref = reference(dt, steps, alpha);
  const Eigen::VectorXd& u_ref = ref.back();
  const PetscScalar* u;
  PCSIM_PETSC(VecGetArrayRead(U, &u));
  double local_err = 0;
  for (PetscInt i = lo; i < hi; ++i)
    local_err = std::max(local_err, std::abs(u[i - lo] - u_ref(i)));
  PCSIM_PETSC(VecRestoreArrayRead(U, &u));
  double err = 0;
  MPI_Allreduce(&local_err, &err, 1, MPI_DOUBLE, MPI_MAX, PETSC_COMM_WORLD);
  int rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (rank == 0)
    std::cout << "[ measured ] max |u - u_ref| = " << err << " (max |u_ref| "
              << u_ref.cwiseAbs().maxCoeff() << ")\n";
  EXPECT_LT(err, 1e-8 * u_ref.cwiseAbs().maxCoeff());  // GMRES/Newton tolerances
  EXPECT_GT(u_ref.cwiseAbs().maxCoeff(), 1e-3);        // the chain moved

  TSDestroy(&ts);
  VecDestroy(&U);
  VecDestroy(&V);
  VecDestroy(&R);
  MatDestroy(&J);
  DMDestroy(&chain.da);
}
