#include "pcsim/solvers/pantograph_time.hpp"

#include <petscts.h>

#include <cfloat>
#include <cmath>

#include "pcsim/core/error.hpp"
#include "pcsim/solvers/hht.hpp"

namespace pcsim::solvers {

namespace {

using pantograph::ForceHistory;
using pantograph::PantographModel;
using pantograph::PowerSplit;
using pantograph::TimeHistory;
using pantograph::TimeOptions;

// The single place that selects the implicit integrator, by the options database
// (-pantograph_ts_type): the project's HHT-α TS type (pcsim::solvers, "hht", the
// default) or PETSc's generalised-α configured as the same HHT ("alpha2": alpha_m = 1,
// alpha_f = 1−α, γ = ½+α, β = (1+α)²/4; its -pantograph_ts_alpha_* options still
// apply). No other TS type integrates the second-order form.
void configure_hht(TS ts, double alpha) {
  const std::string chosen = pantograph_ts_type();
  if (chosen == kTSHHT) {
    register_hht_ts();
    PCSIM_PETSC(TSSetType(ts, kTSHHT));
    hht_set_alpha(ts, alpha);
  } else if (chosen == TSALPHA2) {
    PCSIM_PETSC(TSSetType(ts, TSALPHA2));
    PCSIM_PETSC(
        TSAlpha2SetParams(ts, 1.0, 1.0 - alpha, 0.5 + alpha, 0.25 * (1 + alpha) * (1 + alpha)));
  }
}

struct Context {
  const PantographModel* model = nullptr;
  const ForceHistory* force = nullptr;
  int n = 0;
  int c = 0;
  // scratch
  Eigen::VectorXd q, qd, qdd, R;
  Eigen::MatrixXd Kq, Cq, Mq;
  TimeHistory* hist = nullptr;
  int record_every = 1;
  bool implicit = false;
  // trapezoidal work (implicit scheme)
  double last_t = 0, last_pd = 0, last_pe = 0, wd = 0, we = 0;
};

void to_eigen(Vec v, Eigen::VectorXd* out, int offset, int n) {
  const PetscScalar* a;
  PCSIM_PETSC(VecGetArrayRead(v, &a));
  for (int i = 0; i < n; ++i) (*out)[i] = a[offset + i];
  PCSIM_PETSC(VecRestoreArrayRead(v, &a));
}

void powers(Context* ctx, double t, double* pd, double* pe) {
  const PowerSplit P = ctx->model->power(t, ctx->q, ctx->qd);
  *pd = P.dissipative;
  *pe = P.external + P.base - (*ctx->force)(t)*ctx->qd[ctx->c];
}

void record(Context* ctx, double t, double wd, double we) {
  TimeHistory& h = *ctx->hist;
  h.t.push_back(t);
  h.q.push_back(ctx->q);
  h.qd.push_back(ctx->qd);
  h.contact_force.push_back((*ctx->force)(t));
  h.kinetic.push_back(ctx->model->kinetic_energy(ctx->q, ctx->qd));
  h.potential.push_back(ctx->model->potential_energy(ctx->q));
  h.work_dissipative.push_back(wd);
  h.work_external.push_back(we);
}

// ---- explicit: first-order form ----
PetscErrorCode rhs_function(TS, PetscReal t, Vec Y, Vec Ydot, void* p) {
  PCSIM_CALLBACK_BEGIN
  auto* ctx = static_cast<Context*>(p);
  const int n = ctx->n;
  to_eigen(Y, &ctx->q, 0, n);
  to_eigen(Y, &ctx->qd, n, n);
  ctx->qdd.setZero();
  ctx->model->residual(t, ctx->q, ctx->qd, ctx->qdd, ctx->R);
  ctx->R[ctx->c] += (*ctx->force)(t);
  ctx->model->tangents(t, ctx->q, ctx->qd, ctx->qdd, ctx->Kq, ctx->Cq, ctx->Mq);
  const Eigen::VectorXd acc = ctx->Mq.partialPivLu().solve(-ctx->R);
  double pd, pe;
  powers(ctx, t, &pd, &pe);
  PetscScalar* d;
  PCSIM_PETSC(VecGetArray(Ydot, &d));
  for (int i = 0; i < n; ++i) {
    d[i] = ctx->qd[i];
    d[n + i] = acc[i];
  }
  d[2 * n] = pd;
  d[2 * n + 1] = pe;
  PCSIM_PETSC(VecRestoreArray(Ydot, &d));
  PCSIM_CALLBACK_END
}

PetscErrorCode monitor_explicit(TS, PetscInt step, PetscReal t, Vec Y, void* p) {
  PCSIM_CALLBACK_BEGIN
  auto* ctx = static_cast<Context*>(p);
  ctx->hist->steps = step;
  if (step % ctx->record_every != 0) return 0;
  const int n = ctx->n;
  to_eigen(Y, &ctx->q, 0, n);
  to_eigen(Y, &ctx->qd, n, n);
  const PetscScalar* a;
  PCSIM_PETSC(VecGetArrayRead(Y, &a));
  const double wd = a[2 * n], we = a[2 * n + 1];
  PCSIM_PETSC(VecRestoreArrayRead(Y, &a));
  record(ctx, t, wd, we);
  PCSIM_CALLBACK_END
}

// ---- implicit: second-order form ----
PetscErrorCode i2_function(TS, PetscReal t, Vec U, Vec V, Vec A, Vec F, void* p) {
  PCSIM_CALLBACK_BEGIN
  auto* ctx = static_cast<Context*>(p);
  const int n = ctx->n;
  to_eigen(U, &ctx->q, 0, n);
  to_eigen(V, &ctx->qd, 0, n);
  to_eigen(A, &ctx->qdd, 0, n);
  ctx->model->residual(t, ctx->q, ctx->qd, ctx->qdd, ctx->R);
  ctx->R[ctx->c] += (*ctx->force)(t);
  PetscScalar* f;
  PCSIM_PETSC(VecGetArray(F, &f));
  for (int i = 0; i < n; ++i) f[i] = ctx->R[i];
  PCSIM_PETSC(VecRestoreArray(F, &f));
  PCSIM_CALLBACK_END
}

PetscErrorCode i2_jacobian(TS, PetscReal t, Vec U, Vec V, Vec A, PetscReal shiftV, PetscReal shiftA,
                           Mat J, Mat P, void* p) {
  PCSIM_CALLBACK_BEGIN
  auto* ctx = static_cast<Context*>(p);
  const int n = ctx->n;
  to_eigen(U, &ctx->q, 0, n);
  to_eigen(V, &ctx->qd, 0, n);
  to_eigen(A, &ctx->qdd, 0, n);
  ctx->model->tangents(t, ctx->q, ctx->qd, ctx->qdd, ctx->Kq, ctx->Cq, ctx->Mq);
  // P is dense, column-major with leading dimension n, as Eigen's default matrices.
  PetscScalar* p_values;
  PCSIM_PETSC(MatDenseGetArrayWrite(P, &p_values));
  Eigen::Map<Eigen::MatrixXd>(p_values, n, n) = ctx->Kq + shiftV * ctx->Cq + shiftA * ctx->Mq;
  PCSIM_PETSC(MatDenseRestoreArrayWrite(P, &p_values));
  PCSIM_PETSC(MatAssemblyBegin(P, MAT_FINAL_ASSEMBLY));
  PCSIM_PETSC(MatAssemblyEnd(P, MAT_FINAL_ASSEMBLY));
  if (J != P) {
    PCSIM_PETSC(MatAssemblyBegin(J, MAT_FINAL_ASSEMBLY));
    PCSIM_PETSC(MatAssemblyEnd(J, MAT_FINAL_ASSEMBLY));
  }
  PCSIM_CALLBACK_END
}

PetscErrorCode monitor_implicit(TS ts, PetscInt step, PetscReal t, Vec, void* p) {
  PCSIM_CALLBACK_BEGIN
  auto* ctx = static_cast<Context*>(p);
  ctx->hist->steps = step;
  Vec U, V;
  PCSIM_PETSC(TS2GetSolution(ts, &U, &V));
  to_eigen(U, &ctx->q, 0, ctx->n);
  to_eigen(V, &ctx->qd, 0, ctx->n);
  double pd, pe;
  powers(ctx, t, &pd, &pe);
  if (step > 0) {  // trapezoidal rule for the work of non-conservative forces
    ctx->wd += 0.5 * (t - ctx->last_t) * (pd + ctx->last_pd);
    ctx->we += 0.5 * (t - ctx->last_t) * (pe + ctx->last_pe);
  }
  ctx->last_t = t, ctx->last_pd = pd, ctx->last_pe = pe;
  if (step % ctx->record_every == 0) record(ctx, t, ctx->wd, ctx->we);
  PCSIM_CALLBACK_END
}

// RK4 on the first-order form; U = {q, q̇, W_diss, W_ext}.
void set_up_rk4(TS ts, Context* ctx, const Eigen::VectorXd& q0, const Eigen::VectorXd& qd0,
                Vec* U) {
  const int n = ctx->n;
  PCSIM_PETSC(VecCreateSeq(PETSC_COMM_SELF, 2 * n + 2, U));
  PetscScalar* y;
  PCSIM_PETSC(VecGetArray(*U, &y));
  for (int i = 0; i < n; ++i) y[i] = q0[i], y[n + i] = qd0[i];
  y[2 * n] = y[2 * n + 1] = 0;
  PCSIM_PETSC(VecRestoreArray(*U, &y));
  PCSIM_PETSC(TSSetType(ts, TSRK));
  PCSIM_PETSC(TSRKSetType(ts, TSRK4));
  PCSIM_PETSC(TSSetRHSFunction(ts, nullptr, rhs_function, ctx));
  PCSIM_PETSC(TSMonitorSet(ts, monitor_explicit, ctx, nullptr));
  PCSIM_PETSC(TSSetSolution(ts, *U));
}

// Rounding floor of R near q0: 10 eps max|dR/dq| max|q|, at least 1e-12 (the rigid
// models reach 1e-12; the flexible model's beam forces, EA/l0 up to 5e10 N/m times
// coordinates of ~2 m, round to ~1e-4 N, which Newton cannot go below).
double residual_floor(const PantographModel& model, const Eigen::VectorXd& q0,
                      const Eigen::VectorXd& qd0) {
  const int n = model.dof_count();
  Eigen::MatrixXd K(n, n), C(n, n), M(n, n);
  model.tangents(0.0, q0, qd0, Eigen::VectorXd::Zero(n), K, C, M);
  const double floor =
      10 * DBL_EPSILON * K.cwiseAbs().maxCoeff() * std::max(1.0, q0.cwiseAbs().maxCoeff());
  return std::max(1e-12, floor);
}

// HHT on the second-order form, Newton with dense LU.
void set_up_hht(TS ts, Context* ctx, const Eigen::VectorXd& q0, const Eigen::VectorXd& qd0,
                double alpha, Vec* U, Vec* V, Vec* F, Mat* J) {
  const int n = ctx->n;
  PCSIM_PETSC(VecCreateSeq(PETSC_COMM_SELF, n, U));
  PCSIM_PETSC(VecDuplicate(*U, V));
  PCSIM_PETSC(VecDuplicate(*U, F));
  PetscScalar *u, *v;
  PCSIM_PETSC(VecGetArray(*U, &u));
  PCSIM_PETSC(VecGetArray(*V, &v));
  for (int i = 0; i < n; ++i) u[i] = q0[i], v[i] = qd0[i];
  PCSIM_PETSC(VecRestoreArray(*U, &u));
  PCSIM_PETSC(VecRestoreArray(*V, &v));
  PCSIM_PETSC(MatCreateSeqDense(PETSC_COMM_SELF, n, n, nullptr, J));
  configure_hht(ts, alpha);
  PCSIM_PETSC(TSSetI2Function(ts, *F, i2_function, ctx));
  PCSIM_PETSC(TSSetI2Jacobian(ts, *J, *J, i2_jacobian, ctx));
  PCSIM_PETSC(TS2SetSolution(ts, *U, *V));
  PCSIM_PETSC(TSMonitorSet(ts, monitor_implicit, ctx, nullptr));
  SNES snes;
  KSP ksp;
  PC pc;
  PCSIM_PETSC(TSGetSNES(ts, &snes));
  PCSIM_PETSC(SNESSetTolerances(snes, residual_floor(*ctx->model, q0, qd0), 1e-10, 1e-14, 30,
                                PETSC_DEFAULT));
  PCSIM_PETSC(SNESGetKSP(snes, &ksp));
  PCSIM_PETSC(KSPSetType(ksp, KSPPREONLY));
  PCSIM_PETSC(KSPGetPC(ksp, &pc));
  PCSIM_PETSC(PCSetType(pc, PCLU));
}

}  // namespace

std::string pantograph_ts_type() {
  char type[64] = "";
  PetscBool set = PETSC_FALSE;
  PCSIM_PETSC(PetscOptionsGetString(nullptr, "pantograph_", "-ts_type", type, sizeof type, &set));
  const std::string chosen = set ? type : kTSHHT;
  if (chosen != kTSHHT && chosen != TSALPHA2)
    throw InputError("command line", "-pantograph_ts_type",
                     "'" + chosen + "' cannot integrate the pantograph's second-order form; use " +
                         kTSHHT + " (the default) or " + TSALPHA2);
  return chosen;
}

TimeHistory integrate_pantograph(const PantographModel& model, const Eigen::VectorXd& q0,
                                 const Eigen::VectorXd& qd0, const ForceHistory& contact_force,
                                 const TimeOptions& opt) {
  const int n = model.dof_count();
  TimeHistory hist;
  Context ctx;
  ctx.model = &model;
  ctx.force = &contact_force;
  ctx.n = n;
  ctx.c = model.contact_dof();
  ctx.q = ctx.qd = ctx.qdd = ctx.R = Eigen::VectorXd::Zero(n);
  ctx.Kq = ctx.Cq = ctx.Mq = Eigen::MatrixXd::Zero(n, n);
  ctx.hist = &hist;
  ctx.record_every = std::max(1, opt.record_every);
  ctx.implicit = opt.scheme == "hht";
  if (opt.scheme != "rk4" && opt.scheme != "hht")
    throw SolverError("pantograph time integration: unknown scheme '" + opt.scheme + "'");

  TS ts;
  PCSIM_PETSC(TSCreate(PETSC_COMM_SELF, &ts));
  PCSIM_PETSC(TSSetOptionsPrefix(ts, "pantograph_"));
  Vec U = nullptr, V = nullptr, F = nullptr;
  Mat J = nullptr;
  if (!ctx.implicit)
    set_up_rk4(ts, &ctx, q0, qd0, &U);
  else
    set_up_hht(ts, &ctx, q0, qd0, opt.hht_alpha, &U, &V, &F, &J);
  PCSIM_PETSC(TSSetTime(ts, 0.0));
  PCSIM_PETSC(TSSetTimeStep(ts, opt.dt));
  PCSIM_PETSC(TSSetMaxTime(ts, opt.t_end));
  PCSIM_PETSC(TSSetMaxSteps(ts, static_cast<PetscInt>(std::ceil(opt.t_end / opt.dt)) + 10));
  PCSIM_PETSC(TSSetExactFinalTime(ts, TS_EXACTFINALTIME_MATCHSTEP));
  PCSIM_PETSC(TSSetFromOptions(ts));
  if (!ctx.implicit) {  // -pantograph_ts_type is the hht scheme's: rk4 stays RK4
    PCSIM_PETSC(TSSetType(ts, TSRK));
    PCSIM_PETSC(TSRKSetType(ts, TSRK4));
  }
  PCSIM_PETSC(TSSolve(ts, U));
  TSConvergedReason reason;
  PCSIM_PETSC(TSGetConvergedReason(ts, &reason));
  PCSIM_PETSC(VecDestroy(&U));
  PCSIM_PETSC(VecDestroy(&V));
  PCSIM_PETSC(VecDestroy(&F));
  PCSIM_PETSC(MatDestroy(&J));
  PCSIM_PETSC(TSDestroy(&ts));
  if (reason < 0)
    throw SolverError("pantograph time integration diverged (TS reason " +
                      std::to_string(static_cast<int>(reason)) + ")");
  return hist;
}

}  // namespace pcsim::solvers
