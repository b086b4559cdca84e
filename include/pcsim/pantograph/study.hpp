// Studies of the pantograph alone (thesis chapter 2): what a `pcsim pantograph` scene asks
// for and what each study gives back. Plain data: the scene reader
// (scene/pantograph_scene.hpp) fills a StudyScene, the driver
// (solvers/pantograph_study.hpp) runs it, the writer
// (output/pantograph_results.hpp) stores the StudyResult.
#pragma once

#include <complex>
#include <memory>
#include <string>
#include <variant>
#include <vector>

#include "pcsim/pantograph/calibration.hpp"
#include "pcsim/pantograph/linear.hpp"
#include "pcsim/pantograph/model.hpp"
#include "pcsim/pantograph/time_history.hpp"

namespace pcsim::pantograph {

// Time responses under a prescribed contact force, one per scheme; with `linear` also
// the response of the model linearised at the equilibrium (Fig. 2.18).
struct TimeStudy {
  std::vector<std::string> schemes = {"rk4"};
  TimeOptions options;  // options.scheme is set per run
  ForceHistory force;
  bool linear = false;
};

// Undamped and damped modes at the equilibrium (2.21–2.28); with f_max_hz > 0 only the
// modes up to that frequency are kept (the thesis lists 0–30 Hz; the flexible model has
// one mode per beam unknown, up to ~1e5 Hz).
struct ModesStudy {
  double f_max_hz = 0;
};

// Receptance of the contact coordinate H_cc(ω): direct (2.36) and modal (2.40).
struct FrfStudy {
  std::vector<double> frequencies_hz;
};

// Nonlinear "FRF" (2.3.3): peak-to-peak of the contact coordinate in steady state under
// F0 + A sin(2πft), divided by 2A; the measurement starts at max(settle_s, settle_periods
// periods) and lasts measure_periods periods.
struct SweepStudy {
  std::vector<double> frequencies_hz, amplitudes;
  double dt = 1e-3, settle_s = 10, settle_periods = 20, measure_periods = 5;
  std::string scheme = "rk4";  // "rk4" | "hht" (stiff models: the flexible bars)
  double hht_alpha = 0.05;
  bool linear = false;                       // also the linearised model
  bool start_on_linear_steady_state = true;  // else start at rest in the equilibrium
};

// Calibration of the DSA-380 parameters to Table 2.2 from a start set.
struct CalibrationStudy {
  Dsa380Parameters start;
};

using Study = std::variant<TimeStudy, ModesStudy, FrfStudy, SweepStudy, CalibrationStudy>;

struct StudyScene {
  std::unique_ptr<PantographModel> model;
  double speed = 0;             // m/s (aerodynamic force only)
  double contact_force = 120;   // F0 of the static equilibrium [N]
  double working_height = 1.2;  // h0 of the static equilibrium [m]
  std::string study_type;       // time | modes | frf | sweep | calibrate
  Study study;
};

struct TimeRun {
  std::string scheme;
  TimeHistory history;
  bool has_linear = false;
  TimeHistory linear;  // the linearised model's response (has_linear)
};
struct TimeStudyResult {
  std::vector<TimeRun> runs;
};

struct ModesStudyResult {
  LinearModel linear;
  std::vector<Mode> undamped, damped;  // SLEPc
  double slepc_vs_eigen_max_relative_difference = 0;
};

struct FrfStudyResult {
  int dof = 0;  // the contact coordinate
  std::vector<double> frequencies_hz;
  std::vector<std::complex<double>> direct;
  bool symmetric = false;                   // M, K symmetric: the modal FRF is given
  std::vector<std::complex<double>> modal;  // (symmetric)
  double direct_vs_modal_max_relative_difference = 0;
  // Base-to-head transmissibility z_c / z_b (models with a base support or a moving frame;
  // else empty).
  std::vector<std::complex<double>> transmissibility;
};

struct SweepCurve {
  std::string group;  // "nonlinear" | "linear"
  double amplitude = 0;
  std::vector<double> response;  // per frequency, m/N; NaN where the run diverged
};
struct SweepStudyResult {
  std::vector<double> frequencies_hz, amplitudes;
  std::vector<SweepCurve> curves;
};

struct StudyResult {
  Eigen::VectorXd q0;  // static equilibrium under (F0, h0)
  std::variant<TimeStudyResult, ModesStudyResult, FrfStudyResult, SweepStudyResult,
               CalibrationResult>
      values;
};

}  // namespace pcsim::pantograph
