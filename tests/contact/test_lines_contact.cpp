// Contact with two wires at an overlap (meshes/lines/three-sections-short.yaml,
// both wires in service at 150 m): one penalty term per wire, their tangents
// against finite differences, and the cheap path's J0 + low-rank changes
// equal to the exact Jacobian. The run over the overlaps is
// test_lines_handover.cpp.
// pcsim-test-ranks: 1 2
#include <gtest/gtest.h>

#include <cmath>

#include "../assembly/interaction_fixtures.hpp"
#include "pcsim/assembly/interaction_terms.hpp"

namespace {

using pcsim::testing::make_problem;
using pcsim::testing::pantograph_model;
using pcsim::testing::Problem;
using pcsim::testing::scene_from_text;
namespace assembly = pcsim::assembly;

int rank() {
  int r = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &r);
  return r;
}

double norm(Vec x) {
  PetscReal n;
  PCSIM_PETSC(VecNorm(x, NORM_2, &n));
  return n;
}

// The short three-section line; the pantograph starts in static contact at
// start_x, running at 250 km/h to end_x.
std::string scene_text(double start_x, double end_x) {
  return "name: overlap\ncatenary: {design: " PCSIM_SOURCE_DIR
         "/meshes/lines/three-sections-short.yaml}\n"
         "pantographs:\n  - name: p\n    model: " +
         pantograph_model("en50318_two_mass.yaml") + "\n    start_x: " + std::to_string(start_x) +
         "\n    static_force: 120\n    start: static\n"
         "simulation: {speed_kmh: 250, end_x: " +
         std::to_string(end_x) + "}\nanalysis: {from_span: 4, to_span: 4}\n";
}

class TwoWires : public ::testing::Test {
 protected:
  void SetUp() override {
    auto run = scene_from_text(scene_text(150.0, 400.0));
    problem_ = make_problem(run);
    U_ = problem_->create_vector();
    V_ = problem_->create_vector();
    A_ = problem_->create_vector();
    problem_->initial_state(U_, V_);
    PCSIM_PETSC(PetscRandomCreate(PETSC_COMM_WORLD, &rng_));
    PCSIM_PETSC(PetscRandomSetInterval(rng_, -1.0, 1.0));
    Vec r = problem_->create_vector();
    PCSIM_PETSC(VecSetRandom(r, rng_));
    PCSIM_PETSC(VecAXPY(U_, 1e-5, r));  // 10 um: no dropper or contact changes branch
    PCSIM_PETSC(VecSetRandom(V_, rng_));
    PCSIM_PETSC(VecScale(V_, 0.01));
    PCSIM_PETSC(VecDestroy(&r));
  }
  void TearDown() override {
    for (Vec* v : {&U_, &V_, &A_}) VecDestroy(v);
    PetscRandomDestroy(&rng_);
  }
  std::unique_ptr<Problem> problem_;
  Vec U_ = nullptr, V_ = nullptr, A_ = nullptr;
  PetscRandom rng_ = nullptr;
};

TEST_F(TwoWires, BothWiresPressedAndTangentMatchesFiniteDifferences) {
  const auto rec = problem_->record(0.0, U_);
  if (rank() == 0) {
    ASSERT_EQ(rec.wire_force[0].size(), 3u);
    // Static start at the support where both wires are in service: both
    // carry part of the 120 N (measured 62 and 58 N).
    EXPECT_GT(rec.wire_force[0][0], 20.0);
    EXPECT_GT(rec.wire_force[0][1], 20.0);
    EXPECT_EQ(rec.wire_force[0][2], 0.0);
    EXPECT_NEAR(rec.contact_force[0], rec.wire_force[0][0] + rec.wire_force[0][1], 1e-12);
  }
  // dF/dU + sv dF/dV + sa dF/dA against central differences (HHT-like shifts).
  const double t = 0.0, sv = 0.6 / 0.3025e-3, sa = 1.0 / (0.3025e-6 * 0.9), h = 1e-7;
  Vec d = problem_->create_vector(), Jd = problem_->create_vector(), Fp = problem_->create_vector(),
      Fm = problem_->create_vector(), Up, Vp, Ap;
  PCSIM_PETSC(VecSetRandom(d, rng_));
  Mat J = problem_->create_matrix();
  problem_->jacobian(t, U_, V_, A_, sv, sa, J);
  PCSIM_PETSC(MatMult(J, d, Jd));
  PCSIM_PETSC(VecDuplicate(U_, &Up));
  PCSIM_PETSC(VecDuplicate(V_, &Vp));
  PCSIM_PETSC(VecDuplicate(A_, &Ap));
  for (int side = 0; side < 2; ++side) {
    const double s = side == 0 ? h : -h;
    PCSIM_PETSC(VecWAXPY(Up, s, d, U_));
    PCSIM_PETSC(VecWAXPY(Vp, s * sv, d, V_));
    PCSIM_PETSC(VecWAXPY(Ap, s * sa, d, A_));
    problem_->residual(t, Up, Vp, Ap, side == 0 ? Fp : Fm);
  }
  PCSIM_PETSC(VecAXPY(Fp, -1.0, Fm));
  PCSIM_PETSC(VecScale(Fp, 0.5 / h));
  const double jd = norm(Jd);
  PCSIM_PETSC(VecAXPY(Fp, -1.0, Jd));
  const double err = norm(Fp) / jd;
  PetscPrintf(PETSC_COMM_WORLD, "  two wires: tangent vs finite differences %.2e\n", err);
  // Project standard 1e-6 (as tests/assembly/test_interaction_jacobian.cpp).
  EXPECT_LT(err, 1e-6);
  for (Vec* v : {&d, &Jd, &Fp, &Fm, &Up, &Vp, &Ap}) VecDestroy(v);
  MatDestroy(&J);
}

