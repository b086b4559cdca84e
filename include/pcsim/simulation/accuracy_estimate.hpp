// Where a run's time step, mesh and modal cut-off sit relative to the
// converged region, from criteria that hold for any scene (docs/fidelity.md,
// "Accuracy estimate"):
//  - time step: steps per period of the highest frequency that matters, the
//    larger of the pantograph's highest mode on the contact spring and the
//    catenary band the filtered force shows, cutoff_hz / (1 - v/c);
//  - mesh: contact-wire elements per wavelength v / cutoff_hz of the filtered
//    force along the track;
//  - modal cut-off: max_frequency_hz over cutoff_hz / (1 - v/c).
// Thresholds and error estimates are calibrated by `pcsim study accuracy` on
// EN 50318 (the tables in accuracy_estimate.cpp). Printed before stepping,
// with a warning naming what to change when a criterion is not met, and
// recorded in summary.json.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "pcsim/assembly/coupled_system.hpp"
#include "pcsim/scene/run_scene.hpp"
#include "pcsim/simulation/catenary_setup.hpp"
#include "pcsim/simulation/context.hpp"
#include "pcsim/solvers/dynamics.hpp"

namespace pcsim::simulation {

struct AccuracyCriterion {
  std::string name;          // "time step", "element length", "modal cut-off"
  std::string measure;       // what 'value' counts
  double value = 0;          // e.g. steps per period
  double converged_min = 0;  // calibrated: errors below the target above it
  double error_percent = 0;  // estimated error of sigma (calibration), %
  bool ok = true;
  std::string advice;  // what to change (when !ok)
};

struct AccuracyEstimate {
  std::vector<AccuracyCriterion> criteria;
  double highest_frequency_hz = 0;  // what the time step must resolve
  bool ok() const;
  nlohmann::json json() const;
};

// The physics inputs of the criteria (any scene).
struct AccuracyInputs {
  double dt = 0, speed = 0, wave_speed = 0, filter_hz = 20;
  double element_length = 0;  // mean contact-wire element length [m]
  double pantograph_hz = 0;   // highest pantograph mode with the head on the contact spring
  bool modal = false;
  double modal_cutoff_hz = 0;  // <= 0: every mode
};
AccuracyEstimate assess_accuracy(const AccuracyInputs& in);

// The inputs of a run (the effective dt from the TS; pantograph frequencies
// at the initial state U0), assessed and printed before stepping.
AccuracyEstimate estimate_accuracy(const Context& ctx, const scene::RunScene& run,
                                   assembly::CoupledSystem& system,
                                   const solvers::DynamicSolver& solver, Vec U0, bool print = true);
void print_accuracy(const Context& ctx, const AccuracyEstimate& estimate);

// Console line of the catenary model (fidelity, modal basis and cache).
void print_catenary_setup(const Context& ctx, const scene::RunScene& run,
                          const CatenarySetup& setup);
// summary.json: catenary model, modal facts, droppers evaluated, accuracy estimate.
void add_fidelity_facts(const scene::RunScene& run, const CatenarySetup& setup,
                        const assembly::CoupledSystem& system, const AccuracyEstimate& estimate,
                        nlohmann::json& facts);

}  // namespace pcsim::simulation
