// Results of an accuracy-cost study (`pcsim study accuracy SCENE`): every run
// of the grid (fidelity, time step, element length, modal cut-off) with its
// EN 50318 figures and costs, the error of each figure against a reference
// run, the reduction error of modal runs against the linearised FE run at the
// same time step and mesh, and the Pareto front of error against cost.
// Written as accuracy.csv, accuracy.md and accuracy.svg (the plot).
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace pcsim::output {

// The figures of one pantograph (EN 50318, thesis 3.4).
struct StudyFigures {
  std::string pantograph;
  double mean = 0, std_dev = 0, stat_max = 0, stat_min = 0, max = 0, min = 0;
};

struct StudyRun {
  std::string model;  // nonlinear | linear | modal
  double dt = 0, element_length = 0;
  double cutoff_hz = 0;  // modal: the cut-off; else 0
  bool vertical_only = false;
  int basis_size = 0;
  bool ok = false;
  std::string failure;  // when !ok
  std::vector<StudyFigures> figures;
  double uplift_m = 0;
  long steps = 0;
  double wall_s = 0, ms_per_step = 0, real_time_factor = 0, peak_memory_mb = 0;
  double setup_s = 0;                  // statics, modes (or cache) and start
  double predicted_error_percent = 0;  // the run's accuracy estimate (sigma)
  bool estimate_ok = true;
  std::string label() const;
};

// Relative errors [%] of a run's figures against another run's, worst over
// pantographs; 'worst' over the figures with targets (mean, sigma, Fm+3sigma,
// actual max, uplift).
struct StudyErrors {
  bool valid = false;
  double mean = 0, std_dev = 0, stat_max = 0, stat_min = 0, max = 0, min = 0, uplift = 0;
  double worst = 0;
};
StudyErrors study_errors(const StudyRun& run, const StudyRun& reference);

struct StudyTable {
  std::string scene;
  int ranks = 1;
  double load_before = -1, load_after = -1;  // 1-minute load average of the machine
  std::vector<StudyRun> runs;
  int reference = -1;               // index of the reference run (the finest FE run by default)
  std::vector<StudyErrors> errors;  // against the reference
  std::vector<StudyErrors> reduction_errors;  // modal: against linear FE at the same dt, h
  std::vector<bool> pareto;                   // not dominated in (ms/step, worst error)
};

// The finest FE run: smallest dt x element length, nonlinear before linear.
int finest_fe_run(const std::vector<StudyRun>& runs);
// Errors, reduction errors and the Pareto front of the table's runs.
void evaluate_study(StudyTable& table);

void write_accuracy_csv(const std::string& path, const StudyTable& table);
// The Markdown table (also printed by the command).
std::string accuracy_markdown(const StudyTable& table);
void write_accuracy_svg(const std::string& path, const StudyTable& table);
nlohmann::json study_json(const StudyTable& table);

}  // namespace pcsim::output