TEST_F(TwoWires, CheapPathOperatorIsTheJacobian) {
  // J0 (no contact) + the rank-one terms of both contacts = the exact tangent
  // at the same state (the bars' tangents are in J0 as they are).
  auto& system = problem_->system();
  const assembly::Shifts shifts{0.6 / 0.3025e-3, 1.0 / (0.3025e-6 * 0.9)};
  Mat J = problem_->create_matrix(), J0 = problem_->create_matrix();
  system.jacobian(0.0, U_, V_, A_, shifts, J);
  system.reference_jacobian(0.0, U_, V_, A_, shifts, J0);
  std::vector<assembly::RankOne> terms;
  ASSERT_TRUE(system.low_rank_change(0.0, U_, V_, A_, terms));
  int contact_terms = 0;
  for (const auto& term : terms) contact_terms += term.reuse_columns && term.coefficient > 0;
  EXPECT_EQ(contact_terms, 2);  // both wires in contact
  Vec d = problem_->create_vector(), Jd = problem_->create_vector(),
      J0d = problem_->create_vector();
  PCSIM_PETSC(VecSet(d, 0.0));
  const PetscInt head = system.pantographs()[0].contact_dof();
  if (rank() == 0) {
    PCSIM_PETSC(VecSetValue(d, head, 1.0, INSERT_VALUES));
    for (const auto& term : terms)
      for (std::size_t i = 0; i < term.index.size(); ++i)
        PCSIM_PETSC(VecSetValue(d, term.index[i], 0.5, INSERT_VALUES));
  }
  PCSIM_PETSC(VecAssemblyBegin(d));
  PCSIM_PETSC(VecAssemblyEnd(d));
  PCSIM_PETSC(MatMult(J, d, Jd));
  PCSIM_PETSC(MatMult(J0, d, J0d));
  for (const auto& term : terms) {  // J0 d + sum c u (u . d), u known on every rank
    double ud_local = 0, ud = 0;
    PetscInt lo, hi;
    PCSIM_PETSC(VecGetOwnershipRange(d, &lo, &hi));
    const PetscScalar* a;
    PCSIM_PETSC(VecGetArrayRead(d, &a));
    for (std::size_t i = 0; i < term.index.size(); ++i)
      if (term.index[i] >= lo && term.index[i] < hi)
        ud_local += term.weight[i] * a[term.index[i] - lo];
    PCSIM_PETSC(VecRestoreArrayRead(d, &a));
    MPI_Allreduce(&ud_local, &ud, 1, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
    if (rank() == 0)
      for (std::size_t i = 0; i < term.index.size(); ++i)
        PCSIM_PETSC(
            VecSetValue(J0d, term.index[i], term.coefficient * ud * term.weight[i], ADD_VALUES));
  }
  PCSIM_PETSC(VecAssemblyBegin(J0d));
  PCSIM_PETSC(VecAssemblyEnd(J0d));
  const double jd = norm(Jd);
  PCSIM_PETSC(VecAXPY(J0d, -1.0, Jd));
  const double err = norm(J0d) / jd;
  PetscPrintf(PETSC_COMM_WORLD, "  two wires: cheap-path operator vs exact tangent %.2e\n", err);
  EXPECT_LT(err, 1e-12);  // the same matrices summed in another order
  for (Vec* v : {&d, &Jd, &J0d}) VecDestroy(v);
  MatDestroy(&J);
  MatDestroy(&J0);
}

}  // namespace
