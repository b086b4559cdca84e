// The static start is an equilibrium of the dynamic model (thesis 3.3.1), also with
// several pantographs all starting static or a ramp start among them: the residual
// F(0, U0, 0, 0) vanishes, every pantograph that starts static presses with its F0
// and a ramp start touches the wire with no force, and with (nearly) standing
// pantographs the HHT integration leaves the state where it is.
// pcsim-test-ranks: 1 2
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "interaction_fixtures.hpp"
#include "pcsim/scene/composition.hpp"

namespace {

using pcsim::testing::contact_data;
using pcsim::testing::integrate;
using pcsim::testing::make_problem;

class StaticStart : public ::testing::TestWithParam<const char*> {};

TEST_P(StaticStart, IsAnEquilibriumOfTheDynamicModel) {
  auto run = pcsim::scene::load_run_scene(
      pcsim::scene::load_composed(contact_data(std::string(GetParam()) + ".yaml")));
  const double vanishing_speed = 1e-6;  // [m/s]: 50 ms move the contact point by 50 nm
  std::vector<double> static_force;     // the contact force at the start: F0, or 0 (ramp)
  for (auto& p : run.pantographs) {
    p.speed = vanishing_speed;
    static_force.push_back(p.static_start ? p.static_force : 0.0);
  }
  const std::size_t count = run.pantographs.size();
  const bool modal = run.catenary.fidelity == pcsim::catenary::CatenaryFidelity::modal;
  auto problem = make_problem(run);
  Vec U0 = problem->create_vector(), V0 = problem->create_vector(), F = problem->create_vector(),
      zero = problem->create_vector();
  PCSIM_PETSC(VecSet(zero, 0.0));
  const auto info = problem->initial_state(U0, V0);
  // The coupled Newton from its guess converges in a few iterations (measured 0 to
  // 2; 15, through residuals of 2e5 N, while a ramp-start DSA-380's rows were in it).
  EXPECT_LE(info.coupled_iterations, 3);

  // 1. F(0, U0, 0, 0) below 1e-3 N (the coupled start's SNES tolerance; the
  // wire tensions are ~2e4 N, so this is 5e-8 relative).
  problem->residual(0.0, U0, zero, zero, F);
  PetscReal start_residual;
  PCSIM_PETSC(VecNorm(F, NORM_2, &start_residual));
  EXPECT_LT(start_residual, 1e-3);
  PetscReal v0_norm;
  PCSIM_PETSC(VecNorm(V0, NORM_INFINITY, &v0_norm));
  EXPECT_EQ(v0_norm, 0.0);
  int rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  const auto start_record = problem->record(0.0, U0);  // collective; filled on rank 0
  std::vector<double> f_start(count, 0.0);
  // Every pantograph presses with the scene's static force F0, up to its frame's static
  // response to the difference between the catenary of the dynamic model and that of
  // the start's first guess (the FE catenary under the point loads F0): the lumped
  // frame spring k2 = 50 N/m (measured 7.2e-3 N on the linearised catenary), the
  // DSA-380's fixed bellows torque 2555 N/m on the nonlinear one (where the guess is
  // the same model), none with its uplift characteristic (the static force is F0 at any
  // height). A ramp start touches the wire where the others' forces hold it, with
  // no force: within 1e-5 N (measured 9.9e-7 N; set on the wire as it was before
  // the coupled Newton, it would press by that Newton's move there, 2.8e-4 m x
  // 5e4 N/m = 14 N).
  for (std::size_t p = 0; p < count && rank == 0; ++p) {
    f_start[p] = start_record.contact_force[p];
    // A modal catenary's start is the closed form under the forces superposed:
    // F0 to round-off (measured below 1e-10 N).
    const double tolerance = modal ? 1e-8 : static_force[p] == 0.0 ? 1e-5 : 0.05;
    EXPECT_NEAR(f_start[p], static_force[p], tolerance) << p;
  }

  // 2. 50 HHT steps (dt = 1 ms, default alpha) from (U0, 0, 0).
  //  a) SNES tolerances of solvers::DynamicSolver (|R| <= 1e-3 N), as in `pcsim run`: U
  //     stays within 1e-9 m (and 1e-9 in slopes) of U0, the contact force within
  //     1e-6 relative of its start value. (The step residual at U0 is below the
  //     tolerance, so Newton leaves U0 as it is: this checks that it is.)
  //  b) Newton forced to act (|R| <= 1e-5 N; the round-off floor of the step
  //     residual is ~1e-6 N): the start's remaining residual (<= 1e-3 N, the
  //     start SNES tolerance) now moves the system by |K^-1 F(0, U0, 0, 0)|:
  //     U within 1e-8 m (measured 1.0e-9 m, lumped), force within 1e-6
  //     (measured 6.5e-8).
  for (const bool forced_newton : {false, true}) {
    double max_du = 0, max_df = 0, max_df_ramp = 0;
    Vec dU = problem->create_vector();
    auto configure = [&](TS ts) {
      if (!forced_newton) return;
      SNES snes;
      PCSIM_PETSC(TSGetSNES(ts, &snes));
      PCSIM_PETSC(SNESSetTolerances(snes, 1e-5, 1e-14, 0.0, 25, 100000));
    };
    const PetscInt steps =
        integrate(*problem, U0, V0, 1e-3, 1.0, 50, configure, [&](double t, Vec U, Vec) {
          PCSIM_PETSC(VecWAXPY(dU, -1.0, U0, U));
          PetscReal du;
          PCSIM_PETSC(VecNorm(dU, NORM_INFINITY, &du));
          max_du = std::max(max_du, static_cast<double>(du));
          const auto rec = problem->record(t, U);
          for (std::size_t p = 0; p < count && rank == 0; ++p)
            if (static_force[p] != 0.0)
              max_df = std::max(max_df, std::abs(rec.contact_force[p] / f_start[p] - 1));
            else
              max_df_ramp = std::max(max_df_ramp, std::abs(rec.contact_force[p]));
        });
    EXPECT_EQ(steps, 50);
    PetscPrintf(PETSC_COMM_WORLD,
                "  %s: ||F(0,U0,0,0)|| = %.2e N, 50 steps (%s): max |U - U0| = %.2e, "
                "max |Fc/Fc0 - 1| = %.2e, a ramp start's max |Fc| = %.2e N\n",
                GetParam(), static_cast<double>(start_residual),
                forced_newton ? "|R| <= 1e-5 N" : "default SNES", max_du, max_df, max_df_ramp);
    EXPECT_LT(max_du, forced_newton ? 1e-8 : 1e-9);
    if (rank == 0) EXPECT_LT(max_df, 1e-6);
    // A ramp start's force stays at its start's (1e-5 N, as above).
    if (rank == 0) EXPECT_LT(max_df_ramp, 1e-5);
    VecDestroy(&dU);
  }
  for (Vec* v : {&U0, &V0, &F, &zero}) VecDestroy(v);
}

// Lumped pantograph on the linearised catenary (cheap path), DSA-380 with
// damper on the nonlinear catenary (full Newton path), and three pantographs all
// starting static (two lumped and a DSA-380 following its uplift characteristic),
// on the nonlinear and on the modal catenary, and the DSA-380 of these three with a
// ramp start (its rows made the coupled Newton singular before it was held).
INSTANTIATE_TEST_SUITE_P(Interaction, StaticStart,
                         ::testing::Values("three-span-lumped", "three-span-dsa380",
                                           "three-span-three-pantographs",
                                           "three-span-three-pantographs-modal",
                                           "three-span-ramp-beside-static"),
                         [](const ::testing::TestParamInfo<const char*>& info) {
                           std::string name = info.param;
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

// The flexible DSA-380 on the modal catenary: the closed-form start is in
// equilibrium to the pantograph's rounding floor (~2e-3 N from its stiff bars),
// below which Newton cannot go, so the coupled Newton (a dense modal matrix)
// does not run, the catenary's rows are within the start's own 1e-5 N, and
// the contact force is F0.
TEST(StaticStartFlexible, ModalStartIsInEquilibriumWithoutNewton) {
  auto run = pcsim::scene::load_run_scene(
      pcsim::scene::InputNode::load_file(contact_data("three-span-flexible-modal.yaml")));
  auto problem = make_problem(run);
  Vec U0 = problem->create_vector(), V0 = problem->create_vector(), F = problem->create_vector(),
      zero = problem->create_vector();
  PCSIM_PETSC(VecSet(zero, 0.0));
  const auto info = problem->initial_state(U0, V0);
  EXPECT_EQ(info.coupled_iterations, 0);
  problem->residual(0.0, U0, zero, zero, F);
  PetscReal start_residual;
  PCSIM_PETSC(VecNorm(F, NORM_2, &start_residual));
  const double floor = problem->pantographs()[0].model->static_residual_floor();
  PetscPrintf(PETSC_COMM_WORLD, "  ||F(0,U0,0,0)|| = %.2e N, floor %.2e N\n",
              static_cast<double>(start_residual), floor);
  EXPECT_GT(floor, 1e-5);  // above the start's own tolerance: the floor decides
  EXPECT_LT(start_residual, floor);
  // The catenary's rows are within the start's own tolerance: the rest is
  // the pantograph's.
  const PetscInt first = problem->pantograph_first_dof(0);
  const PetscInt count = problem->pantographs()[0].dof_count();
  PetscInt lo, hi;
  PCSIM_PETSC(VecGetOwnershipRange(F, &lo, &hi));
  PetscScalar* f;
  PCSIM_PETSC(VecGetArray(F, &f));
  for (PetscInt i = std::max(lo, first); i < std::min(hi, first + count); ++i) f[i - lo] = 0;
  PCSIM_PETSC(VecRestoreArray(F, &f));
  PetscReal catenary_residual;
  PCSIM_PETSC(VecNorm(F, NORM_2, &catenary_residual));
  EXPECT_LT(catenary_residual, 1e-5);
  int rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  const auto record = problem->record(0.0, U0);
  if (rank == 0) EXPECT_NEAR(record.contact_force[0], 120.0, 1e-8);
  for (Vec* v : {&U0, &V0, &F, &zero}) VecDestroy(v);
}

// A gap start next to static starts (linearised catenary, whose coupled start runs a
// Newton): the static ones press with F0 on the wire their equilibrium leaves, and
// the gap start keeps its gap below that wire, with no contact force, at rest.
TEST(StaticStartBeside, GapStartKeepsItsGapBelowTheSolvedWire) {
  const std::string file = contact_data("three-span-gap-beside-static.yaml");
  const double gap = 0.02;  // [m]
  const auto scene = pcsim::scene::load_composed_text(
      "base: three-span-three-pantographs.yaml\n"
      "set: {pantographs.2.start: {gap: 0.02}, effects.catenary_nonlinear: false}\n",
      file);
  auto run = pcsim::scene::load_run_scene(scene);
  auto problem = make_problem(run);
  Vec U0 = problem->create_vector(), V0 = problem->create_vector();
  const auto info = problem->initial_state(U0, V0);
  EXPECT_GT(info.coupled_iterations, 0);  // the Newton ran with the gap start held
  EXPECT_LE(info.coupled_iterations, 3);
  int rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  const auto record = problem->record(0.0, U0);  // collective; filled on rank 0
  if (rank == 0) {
    // The static ones: F0 within their frames' response to the guess (0.05 N, as above).
    EXPECT_NEAR(record.contact_force[0], 120.0, 0.05);
    EXPECT_NEAR(record.contact_force[1], 120.0, 0.05);
    EXPECT_EQ(record.contact_force[2], 0.0);
    // The gap on the solved wire: to round-off of heights of ~5 m (measured 4e-16 m
    // off); placed on the wire before the Newton, it would be off by the Newton's
    // move there (measured 3.2e-4 m).
    EXPECT_NEAR(record.wire_z[2] - record.head_z[2], gap, 1e-12);
    std::printf("  gap start: gap %.3e m off, forces %.6f %.6f N\n",
                record.wire_z[2] - record.head_z[2] - gap, record.contact_force[0],
                record.contact_force[1]);
  }
  for (Vec* v : {&U0, &V0}) VecDestroy(v);
}

}  // namespace
