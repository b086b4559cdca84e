// HHT-α TS type "hht": the alpha-term taken from the previous step's last
// residual (-ts_hht_reuse_alpha_term) against the evaluated one.

#include <gtest/gtest.h>
#include <petscts.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include "hht_test_models.hpp"
#include "pcsim/core/error.hpp"
#include "pcsim/solvers/hht.hpp"

using namespace hht_models;

namespace {

// --- The alpha-term from the previous step's last residual (-ts_hht_reuse_alpha_term).

// The chain with a cubic spring on its first mass (Newton iterates) and a load
// that is not affine in t: F affine in A with the constant M.
Model stiffening_chain() {
  const Chain chain;
  Model m = chain.model();
  const auto linear_F = m.F;
  const auto linear_J = m.J;
  m.F = [linear_F](double t, const VectorXd& u, const VectorXd& v, const VectorXd& a) {
    VectorXd r = linear_F(t, u, v, a);
    r(0) += 4e5 * std::pow(u(0), 3);
    r(2) -= 20 * std::sin(30 * t);
    return r;
  };
  m.J = [linear_J](double t, const VectorXd& u, const VectorXd& v, const VectorXd& a, double sv,
                   double sa) {
    MatrixXd j = linear_J(t, u, v, a, sv, sa);
    j(0, 0) += 1.2e6 * u(0) * u(0);
    return j;
  };
  return m;
}

struct InertiaOf {
  MatrixXd M;
  static PetscErrorCode product(TS, PetscReal, Vec, Vec, Vec A, Vec MA, void* ctx) {
    PCSIM_CALLBACK_BEGIN
    from_eigen(static_cast<InertiaOf*>(ctx)->M * to_eigen(A), MA);
    PCSIM_CALLBACK_END
  }
};

// The pendulum's configuration-dependent mass 1 + mu sin²u at the state given
// (or, 'frozen', at the first state it sees: a wrong M for the test).
struct PendulumInertia {
  double mu = 0;
  bool frozen = false;
  double frozen_u = std::nan("");
  static PetscErrorCode product(TS, PetscReal, Vec U, Vec, Vec A, Vec MA, void* ctx) {
    PCSIM_CALLBACK_BEGIN
    auto* self = static_cast<PendulumInertia*>(ctx);
    double u = to_eigen(U)(0);
    if (self->frozen) {
      if (std::isnan(self->frozen_u)) self->frozen_u = u;
      u = self->frozen_u;
    }
    const double s = std::sin(u);
    from_eigen((1 + self->mu * s * s) * to_eigen(A), MA);
    PCSIM_CALLBACK_END
  }
};

}  // namespace

// Taken from the last residual, the alpha-term gives the trajectory of the
// evaluated one to round-off (measured 2e-15 of the motion over 200 Newton
// steps; 1e-12 allowed), and it is used: a wrong inertia (2 M) moves the
// trajectory by more than 1e-4 of the motion.
TEST(HHT, AlphaTermFromLastResidualEqualsEvaluated) {
  const Model model = stiffening_chain();
  VectorXd u0(3), v0(3);
  u0 << 0.01, -0.02, 0.03;
  v0 << 0.1, 0.0, -0.2;
  InertiaOf right{Chain().M}, wrong{2 * Chain().M};
  auto run_with = [&](InertiaOf* inertia) {
    auto run = std::make_unique<TsRun>(model, pcsim::solvers::kTSHHT, u0, v0, 0.01);
    if (inertia) pcsim::solvers::hht_set_inertia_product(run->ts, InertiaOf::product, inertia);
    run->solve_steps(200);
    return run;
  };
  const auto evaluated = run_with(nullptr), reused = run_with(&right), broken = run_with(&wrong);
  const auto info = pcsim::solvers::hht_get_info(reused->ts);
  EXPECT_EQ(info.alpha_terms_reused, 199);
  EXPECT_EQ(info.alpha_terms_evaluated, 1);
  EXPECT_EQ(pcsim::solvers::hht_get_info(evaluated->ts).alpha_terms_reused, 0);
  const double scale = max_abs(evaluated->u);
  const double same = max_gap(reused->u, evaluated->u), off = max_gap(broken->u, evaluated->u);
  EXPECT_LT(same / scale, 1e-12);
  EXPECT_GT(off / scale, 1e-4);
  EXPECT_GT(scale, 0.01);
}

