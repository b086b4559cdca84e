// The run pipeline (simulation/run.hpp) as a library: runs are re-entrant
// (the same figures however many runs came before in the process), a
// failure is an exception the caller catches and then runs on, and the
// modal catenary built by the pipeline's factory with every mode is the
// linearised FE catenary written in another basis.
// pcsim-test-ranks: 1 2
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "pcsim/scene/composition.hpp"
#include "pcsim/scene/run_scene.hpp"
#include "pcsim/simulation/run.hpp"

namespace {

using namespace pcsim;

std::string scene_file(const std::string& name) {
  return std::string(PCSIM_SOURCE_DIR) + "/tests/contact/data/" + name;
}

simulation::Context test_context() {
  auto ctx = simulation::Context::of(PETSC_COMM_WORLD);
  ctx.quiet = true;
  ctx.cache_dir = "test-run-pipeline-cache";  // in the build folder
  return ctx;
}

// A fresh folder for one run's results (removed first: earlier test runs).
output::OutputDir output_dir(const simulation::Context& ctx, const std::string& name) {
  const std::string dir = "test-run-pipeline/" + name;
  if (ctx.rank == 0) {
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories("test-run-pipeline");
  }
  MPI_Barrier(ctx.comm);
  output::OutputRequest request{dir, "test", "-o", "run", "test", name, nlohmann::json::object()};
  return output::OutputDir(ctx.comm, request);
}

// Runs the scene file with the overrides (KEY=VALUE) into its own folder.
simulation::RunOutcome run_scene(const std::string& file, const std::string& name,
                                 const std::vector<std::string>& overrides = {}) {
  const auto ctx = test_context();
  std::vector<scene::InputOverride> parsed;
  for (const auto& o : overrides) parsed.push_back(scene::parse_override(o, {"", "test --set " + o}));
  auto scene = scene::load_run_scene(scene::load_composed(scene_file(file), parsed));
  simulation::RunRequest request;
  request.name = name;
  request.scene_path = scene_file(file);
  request.stop_on_signal = false;
  auto out = output_dir(ctx, name);
  auto outcome = simulation::run(ctx, scene, request, out);
  out.commit();
  return outcome;
}

// The EN 50318 figures of the first pantograph (rank 0; the other ranks get
// no statistics).
std::vector<double> figures(const simulation::RunOutcome& o) {
  if (o.stats.pantographs.empty()) return {};
  const auto& f = o.stats.pantographs.front().force;
  return {f.mean,       f.std_dev,    f.statistical_max,   f.statistical_min,
          f.actual_max, f.actual_min, o.stats.max_uplift_m};
}

TEST(RunPipeline, RunsAreReentrant) {
  // A, then B (another scene: nonlinear catenary, another speed), then A again.
  const auto first = run_scene("three-span-lumped.yaml", "a1");
  const auto other = run_scene("three-span-lumped.yaml", "b",
                               {"simulation.speed_kmh=150", "effects.catenary_nonlinear=true"});
  const auto again = run_scene("three-span-lumped.yaml", "a2");
  ASSERT_TRUE(first.complete && other.complete && again.complete);
  EXPECT_EQ(first.steps, again.steps);
  // One rank: bit for bit, nothing of the first run or of B is left in the
  // process. Two: MUMPS (the static solutions) schedules its work
  // dynamically, so two identical runs differ by its round-off; measured
  // 2.6e-11 relative at most, the README's 1e-10 the bound.
  const auto a = figures(first), b = figures(again);
  if (test_context().size == 1) EXPECT_EQ(a, b);
  for (std::size_t i = 0; i < a.size(); ++i)
    EXPECT_NEAR(b[i], a[i], 1e-10 * std::abs(a[i])) << "figure " << i;
  if (test_context().rank == 0) {
    ASSERT_EQ(figures(first).size(), 7u);
    EXPECT_NE(figures(first)[1], figures(other)[1]);  // B is another run
  }
}

TEST(RunPipeline, FailureIsAnExceptionAndTheProcessRunsOn) {
  // 'all' modes of a structure over 4000 unknowns is refused by the factory
  // (the EN 50318 catenary has 14 364): an InputError naming the key.
  try {
    run_scene("en50318-short.yaml", "refused",
              {"catenary.model=modal", "catenary.max_frequency_hz=all"});
    FAIL() << "the run should have been refused";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("max_frequency_hz"), std::string::npos) << e.what();
  }
  const auto after = run_scene("three-span-lumped.yaml", "after-failure");
  const auto reference = run_scene("three-span-lumped.yaml", "reference");  // collective
  EXPECT_TRUE(after.complete);
  const auto a = figures(after), b = figures(reference);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i)  // as in RunsAreReentrant
    EXPECT_NEAR(b[i], a[i], 1e-10 * std::abs(a[i])) << "figure " << i;
}

TEST(RunPipeline, ModalWithEveryModeMatchesLinearFE) {
  // Every mode of the small catenary (about 900 unknowns): the modal basis
  // spans the whole space and the reduced model is the linearised FE model in
  // modal coordinates, built by the pipeline's factory. Measured differences
  // (1 rank): mean 0.006 N, sigma 0.029 N, Fm+3sigma 0.079 N, Fm-3sigma
  // 0.092 N, max 0.12 N, min 0.061 N, uplift 1.9e-5 m. They start at t = 0:
  // the FE run's coupled static start is solved to the SNES tolerance (its
  // contact force 120.007 N, the modal one's 120 N exactly) and the
  // difference rides on the dynamics. The tolerances are twice those.
  const auto fe = run_scene("three-span-lumped.yaml", "linear-fe", {"catenary.model=linear"});
  const auto modal = run_scene("three-span-lumped.yaml", "modal-all",
                               {"catenary.model=modal", "catenary.max_frequency_hz=all"});
  ASSERT_TRUE(fe.complete && modal.complete);
  EXPECT_EQ(modal.facts["catenary_model"], "modal");
  EXPECT_GT(modal.facts["modal"]["basis_size"].get<int>(), 500);
  const auto a = figures(fe), b = figures(modal);
  ASSERT_EQ(a.size(), b.size());
  const double tolerance[] = {0.012, 0.06, 0.16, 0.19, 0.25, 0.13, 4e-5};  // N ..., m
  for (std::size_t i = 0; i < a.size(); ++i)
    EXPECT_NEAR(b[i], a[i], tolerance[i]) << "figure " << i;
}

}  // namespace
