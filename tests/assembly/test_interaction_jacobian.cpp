// Coupled Jacobian of the coupled system against central finite differences of
// its residual, for the lumped EN 50318 pantograph and the DSA-380 (friction and
// one-way damper on), with the catenary linearised and fully nonlinear, dropper
// slack on, the pantograph pressing the wire (thesis 3.3.3: every tangent term).
// pcsim-test-ranks: 1 2
#include <gtest/gtest.h>

#include <cmath>

#include "interaction_fixtures.hpp"

namespace {

using pcsim::testing::make_problem;
using pcsim::testing::pantograph_model;
using pcsim::testing::Problem;
using pcsim::testing::scene_from_text;

struct Case {
  const char* name;
  bool dsa380;
  bool nonlinear;
};

// Time of the checks: the contact point is 4 cm from where the static start
// put it (13.1 m + 41.7 m/s * 1 ms), in the same element.
constexpr double kTime = 1e-3;
// Relative error <= 1e-6 (project standard). The central difference has a
// truncation error ~ h^2 (the state is 10 um to 2 mm away from every kink) and
// a round-off ~ 1e-16 |F| / h (|F| ~ 1e4 N): with h = 1e-6 both are < 1e-8.
constexpr double kTol = 1e-6;
constexpr double kStep = 1e-6;

std::string scene_text(const Case& c) {
  std::string text = "name: fd\ncatenary: {design: three-span.yaml}\npantographs:\n  - name: p\n";
  if (c.dsa380) {
    text +=
        "    model: " + pantograph_model("dsa380_rigid.yaml") + "\n" +
        "    effects: {friction: {force: 10, kt: 0.02}, damper: {enabled: true, one_way: true}}\n";
  } else {
    text += "    model: " + pantograph_model("en50318_two_mass.yaml") + "\n";
  }
  // 13.1 m: inside an element (nodes at 12.0 and 13.5), between droppers.
  text +=
      "    start_x: 13.1\n    static_force: 120\n    start: static\n"
      "simulation: {speed_kmh: 150, end_x: 80}\n"
      "analysis: {from_span: 2, to_span: 2}\n"
      "effects: {catenary_nonlinear: ";
  text += c.nonlinear ? "true" : "false";
  text += ", dropper_slack: true, rayleigh_damping: true}\n";
  return text;
}

double norm(Vec x) {
  PetscReal n;
  PCSIM_PETSC(VecNorm(x, NORM_2, &n));
  return n;
}

class CoupledJacobian : public ::testing::TestWithParam<Case> {
 protected:
  void SetUp() override {
    auto run = scene_from_text(scene_text(GetParam()));
    problem_ = make_problem(run);
    U_ = problem_->create_vector();
    V_ = problem_->create_vector();
    A_ = problem_->create_vector();
    problem_->initial_state(U_, V_);
    // Press the head 2 mm further up (static penetration F0/kH = 2.4 mm), so the
    // contact is well inside the compressive branch.
    const auto& p = problem_->pantographs()[0];
    const PetscInt head = problem_->pantograph_first_dof(0) + p.model->contact_dof();
    int rank;
    MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
    if (rank == 0) PCSIM_PETSC(VecSetValue(U_, head, 0.002, ADD_VALUES));
    PCSIM_PETSC(VecAssemblyBegin(U_));
    PCSIM_PETSC(VecAssemblyEnd(U_));
    // A generic state: small random displacements, velocities, accelerations.
    PCSIM_PETSC(PetscRandomCreate(PETSC_COMM_WORLD, &rng_));
    PCSIM_PETSC(PetscRandomSetInterval(rng_, -1.0, 1.0));
    PCSIM_PETSC(PetscRandomSetSeed(rng_, 1234));
    PCSIM_PETSC(PetscRandomSeed(rng_));
    Vec r = problem_->create_vector();
    PCSIM_PETSC(VecSetRandom(r, rng_));
    PCSIM_PETSC(VecAXPY(U_, 1e-5, r));  // 10 um: no dropper or contact changes branch
    PCSIM_PETSC(VecSetRandom(V_, rng_));
    PCSIM_PETSC(VecScale(V_, 0.01));  // 1 cm/s (friction kt = 2 cm/s: smooth)
    PCSIM_PETSC(VecSetRandom(A_, rng_));
    PCSIM_PETSC(VecScale(A_, 0.5));
    // Pantograph velocities away from the kinks of the one-way damper (frame
    // velocity 0) and of the friction (relative velocity 0): DSA-380 theta' < 0
    // (frame descending: damper on), y10' - y5' ~ 0.1 m/s = 5 kt.
    const std::vector<double> qd = GetParam().dsa380 ? std::vector<double>{-0.05, 0.01, 0.02, 0.03}
                                                     : std::vector<double>{0.01, -0.02};
    if (rank == 0)
      for (std::size_t i = 0; i < qd.size(); ++i)
        PCSIM_PETSC(VecSetValue(V_, problem_->pantograph_first_dof(0) + i, qd[i], INSERT_VALUES));
    PCSIM_PETSC(VecAssemblyBegin(V_));
    PCSIM_PETSC(VecAssemblyEnd(V_));
    PCSIM_PETSC(VecDestroy(&r));
    J_ = problem_->create_matrix();
  }
  void TearDown() override {
    VecDestroy(&U_);
    VecDestroy(&V_);
    VecDestroy(&A_);
    MatDestroy(&J_);
    PetscRandomDestroy(&rng_);
  }

