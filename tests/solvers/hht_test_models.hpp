// Small dense second-order models and a TS driver for the tests of the HHT-α
// TS type (test_hht.cpp, test_hht_alpha_term.cpp, test_hht_newton.cpp).
#pragma once

#include <petscts.h>

#include <Eigen/Dense>
#include <cmath>
#include <functional>
#include <vector>

#include "pcsim/core/error.hpp"
#include "pcsim/solvers/hht.hpp"

namespace hht_models {

using Eigen::MatrixXd;
using Eigen::VectorXd;

// Small dense second-order model F(t, u, v, a) = M(u) a + f(t, u, v) = 0.
struct Model {
  int n = 0;
  std::function<VectorXd(double t, const VectorXd& u, const VectorXd& v, const VectorXd& a)> F;
  // dF/du + sv dF/dv + sa dF/da
  std::function<MatrixXd(double t, const VectorXd& u, const VectorXd& v, const VectorXd& a,
                         double sv, double sa)>
      J;
};

inline VectorXd to_eigen(Vec x) {
  PetscInt n = 0;
  const PetscScalar* a = nullptr;
  PCSIM_PETSC(VecGetLocalSize(x, &n));
  PCSIM_PETSC(VecGetArrayRead(x, &a));
  VectorXd out = Eigen::Map<const VectorXd>(a, n);
  PCSIM_PETSC(VecRestoreArrayRead(x, &a));
  return out;
}

inline void from_eigen(const VectorXd& in, Vec x) {
  PetscScalar* a = nullptr;
  PCSIM_PETSC(VecGetArray(x, &a));
  Eigen::Map<VectorXd>(a, in.size()) = in;
  PCSIM_PETSC(VecRestoreArray(x, &a));
}

inline PetscErrorCode i2function(TS, PetscReal t, Vec U, Vec V, Vec A, Vec F, void* ctx) {
  const Model* m = static_cast<const Model*>(ctx);
  PCSIM_CALLBACK_BEGIN
  from_eigen(m->F(t, to_eigen(U), to_eigen(V), to_eigen(A)), F);
  PCSIM_CALLBACK_END
}

inline PetscErrorCode i2jacobian(TS, PetscReal t, Vec U, Vec V, Vec A, PetscReal sv, PetscReal sa,
                                 Mat J, Mat P, void* ctx) {
  const Model* m = static_cast<const Model*>(ctx);
  PCSIM_CALLBACK_BEGIN
  MatrixXd jac = m->J(t, to_eigen(U), to_eigen(V), to_eigen(A), sv, sa);
  for (int i = 0; i < m->n; ++i)
    for (int j = 0; j < m->n; ++j) PCSIM_PETSC(MatSetValue(P, i, j, jac(i, j), INSERT_VALUES));
  PCSIM_PETSC(MatAssemblyBegin(P, MAT_FINAL_ASSEMBLY));
  PCSIM_PETSC(MatAssemblyEnd(P, MAT_FINAL_ASSEMBLY));
  PCSIM_CALLBACK_END
}

// One TS on a Model, recording (t, u, v) at every monitor call (step 0 included).
class TsRun {
 public:
  TsRun(const Model& model, const char* type, const VectorXd& u0, const VectorXd& v0, double dt,
        const char* prefix = nullptr)
      : model_(model) {
    pcsim::solvers::register_hht_ts();
    PCSIM_PETSC(TSCreate(PETSC_COMM_SELF, &ts));
    if (prefix) PCSIM_PETSC(TSSetOptionsPrefix(ts, prefix));
    PCSIM_PETSC(TSSetType(ts, type));
    PCSIM_PETSC(VecCreateSeq(PETSC_COMM_SELF, model.n, &U));
    PCSIM_PETSC(VecDuplicate(U, &V));
    PCSIM_PETSC(VecDuplicate(U, &R));
    from_eigen(u0, U);
    from_eigen(v0, V);
    PCSIM_PETSC(MatCreateSeqDense(PETSC_COMM_SELF, model.n, model.n, nullptr, &J));
    PCSIM_PETSC(TSSetI2Function(ts, R, i2function, &model_));
    PCSIM_PETSC(TSSetI2Jacobian(ts, J, J, i2jacobian, &model_));
    PCSIM_PETSC(TS2SetSolution(ts, U, V));
    PCSIM_PETSC(TSSetTimeStep(ts, dt));
    PCSIM_PETSC(TSSetMaxTime(ts, 1e30));
    PCSIM_PETSC(TSSetExactFinalTime(ts, TS_EXACTFINALTIME_STEPOVER));
    PCSIM_PETSC(TSMonitorSet(ts, record, this, nullptr));
    direct_solver(false);
  }
  ~TsRun() {
    TSDestroy(&ts);
    VecDestroy(&U);
    VecDestroy(&V);
    VecDestroy(&R);
    MatDestroy(&J);
  }
  // LU per Newton iteration; linear problems: a single linear solve per step.
  void direct_solver(bool linear, double rtol = 1e-12, PetscInt max_it = 50) {
    SNES snes;
    KSP ksp;
    PC pc;
    SNESLineSearch ls;
    PCSIM_PETSC(TSGetSNES(ts, &snes));
    PCSIM_PETSC(SNESSetType(snes, linear ? SNESKSPONLY : SNESNEWTONLS));
    PCSIM_PETSC(SNESGetLineSearch(snes, &ls));
    PCSIM_PETSC(SNESLineSearchSetType(ls, SNESLINESEARCHBASIC));
    PCSIM_PETSC(SNESSetTolerances(snes, 1e-11, rtol, 1e-14, max_it, 100000));
    PCSIM_PETSC(SNESGetKSP(snes, &ksp));
    PCSIM_PETSC(KSPSetType(ksp, KSPPREONLY));
    PCSIM_PETSC(KSPGetPC(ksp, &pc));
    PCSIM_PETSC(PCSetType(pc, PCLU));
  }
  SNES snes() {
    SNES s;
    PCSIM_PETSC(TSGetSNES(ts, &s));
    return s;
  }
  void solve_steps(PetscInt steps) {
    PCSIM_PETSC(TSSetMaxSteps(ts, steps));
    PCSIM_PETSC(TSSolve(ts, U));
  }
  void solve_until(double t_end) {
    PCSIM_PETSC(TSSetMaxSteps(ts, 100000000));
    PCSIM_PETSC(TSSetMaxTime(ts, t_end));
    PCSIM_PETSC(TSSetExactFinalTime(ts, TS_EXACTFINALTIME_MATCHSTEP));
    PCSIM_PETSC(TSSolve(ts, U));
  }