// A configuration-dependent mass (F affine in A, dF/dA = M(U): the DSA-380's
// kind): the alpha-term taken from the last residual with M at the step's
// state gives the evaluated trajectory to round-off (measured: the same bits
// over 400 steps of this one-unknown model; 1e-12 of the swing allowed, the
// bound of the constant-mass test above), and M frozen at the start does not
// (measured 7.4e-2 of the swing; more than 1e-4 asserted).
TEST(HHT, AlphaTermFromLastResidualWithVaryingMass) {
  const double mu = 0.8;
  const Model model = nonlinear_pendulum(0.3, 40.0, mu);
  const VectorXd u0 = VectorXd::Constant(1, 1.2), v0 = VectorXd::Zero(1);
  PendulumInertia right{mu}, frozen{mu, true};
  auto run_with = [&](PendulumInertia* inertia) {
    auto run = std::make_unique<TsRun>(model, pcsim::solvers::kTSHHT, u0, v0, 0.005);
    if (inertia)
      pcsim::solvers::hht_set_inertia_product(run->ts, PendulumInertia::product, inertia);
    run->solve_steps(400);
    return run;
  };
  const auto evaluated = run_with(nullptr), reused = run_with(&right), broken = run_with(&frozen);
  EXPECT_EQ(pcsim::solvers::hht_get_info(reused->ts).alpha_terms_reused, 399);
  const double scale = max_abs(evaluated->u);
  const double same = max_gap(reused->u, evaluated->u), off = max_gap(broken->u, evaluated->u);
  std::printf("varying mass: reused alpha-term within %.1e of the swing, frozen M %.1e\n",
              same / scale, off / scale);
  EXPECT_LT(same / scale, 1e-12);
  EXPECT_GT(off / scale, 1e-4);
  EXPECT_GT(scale, 1.0);
}

// A solution changed between steps, an invalidation or a new time make the
// next step evaluate its alpha-term; a saved one is given back (checkpoints).
TEST(HHT, AlphaTermEvaluatedAfterOutsideChange) {
  InertiaOf inertia{Chain().M};
  TsRun run(stiffening_chain(), pcsim::solvers::kTSHHT, VectorXd::Constant(3, 0.01),
            VectorXd::Zero(3), 0.01);
  pcsim::solvers::hht_set_inertia_product(run.ts, InertiaOf::product, &inertia);
  run.solve_steps(10);
  auto evaluated = [&] { return pcsim::solvers::hht_get_info(run.ts).alpha_terms_evaluated; };
  EXPECT_EQ(evaluated(), 1);
  Vec F0;
  PCSIM_PETSC(VecDuplicate(run.U, &F0));
  EXPECT_TRUE(pcsim::solvers::hht_get_alpha_term(run.ts, F0));
  from_eigen(to_eigen(run.U), run.U);  // the same values written: a change all the same
  EXPECT_FALSE(pcsim::solvers::hht_get_alpha_term(run.ts, F0));
  run.solve_steps(20);
  EXPECT_EQ(evaluated(), 2);
  pcsim::solvers::hht_invalidate_alpha_term(run.ts);
  run.solve_steps(30);
  EXPECT_EQ(evaluated(), 3);
  EXPECT_TRUE(pcsim::solvers::hht_get_alpha_term(run.ts, F0));
  pcsim::solvers::hht_set_alpha_term(run.ts, F0);  // given back: used
  run.solve_steps(40);
  EXPECT_EQ(evaluated(), 3);
  PCSIM_PETSC(VecDestroy(&F0));
}