  // || J(sv, sa) d - FD || / || J d ||, FD the central difference of the
  // residual along (d, wu d, wv d, wa d) with step h.
  double relative_error(double sv, double sa, double wu, double wv, double wa, Vec d, double h,
                        Vec Jd_out = nullptr) {
    const double t = kTime;
    problem_->jacobian(t, U_, V_, A_, sv, sa, J_);
    Vec Jd = problem_->create_vector(), fd = problem_->create_vector(),
        Fm = problem_->create_vector();
    PCSIM_PETSC(MatMult(J_, d, Jd));
    Vec Up, Vp, Ap;
    PCSIM_PETSC(VecDuplicate(U_, &Up));
    PCSIM_PETSC(VecDuplicate(V_, &Vp));
    PCSIM_PETSC(VecDuplicate(A_, &Ap));
    for (int side = 0; side < 2; ++side) {
      const double s = side == 0 ? h : -h;
      PCSIM_PETSC(VecWAXPY(Up, s * wu, d, U_));
      PCSIM_PETSC(VecWAXPY(Vp, s * wv, d, V_));
      PCSIM_PETSC(VecWAXPY(Ap, s * wa, d, A_));
      problem_->residual(t, Up, Vp, Ap, side == 0 ? fd : Fm);
    }
    PCSIM_PETSC(VecAXPY(fd, -1.0, Fm));
    PCSIM_PETSC(VecScale(fd, 0.5 / h));
    const double jd_norm = norm(Jd);
    PCSIM_PETSC(VecAXPY(fd, -1.0, Jd));
    const double err = norm(fd) / jd_norm;
    if (Jd_out) PCSIM_PETSC(VecCopy(Jd, Jd_out));
    for (Vec* v : {&Jd, &fd, &Fm, &Up, &Vp, &Ap}) VecDestroy(v);
    return err;
  }