  TS ts = nullptr;
  Vec U = nullptr, V = nullptr, R = nullptr;
  Mat J = nullptr;
  std::vector<double> t;
  std::vector<VectorXd> u, v;

 private:
  static PetscErrorCode record(TS ts, PetscInt, PetscReal time, Vec, void* ctx) {
    TsRun* self = static_cast<TsRun*>(ctx);
    Vec X, Xdot;
    PetscFunctionBeginUser;
    PetscCall(TS2GetSolution(ts, &X, &Xdot));
    self->t.push_back(time);
    self->u.push_back(to_eigen(X));
    self->v.push_back(to_eigen(Xdot));
    PetscFunctionReturn(0);
  }
  Model model_;
};

// 3-DOF spring chain (wall-m1-m2-m3), Rayleigh damping C = a0 M + a1 K, forcing affine in t.
struct Chain {
  MatrixXd M = MatrixXd::Zero(3, 3), K = MatrixXd::Zero(3, 3), C;
  VectorXd f0 = VectorXd::Zero(3), f1 = VectorXd::Zero(3);
  Chain() {
    M.diagonal() << 2.0, 1.0, 1.5;
    const double k1 = 400, k2 = 300, k3 = 200;
    K << k1 + k2, -k2, 0, -k2, k2 + k3, -k3, 0, -k3, k3;
    C = 0.5 * M + 1e-3 * K;
    f0 << 0, 0, 10;
    f1 << 5, 0, 50;
  }
  Model model() const {
    Model m;
    m.n = 3;
    Chain c = *this;
    m.F = [c](double t, const VectorXd& u, const VectorXd& v, const VectorXd& a) -> VectorXd {
      return c.M * a + c.C * v + c.K * u - (c.f0 + t * c.f1);
    };
    m.J = [c](double, const VectorXd&, const VectorXd&, const VectorXd&, double sv,
              double sa) -> MatrixXd { return c.K + sv * c.C + sa * c.M; };
    return m;
  }
};

// Damped pendulum, optionally with configuration-dependent mass:
// (1 + mu sin²u) a + c v + k sin u = 0.
inline Model nonlinear_pendulum(double c, double k, double mu = 0.0) {
  Model m;
  m.n = 1;
  m.F = [c, k, mu](double, const VectorXd& u, const VectorXd& v, const VectorXd& a) -> VectorXd {
    const double s = std::sin(u(0));
    return VectorXd::Constant(1, (1 + mu * s * s) * a(0) + c * v(0) + k * s);
  };
  m.J = [c, k, mu](double, const VectorXd& u, const VectorXd&, const VectorXd& a, double sv,
                   double sa) -> MatrixXd {
    const double s = std::sin(u(0)), co = std::cos(u(0));
    return MatrixXd::Constant(1, 1,
                              2 * mu * s * co * a(0) + k * co + sv * c + sa * (1 + mu * s * s));
  };
  return m;
}

// Duffing oscillator a + c v + k u + k3 u³ = 0.
inline Model duffing(double c, double k, double k3) {
  Model m;
  m.n = 1;
  m.F = [c, k, k3](double, const VectorXd& u, const VectorXd& v, const VectorXd& a) -> VectorXd {
    return VectorXd::Constant(1, a(0) + c * v(0) + k * u(0) + k3 * std::pow(u(0), 3));
  };
  m.J = [c, k, k3](double, const VectorXd& u, const VectorXd&, const VectorXd&, double sv,
                   double sa) -> MatrixXd {
    return MatrixXd::Constant(1, 1, k + 3 * k3 * u(0) * u(0) + sv * c + sa);
  };
  return m;
}

// The largest difference between two trajectories of the same steps.
inline double max_gap(const std::vector<VectorXd>& a, const std::vector<VectorXd>& b) {
  double gap = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    gap = std::max(gap, (a[i] - b[i]).cwiseAbs().maxCoeff());
  return gap;
}

inline double max_abs(const std::vector<VectorXd>& xs) {
  double m = 0;
  for (const auto& x : xs) m = std::max(m, x.cwiseAbs().maxCoeff());
  return m;
}

}  // namespace hht_models
