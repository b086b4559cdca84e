// The cheap path's operator J0 + sum c u u^T (solvers/low_rank.hpp) is the
// true Jacobian of the step, also after droppers have switched between taut
// and slack: its product with a direction equals the central finite
// difference of the coupled residual with the integrator's shifts. The
// preconditioning matrix J0 alone (no contact, switched droppers frozen at
// J0) fails the same check, so the comparison can fail. With a nonlinear
// pantograph (rigid DSA-380) on the linear FE and the modal catenary, the
// operator with the pantograph's varying block (refactored per iteration) is
// the full path's Jacobian, and the preconditioner is its exact inverse.
// pcsim-test-ranks: 1 2
#include <gtest/gtest.h>

#include <cmath>

#include "../assembly/interaction_fixtures.hpp"

namespace {

using pcsim::testing::contact_data;
using pcsim::testing::make_problem;
using pcsim::testing::scene_from_text;

double norm(Vec x) {
  PetscReal n;
  PCSIM_PETSC(VecNorm(x, NORM_2, &n));
  return n;
}

// ||A d - FD(d)|| / ||FD(d)||, FD the central difference of F(t, U + h d,
// V + sv h d, A + sa h d) with step h.
double relative_error(pcsim::testing::Problem& problem, Mat op, double t, Vec U, Vec V, Vec A,
                      double sv, double sa, Vec d) {
  const double h = 1e-7;
  Vec Ad = problem.create_vector(), Fp = problem.create_vector(), Fm = problem.create_vector(), Up,
      Vp, Ap;
  PCSIM_PETSC(MatMult(op, d, Ad));
  PCSIM_PETSC(VecDuplicate(U, &Up));
  PCSIM_PETSC(VecDuplicate(V, &Vp));
  PCSIM_PETSC(VecDuplicate(A, &Ap));
  for (int side = 0; side < 2; ++side) {
    const double s = side == 0 ? h : -h;
    PCSIM_PETSC(VecWAXPY(Up, s, d, U));
    PCSIM_PETSC(VecWAXPY(Vp, s * sv, d, V));
    PCSIM_PETSC(VecWAXPY(Ap, s * sa, d, A));
    problem.residual(t, Up, Vp, Ap, side == 0 ? Fp : Fm);
  }
  PCSIM_PETSC(VecAXPY(Fp, -1.0, Fm));
  PCSIM_PETSC(VecScale(Fp, 0.5 / h));
  const double fd_norm = norm(Fp);
  PCSIM_PETSC(VecAXPY(Fp, -1.0, Ad));
  const double err = norm(Fp) / fd_norm;
  for (Vec* v : {&Ad, &Fp, &Fm, &Up, &Vp, &Ap}) VecDestroy(v);
  return err;
}

TEST(CheapPath, OperatorIsTheJacobianAfterDroppersSwitch) {
  auto run =
      pcsim::scene::load_run_scene(pcsim::scene::InputNode::load_file(contact_data("en50318-short.yaml")));
  auto problem = make_problem(run);
  Vec U0 = problem->create_vector(), V0 = problem->create_vector();
  problem->initial_state(U0, V0);
  pcsim::solvers::DynamicSolver solver(problem->system(), 1e-3, 0.12);
  ASSERT_TRUE(solver.cheap_path());
  TS ts = solver.ts();
  PCSIM_PETSC(TS2SetSolution(ts, U0, V0));
  Vec A = problem->create_vector();
  PCSIM_PETSC(VecSet(A, 0.0));
  pcsim::solvers::hht_set_initial_acceleration(ts, A);
  // Step until a dropper has switched against J0 (rank-one terms beyond the
  // contact's). On this case that happens within the first 120 steps.
  std::vector<pcsim::assembly::RankOne> terms;
  Vec U, V;
  PetscReal t = 0;
  std::size_t bar_terms = 0;
  for (int step = 0; step < 120 && bar_terms == 0; ++step) {
    PCSIM_PETSC(TSStep(ts));
    PCSIM_PETSC(TSGetTime(ts, &t));
    PCSIM_PETSC(TS2GetSolution(ts, &U, &V));
    pcsim::solvers::hht_get_acceleration(ts, A);
    problem->system().low_rank_change(t, U, V, A, terms);
    bar_terms = 0;
    for (const auto& term : terms) bar_terms += term.reuse_columns ? 0 : 1;
  }
  ASSERT_GT(bar_terms, 0u) << "no dropper switched: the check would not test the low-rank terms";
  // The integrator's shifts (HHT, thesis 3.23) and its Jacobian at this state.
  PetscReal alpha, gamma, beta, dt;
  pcsim::solvers::hht_get_params(ts, &alpha, &gamma, &beta);
  PCSIM_PETSC(TSGetTimeStep(ts, &dt));
  const double sv = gamma / (beta * dt), sa = 1.0 / (beta * dt * dt * (1 - alpha));
  Mat J, P;
  PCSIM_PETSC(TSGetI2Jacobian(ts, &J, &P, nullptr, nullptr));
  PCSIM_PETSC(TSComputeI2Jacobian(ts, t, U, V, A, sv, sa, J, P));
  // Direction: the unknowns of the switched droppers' rank-one terms, where
  // the low-rank change lives (a global direction would be dominated by the
  // mass matrix M/(beta dt^2)).
  Vec d = problem->create_vector();
  PCSIM_PETSC(VecSet(d, 0.0));
  int rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  for (const auto& term : terms)
    if (!term.reuse_columns && rank == 0)
      for (std::size_t i = 0; i < term.index.size(); ++i)
        PCSIM_PETSC(VecSetValue(d, term.index[i], term.weight[i], ADD_VALUES));
  PCSIM_PETSC(VecAssemblyBegin(d));
  PCSIM_PETSC(VecAssemblyEnd(d));
  const double e_op = relative_error(*problem, J, t, U, V, A, sv, sa, d);
  const double e_j0 = relative_error(*problem, P, t, U, V, A, sv, sa, d);
  PetscPrintf(PETSC_COMM_WORLD,
              "  t = %.3f s, %zu dropper rank-one terms: operator %.2e, J0 alone %.2e\n", t,
              bar_terms, e_op, e_j0);
  // Project standard 1e-6 (measured 6.1e-9 on 1 and 2 ranks: the frozen
  // geometric stiffness of taut bars and the FD truncation stay far below).
  EXPECT_LT(e_op, 1e-6);
  // J0 alone misses the switched droppers' stiffness change (measured 2.2e-3:
  // k of a dropper against the nodal mass term M/(beta dt^2) along d), more
  // than 100 times the bound above: an operator without its low-rank terms
  // would fail the first check.
  EXPECT_GT(e_j0, 1e-4);
  for (Vec* v : {&U0, &V0, &A, &d}) VecDestroy(v);
}

// The rigid DSA-380 (two-way damper) on the three-span catenary, model
// 'linear' (FE) or 'modal'.
pcsim::scene::RunScene dsa380_scene(const std::string& model) {
  return scene_from_text(
      "name: cheap-dsa380\n"
      "catenary: {design: three-span.yaml, model: " +
      model +
      "}\n"
      "pantographs:\n"
      "  - {name: dsa380, model: ../../../meshes/pantographs/dsa380_rigid.yaml,\n"
      "     start_x: 13.1, static_force: 120, start: static,\n"
      "     effects: {damper: {enabled: true, one_way: false}}}\n"
      "simulation: {speed_kmh: 200, end_x: 80, dt: 0.001}\n"
      "effects: {dropper_slack: true, rayleigh_damping: true}\n"
      "analysis: {from_span: 2, to_span: 2}\n");
}

double relative_difference(Vec a, Vec b) {
  Vec d;
  PCSIM_PETSC(VecDuplicate(a, &d));
  PCSIM_PETSC(VecWAXPY(d, -1.0, b, a));
  const double r = norm(d) / norm(b);
  PCSIM_PETSC(VecDestroy(&d));
  return r;
}

// ||J_b - J0_b||_F / ||J_b||_F over the pantograph's block (collective).
double pantograph_block_change(Mat J, Mat J0, const pcsim::assembly::PantographSlot& slot) {
  double change = 0;
  PetscInt lo, hi;
  PCSIM_PETSC(MatGetOwnershipRange(J, &lo, &hi));
  if (slot.first_dof >= lo && slot.first_dof < hi) {
    const int n = slot.dof_count();
    std::vector<PetscInt> idx(n);
    for (int i = 0; i < n; ++i) idx[i] = slot.first_dof + i;
    std::vector<double> a(n * n), b(n * n);
    PCSIM_PETSC(MatGetValues(J, n, idx.data(), n, idx.data(), a.data()));
    PCSIM_PETSC(MatGetValues(J0, n, idx.data(), n, idx.data(), b.data()));
    double diff = 0, size = 0;
    for (int k = 0; k < n * n; ++k) diff += (a[k] - b[k]) * (a[k] - b[k]), size += a[k] * a[k];
    change = std::sqrt(diff / size);
  }
  MPI_Allreduce(MPI_IN_PLACE, &change, 1, MPI_DOUBLE, MPI_MAX, PETSC_COMM_WORLD);
  return change;
}

class CheapPathDsa380 : public ::testing::TestWithParam<const char*> {};

TEST_P(CheapPathDsa380, OperatorAndInverseWithAVaryingPantographBlock) {
  auto run = dsa380_scene(GetParam());
  auto problem = make_problem(run);
  Vec U0 = problem->create_vector(), V0 = problem->create_vector();
  problem->initial_state(U0, V0);
  pcsim::solvers::DynamicSolver solver(problem->system(), 1e-3, 1.0);
  ASSERT_TRUE(solver.cheap_path());
  TS ts = solver.ts();
  PCSIM_PETSC(TS2SetSolution(ts, U0, V0));
  Vec A = problem->create_vector();
  PCSIM_PETSC(VecSet(A, 0.0));
  pcsim::solvers::hht_set_initial_acceleration(ts, A);
  // 150 steps: the head has left J0's state (built at the first step).
  for (int step = 0; step < 150; ++step) PCSIM_PETSC(TSStep(ts));
  PetscReal t, alpha, gamma, beta, dt;
  Vec U, V;
  PCSIM_PETSC(TSGetTime(ts, &t));
  PCSIM_PETSC(TS2GetSolution(ts, &U, &V));
  pcsim::solvers::hht_get_acceleration(ts, A);
  pcsim::solvers::hht_get_params(ts, &alpha, &gamma, &beta);
  PCSIM_PETSC(TSGetTimeStep(ts, &dt));
  const double sv = gamma / (beta * dt), sa = 1.0 / (beta * dt * dt * (1 - alpha));
  Mat J, P;
  PCSIM_PETSC(TSGetI2Jacobian(ts, &J, &P, nullptr, nullptr));
  const long builds = solver.reference_builds();
  PCSIM_PETSC(TSComputeI2Jacobian(ts, t, U, V, A, sv, sa, J, P));
  ASSERT_EQ(solver.reference_builds(), builds) << "J0 was rebuilt: the block change would be 0";
  // Direction: the pantograph's unknowns and the contact wire's (random-ish).
  const auto& slot = problem->pantographs().front();
  Vec d = problem->create_vector();
  PCSIM_PETSC(VecSet(d, 0.0));
  int rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  std::vector<pcsim::assembly::RankOne> terms;
  problem->system().low_rank_change(t, U, V, A, terms);
  ASSERT_FALSE(terms.empty());
  if (rank == 0) {
    for (int i = 0; i < slot.dof_count(); ++i)
      PCSIM_PETSC(VecSetValue(d, slot.first_dof + i, 1e-3 * (1.0 + 0.3 * i), INSERT_VALUES));
    for (std::size_t i = 0; i + 1 < terms.front().index.size(); ++i)
      PCSIM_PETSC(
          VecSetValue(d, terms.front().index[i], 1e-3 * terms.front().weight[i], INSERT_VALUES));
  }
  PCSIM_PETSC(VecAssemblyBegin(d));
  PCSIM_PETSC(VecAssemblyEnd(d));
  // 1. The operator equals the full path's assembled Jacobian (no FD), whose
  // pantograph block has left J0's.
  Mat Jfull = problem->create_matrix();
  problem->system().jacobian(t, U, V, A, {sv, sa}, Jfull);
  const double block_change = pantograph_block_change(Jfull, P, slot);
  Vec Jd = problem->create_vector(), Fd = problem->create_vector(), x = problem->create_vector();
  PCSIM_PETSC(MatMult(J, d, Jd));
  PCSIM_PETSC(MatMult(Jfull, d, Fd));
  const double e_full = relative_difference(Jd, Fd);
  // 2. Finite differences of the residual.
  const double e_op = relative_error(*problem, J, t, U, V, A, sv, sa, d);
  const double e_j0 = relative_error(*problem, P, t, U, V, A, sv, sa, d);
  // 3. The preconditioner (J0 factored once, the block refactored, Woodbury)
  // inverts the operator.
  SNES snes;
  KSP ksp;
  PCSIM_PETSC(TSGetSNES(ts, &snes));
  PCSIM_PETSC(SNESGetKSP(snes, &ksp));
  PCSIM_PETSC(KSPSolve(ksp, Jd, x));
  const double e_inv = relative_difference(x, d);
  PetscPrintf(PETSC_COMM_WORLD,
              "  %s, t = %.3f s: pantograph block changed by %.2e; operator vs full Jacobian "
              "%.2e, vs FD %.2e (J0 alone %.2e), inverse %.2e\n",
              GetParam(), t, block_change, e_full, e_op, e_j0, e_inv);
  // Measured on 1 and 2 ranks, both catenaries: the block moved by 1.4e-4
  // (asserted > 1e-5, so that the checks below see it); operator = full
  // Jacobian to 1.3e-16 (round-off, while the block moved by 1.4e-4); FD 1.5e-10 to 8.9e-10
  // (project standard 1e-6), J0 alone 1.6e-4 (without contact and block change); inverse 3.2e-16
  // (asserted 1e-12).
  EXPECT_GT(block_change, 1e-5);
  EXPECT_LT(e_full, 1e-12);
  EXPECT_LT(e_op, 1e-6);
  EXPECT_GT(e_j0, 1e-5);
  EXPECT_LT(e_inv, 1e-12);
  PCSIM_PETSC(MatDestroy(&Jfull));
  for (Vec* v : {&U0, &V0, &A, &d, &Jd, &Fd, &x}) VecDestroy(v);
}

INSTANTIATE_TEST_SUITE_P(Catenaries, CheapPathDsa380, ::testing::Values("linear", "modal"));

}  // namespace