  std::unique_ptr<Problem> problem_;
  Vec U_ = nullptr, V_ = nullptr, A_ = nullptr;
  Mat J_ = nullptr;
  PetscRandom rng_ = nullptr;
};

TEST_P(CoupledJacobian, EachPartAndTheCombinationMatchFiniteDifferences) {
  Vec d = problem_->create_vector();
  PCSIM_PETSC(VecSetRandom(d, rng_));
  // dF/dU alone (shifts 0), dF/dV (J(1, 0) - J(0, 0) = dF/dV: checked through
  // the combination with only V moving), dF/dA, then a realistic HHT step.
  Vec J0d = problem_->create_vector(), J1d = problem_->create_vector();
  const double e_u = relative_error(0, 0, 1, 0, 0, d, kStep, J0d);
  // V only: FD of F along V equals (J(sv=1) - J(0)) d.
  problem_->jacobian(kTime, U_, V_, A_, 1.0, 0.0, J_);
  PCSIM_PETSC(MatMult(J_, d, J1d));
  PCSIM_PETSC(VecAXPY(J1d, -1.0, J0d));  // dF/dV d
  Vec fd = problem_->create_vector(), Fm = problem_->create_vector(), Vp;
  PCSIM_PETSC(VecDuplicate(V_, &Vp));
  auto fd_along = [&](int which, Vec out) {  // which: 1 = V, 2 = A
    for (int side = 0; side < 2; ++side) {
      const double s = side == 0 ? kStep : -kStep;
      PCSIM_PETSC(VecWAXPY(Vp, s, d, which == 1 ? V_ : A_));
      if (which == 1)
        problem_->residual(kTime, U_, Vp, A_, side == 0 ? out : Fm);
      else
        problem_->residual(kTime, U_, V_, Vp, side == 0 ? out : Fm);
    }
    PCSIM_PETSC(VecAXPY(out, -1.0, Fm));
    PCSIM_PETSC(VecScale(out, 0.5 / kStep));
  };
  fd_along(1, fd);
  PCSIM_PETSC(VecAXPY(fd, -1.0, J1d));
  const double e_v = norm(fd) / norm(J1d);
  problem_->jacobian(kTime, U_, V_, A_, 0.0, 1.0, J_);
  PCSIM_PETSC(MatMult(J_, d, J1d));
  PCSIM_PETSC(VecAXPY(J1d, -1.0, J0d));  // dF/dA d = M d
  fd_along(2, fd);
  PCSIM_PETSC(VecAXPY(fd, -1.0, J1d));
  const double e_a = norm(fd) / norm(J1d);
  // HHT-like shifts (dt = 1 ms, alpha = 0.1): gamma/(beta dt), 1/(beta dt^2 (1-alpha)).
  const double sv = 0.6 / (0.3025e-3), sa = 1.0 / (0.3025e-6 * 0.9);
  // Step 1e-7: V then moves by sv h = 2e-4 m/s, 1 % of the friction's kt;
  // smaller steps lose digits in U + h d (|U| ~ 10 m: 2e-16 * 10 / h).
  const double e_step = relative_error(sv, sa, 1, sv, sa, d, 1e-7);
  // Direction on the pantograph DOFs only: the head column of the contact
  // tangent and the pantograph block, not hidden by the stiff cables.
  PCSIM_PETSC(VecSet(d, 0.0));
  const auto& p = problem_->pantographs()[0];
  const PetscInt first = problem_->pantograph_first_dof(0);
  for (int i = 0; i < p.model->dof_count(); ++i)
    PCSIM_PETSC(VecSetValue(d, first + i, 1.0 + 0.1 * i, INSERT_VALUES));
  PCSIM_PETSC(VecAssemblyBegin(d));
  PCSIM_PETSC(VecAssemblyEnd(d));
  const double e_panto = relative_error(0.7, 1.3, 1, 0.7, 1.3, d, kStep);
  PetscPrintf(PETSC_COMM_WORLD,
              "  %s: rel. error dF/dU %.2e, dF/dV %.2e, dF/dA %.2e, HHT step %.2e, "
              "pantograph direction %.2e\n",
              GetParam().name, e_u, e_v, e_a, e_step, e_panto);
  EXPECT_LT(e_u, kTol);
  EXPECT_LT(e_v, kTol);
  EXPECT_LT(e_a, kTol);
  EXPECT_LT(e_step, kTol);
  EXPECT_LT(e_panto, kTol);
  for (Vec* v : {&d, &J0d, &J1d, &fd, &Fm, &Vp}) VecDestroy(v);
}

// The contact actually acts in these states (else the test would not check it).
TEST_P(CoupledJacobian, PantographPressesTheWire) {
  const auto rec = problem_->record(kTime, U_);
  int rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (rank == 0) {
    // Static 120 N plus kH * 2 mm = 100 N, within the random perturbation.
    EXPECT_GT(rec.contact_force[0], 150.0);
    EXPECT_LT(rec.contact_force[0], 300.0);
  }
}

INSTANTIATE_TEST_SUITE_P(Interaction, CoupledJacobian,
                         ::testing::Values(Case{"lumped_linearised", false, false},
                                           Case{"lumped_nonlinear", false, true},
                                           Case{"dsa380_linearised", true, false},
                                           Case{"dsa380_nonlinear", true, true}),
                         [](const ::testing::TestParamInfo<Case>& info) {
                           return std::string(info.param.name);
                         });

}  // namespace
