// The accuracy study's table (output/accuracy_study.hpp): errors against the
// reference, the reduction error of modal runs, the finest FE run, the
// Pareto front and the written table. Made-up runs with known answers.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "pcsim/output/accuracy_study.hpp"

namespace {

using pcsim::output::StudyRun;
using pcsim::output::StudyTable;

StudyRun make_run(const std::string& model, double dt, double h, double mean, double sigma,
                  double ms_per_step, double cutoff = 0) {
  StudyRun r;
  r.model = model;
  r.dt = dt;
  r.element_length = h;
  r.cutoff_hz = cutoff;
  r.ok = true;
  // Fm+3σ and the other figures follow mean and σ; uplift fixed at 60 mm.
  r.figures.push_back({"pantograph", mean, sigma, mean + 3 * sigma, mean - 3 * sigma,
                       mean + 2.5 * sigma, mean - 2 * sigma});
  r.uplift_m = 0.06;
  r.ms_per_step = ms_per_step;
  r.steps = 100;
  return r;
}

// A ladder: nonlinear and linear at the fine and the base mesh, modal at the
// base mesh (two cut-offs), and a failed run.
StudyTable ladder() {
  StudyTable t;
  t.scene = "test";
  t.runs.push_back(make_run("linear", 1e-3, 0.5, 120.0, 40.0, 1.0));       // 0
  t.runs.push_back(make_run("nonlinear", 1e-3, 0.5, 120.0, 40.0, 5.0));    // 1: reference (tie)
  t.runs.push_back(make_run("linear", 1e-3, 1.0, 120.0, 41.0, 0.5));       // 2
  t.runs.push_back(make_run("modal", 1e-3, 1.0, 120.6, 41.0, 0.1, 70.0));  // 3
  t.runs.push_back(make_run("modal", 1e-3, 1.0, 121.2, 50.0, 0.2, 40.0));  // 4: dominated by 3
  StudyRun failed = make_run("linear", 5e-4, 0.25, 0, 0, 0);
  failed.ok = false;
  failed.failure = "time integration failed";
  t.runs.push_back(failed);  // 5: finer, but failed: not the reference
  pcsim::output::evaluate_study(t);
  return t;
}

}  // namespace

TEST(AccuracyStudy, RelativeErrorsOfEveryFigure) {
  const auto a = make_run("linear", 1e-3, 1, 126.0, 36.0, 1);
  const auto b = make_run("linear", 1e-3, 1, 120.0, 40.0, 1);
  const auto e = pcsim::output::study_errors(a, b);
  ASSERT_TRUE(e.valid);
  EXPECT_NEAR(e.mean, 5.0, 1e-12);                                  // 126 / 120 - 1
  EXPECT_NEAR(e.std_dev, -10.0, 1e-12);                             // 36 / 40 - 1
  EXPECT_NEAR(e.stat_max, 100.0 * (234.0 - 240.0) / 240.0, 1e-12);  // Fm+3σ
  EXPECT_NEAR(e.uplift, 0.0, 1e-12);
  EXPECT_NEAR(e.worst, 10.0, 1e-12);  // the largest magnitude over the targeted figures
  StudyRun failed = a;
  failed.ok = false;
  EXPECT_FALSE(pcsim::output::study_errors(failed, b).valid);
}

TEST(AccuracyStudy, WorstOverPantographsKeepsTheSign) {
  auto a = make_run("linear", 1e-3, 1, 120.0, 40.0, 1);
  auto b = a;
  a.figures.push_back(a.figures[0]);
  b.figures.push_back(b.figures[0]);
  a.figures[0].mean = 121.2;  // +1 %
  a.figures[1].mean = 117.6;  // -2 %: the worse one
  const auto e = pcsim::output::study_errors(a, b);
  EXPECT_NEAR(e.mean, -2.0, 1e-12);
}

TEST(AccuracyStudy, ReferenceIsTheFinestSuccessfulFERun) {
  const auto t = ladder();
  EXPECT_EQ(t.reference, 1);  // dt x h tie between 0 and 1: nonlinear first; 5 failed
  EXPECT_EQ(pcsim::output::finest_fe_run({make_run("modal", 1e-4, 0.1, 1, 1, 1)}), -1);
}

TEST(AccuracyStudy, ReductionErrorAgainstLinearAtTheSameStepAndMesh) {
  const auto t = ladder();
  ASSERT_TRUE(t.reduction_errors[3].valid);
  EXPECT_NEAR(t.reduction_errors[3].mean, 0.5, 1e-12);  // 120.6 against run 2's 120
  EXPECT_NEAR(t.reduction_errors[3].std_dev, 0.0, 1e-12);
  EXPECT_FALSE(t.reduction_errors[2].valid);     // FE runs have none
  EXPECT_NEAR(t.errors[3].std_dev, 2.5, 1e-12);  // 41 against the reference's 40
}

TEST(AccuracyStudy, ParetoFrontOfErrorAgainstCost) {
  const auto t = ladder();
  // Run 0: 0 % error at 1 ms; run 2: 2.5 % at 0.5 ms; run 3: 2.5 % at 0.1 ms
  // dominates run 2 (as wrong, cheaper) and run 4 (25 %, costlier).
  EXPECT_TRUE(t.pareto[0]);
  EXPECT_FALSE(t.pareto[1]);  // the reference is not on the front
  EXPECT_FALSE(t.pareto[2]);
  EXPECT_TRUE(t.pareto[3]);
  EXPECT_FALSE(t.pareto[4]);
  EXPECT_FALSE(t.pareto[5]);  // failed
}

TEST(AccuracyStudy, WritesTableCsvAndPlot) {
  const auto t = ladder();
  const std::string md = pcsim::output::accuracy_markdown(t);
  EXPECT_NE(md.find("| nonlinear | 1 | 0.5 | – | reference"), std::string::npos) << md;
  EXPECT_NE(md.find("| **modal** | 1 | 1 | 70 (0) | +0.50 %"), std::string::npos) << md;
  EXPECT_NE(md.find("failed: time integration failed"), std::string::npos) << md;
  char dir[] = "/tmp/pcsim-accuracy-XXXXXX";
  ASSERT_NE(mkdtemp(dir), nullptr);
  const std::string csv = std::string(dir) + "/accuracy.csv", svg = std::string(dir) + "/a.svg";
  pcsim::output::write_accuracy_csv(csv, t);
  pcsim::output::write_accuracy_svg(svg, t);
  std::ifstream in(csv);
  std::string line;
  int lines = 0;
  while (std::getline(in, line)) ++lines;
  EXPECT_EQ(lines, 1 + 6);  // header + one row per run (one pantograph)
  std::stringstream plot;
  plot << std::ifstream(svg).rdbuf();
  std::size_t circles = 0;
  for (auto p = plot.str().find("<circle"); p != std::string::npos;
       p = plot.str().find("<circle", p + 1))
    ++circles;
  EXPECT_EQ(circles, 4u + 3u);  // runs 0, 2, 3, 4 (not the reference, not failed) + legend
  std::remove(csv.c_str());
  std::remove(svg.c_str());
  rmdir(dir);
}
