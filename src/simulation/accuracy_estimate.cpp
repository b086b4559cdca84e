#include "pcsim/simulation/accuracy_estimate.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "pcsim/assembly/modal_catenary.hpp"
#include "pcsim/simulation/accuracy_pilot.hpp"

namespace pcsim::simulation {

namespace {

// Calibration: |error of sigma| [%] against the criterion's value on EN 50318
// at 300 km/h (docs/fidelity.md), interpolated linearly in log(value), held
// beyond the ends.
struct CalibrationPoint {
  double value, error_percent;
};
// Steps per period of the highest frequency that matters (63.4 Hz): dt 5, 3,
// 2.5, 2, 1 ms against 0.5 ms, linear catenary, 0.5 m elements (`pcsim study
// accuracy runs/en50318-300.yaml -study_models linear -study_dt_factors
// 0.5,1,2,2.5,3,5 -study_h_factors 1`).
const std::vector<CalibrationPoint> kTimeStepCalibration = {{3.15, 51.0}, {5.25, 6.0}, {6.31, 5.8},
                                                            {7.88, 2.2},  {15.8, 0.4}, {31.5, 0.0}};
// Contact-wire elements per wavelength v / cutoff_hz (4.17 m): 2, 1, 0.5 m
// against 0.25 m elements, linear catenary, dt 1 ms (-study_h_factors
// 0.5,1,2,4 -study_dt_factors 1).
const std::vector<CalibrationPoint> kMeshCalibration = {
    {2.08, 10.9}, {4.17, 1.08}, {8.33, 0.13}, {16.7, 0.0}};
// Modal cut-off over cutoff_hz / (1 - v/c) (63.4 Hz): modal against linear
// catenary at 40, 50, 57 and 70 Hz (-study_cutoff_factors; 0.9-1.6 all give
// 0.2-0.6 %, the noise of the comparison).
const std::vector<CalibrationPoint> kModalCalibration = {
    {0.63, 33.5}, {0.79, 8.2}, {0.9, 0.5}, {1.6, 0.2}};
// Converged region: sigma within about 1 % of the converged value.
constexpr double kTargetErrorPercent = 1.0;

double calibrated_error(const std::vector<CalibrationPoint>& table, double value) {
  if (value <= table.front().value) return table.front().error_percent;
  for (std::size_t i = 1; i < table.size(); ++i)
    if (value <= table[i].value) {
      const double w =
          std::log(value / table[i - 1].value) / std::log(table[i].value / table[i - 1].value);
      return (1 - w) * table[i - 1].error_percent + w * table[i].error_percent;
    }
  return table.back().error_percent;
}

// The smallest value whose calibrated error is within the target.
double converged_min(const std::vector<CalibrationPoint>& table) {
  for (std::size_t i = 1; i < table.size(); ++i)
    if (table[i].error_percent <= kTargetErrorPercent) {
      const auto& a = table[i - 1];
      const auto& b = table[i];
      const double w =
          (a.error_percent - kTargetErrorPercent) / (a.error_percent - b.error_percent);
      return a.value * std::pow(b.value / a.value, w);
    }
  return table.back().value;
}

AccuracyCriterion criterion(const char* name, const char* measure, double value,
                            const std::vector<CalibrationPoint>& table) {
  AccuracyCriterion c;
  c.name = name;
  c.measure = measure;
  c.value = value;
  c.converged_min = converged_min(table);
  c.error_percent = calibrated_error(table, value);
  c.ok = value >= c.converged_min * (1 - 1e-9);
  return c;
}

std::string format(const char* fmt, double a) {
  char buffer[160];
  std::snprintf(buffer, sizeof(buffer), fmt, a);
  return buffer;
}

// A mode takes part in the contact when its M-normalised shape moves the
// contact point by at least this fraction (in phi_c^2) of the mode that moves
// it most. The flexible DSA-380 on kH = 50 kN/m (runs/interaction/
// dsa380-300-flexible.yaml), measured: the modes at 13.6, 15.4, 1.9, 7.7 and
// 24.9 Hz move it by 1, 0.10, 3.4e-3, 1.3e-3 and 2.9e-4; every other (the
// bars' bending modes from 26 Hz, the axial ones up to 404 kHz) by 2.8e-7 or
// less: three orders of magnitude between the two groups.
constexpr double kContactParticipation = 1e-4;

// Highest natural frequency of one pantograph with its head on the contact
// spring kH (rigid wire: an upper bound) among the modes that move the
// contact point (the symmetric parts of K and M; M positive definite). A
// model whose M is not (constraints) falls back to every finite mode.
double contact_mode_frequency(const pantograph::PantographModel& model, const Eigen::VectorXd& q,
                              double contact_stiffness) {
  const int n = model.dof_count();
  Eigen::MatrixXd K(n, n), C(n, n), M(n, n);
  model.tangents(0.0, q, Eigen::VectorXd::Zero(n), Eigen::VectorXd::Zero(n), K, C, M);
  K(model.contact_dof(), model.contact_dof()) += contact_stiffness;
  const Eigen::MatrixXd Ks = 0.5 * (K + K.transpose()), Ms = 0.5 * (M + M.transpose());
  double f = 0;
  if (Ms.llt().info() == Eigen::Success) {
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> ges(Ks, Ms);
    const Eigen::VectorXd phi_c = ges.eigenvectors().row(model.contact_dof()).transpose();
    const double most = phi_c.cwiseAbs2().maxCoeff();
    for (int i = 0; i < n; ++i)
      if (phi_c[i] * phi_c[i] >= kContactParticipation * most)
        f = std::max(f, std::sqrt(std::abs(ges.eigenvalues()[i])) / (2 * M_PI));
    return f;
  }
  const Eigen::GeneralizedEigenSolver<Eigen::MatrixXd> ges(K, M);
  for (int i = 0; i < n; ++i) {
    const double beta = ges.betas()[i];
    if (std::abs(beta) < 1e-14) continue;
    f = std::max(f, std::sqrt(std::abs(ges.alphas()[i].real() / beta)) / (2 * M_PI));
  }
  return f;
}

// The highest of the pantographs' contact-mode frequencies, at the initial state.
double pantograph_frequency(assembly::CoupledSystem& system, Vec U0) {
  const auto record = system.record(0.0, U0);  // the coordinates on rank 0
  double f = 0;
  for (std::size_t p = 0; p < record.q.size(); ++p) {
    const auto& model = *system.pantographs()[p].model;
    const Eigen::VectorXd q =
        Eigen::Map<const Eigen::VectorXd>(record.q[p].data(), model.dof_count());
    f = std::max(f, contact_mode_frequency(model, q, system.contact_stiffness()));
  }
  MPI_Bcast(&f, 1, MPI_DOUBLE, 0, system.comm());
  return f;
}

double mean_contact_element(const catenary::CatenaryMesh& mesh) {
  const auto& wire = mesh.wires[mesh.contact_wire];
  double sum = 0;
  for (int e : wire.elements) sum += mesh.cables[e].ref_length;
  return wire.elements.empty() ? 0.0 : sum / wire.elements.size();
}

}  // namespace

bool AccuracyEstimate::ok() const {
  return std::all_of(criteria.begin(), criteria.end(), [](const auto& c) { return c.ok; });
}

nlohmann::json AccuracyEstimate::json() const {
  nlohmann::json j;
  j["ok"] = ok();
  j["highest_frequency_hz"] = highest_frequency_hz;
  for (const auto& c : criteria)
    j["criteria"].push_back({{"name", c.name},
                             {"measure", c.measure},
                             {"value", c.value},
                             {"converged_min", c.converged_min},
                             {"estimated_sigma_error_percent", c.error_percent},
                             {"ok", c.ok},
                             {"advice", c.advice}});
  return j;
}

AccuracyEstimate assess_accuracy(const AccuracyInputs& in) {
  AccuracyEstimate e;
  const double band = catenary::doppler_frequency(in.filter_hz, in.speed, in.wave_speed);
  e.highest_frequency_hz = std::max(in.pantograph_hz, band);
  auto dt = criterion("time step", "steps per period of the highest frequency",
                      1.0 / (in.dt * e.highest_frequency_hz), kTimeStepCalibration);
  dt.advice = "-ts_dt " + format("%.2g", 1.0 / (dt.converged_min * e.highest_frequency_hz)) +
              " (or smaller)";
  e.criteria.push_back(dt);
  const double wavelength = in.speed / in.filter_hz;
  auto mesh = criterion("element length", "contact-wire elements per wavelength v/f_c",
                        wavelength / in.element_length, kMeshCalibration);
  mesh.advice = "an element_length of " + format("%.2g", wavelength / mesh.converged_min) +
                " m or less in the design";
  e.criteria.push_back(mesh);
  if (in.modal && in.modal_cutoff_hz > 0) {
    auto modal = criterion("modal cut-off", "max_frequency_hz over cutoff_hz/(1-v/c)",
                           in.modal_cutoff_hz / band, kModalCalibration);
    modal.advice =
        "catenary.max_frequency_hz: " + format("%.0f", modal.converged_min * band) + " (or more)";
    e.criteria.push_back(modal);
  }
  return e;
}

AccuracyEstimate estimate_accuracy(const Context& ctx, const scene::RunScene& run,
                                   assembly::CoupledSystem& system,
                                   const solvers::DynamicSolver& solver, Vec U0, bool print) {
  const auto& mesh = run.catenary.mesh;
  AccuracyInputs in;
  PetscReal dt;
  PCSIM_PETSC(TSGetTimeStep(solver.ts(), &dt));
  in.dt = dt;
  in.speed = run.speed;
  in.wave_speed = catenary::wave_speed(mesh.wires[mesh.contact_wire]);
  in.filter_hz = run.cutoff_hz;
  in.element_length = mean_contact_element(mesh);
  in.pantograph_hz = pantograph_frequency(system, U0);
  in.modal = run.catenary.fidelity == catenary::CatenaryFidelity::modal;
  in.modal_cutoff_hz = run.catenary.modal.max_frequency_hz;
  const auto estimate = assess_accuracy(in);
  if (print) print_accuracy(ctx, estimate);
  return estimate;
}

void print_accuracy(const Context& ctx, const AccuracyEstimate& e) {
  print0(ctx, "  accuracy estimate (highest frequency to resolve %.1f Hz):\n",
         e.highest_frequency_hz);
  for (const auto& c : e.criteria)
    print0(ctx, "    %-15s %6.2f %s (converged >= %.2f): sigma error ~%.1f %%%s\n", c.name.c_str(),
           c.value, c.measure.c_str(), c.converged_min, c.error_percent, c.ok ? "" : "  OUTSIDE");
  bool discretisation_said = false;
  for (const auto& c : e.criteria) {
    if (c.ok) continue;
    print0(ctx,
           "  warning: the %s is outside the converged region (sigma error ~%.0f %%): use %s\n",
           c.name.c_str(), c.error_percent, c.advice.c_str());
    // The pilot's discretisation estimate assumes second order from dt, h to
    // dt/2, h/2; at dt 2 ms it fell below a trailing pantograph's actual σ
    // error (docs/fidelity.md, "Coarse variants").
    if ((c.name == "time step" || c.name == "element length") && !discretisation_said) {
      print0(ctx,
             "    (an accuracy pilot's discretisation estimate is then an indication, not a bound: "
             "its runs at dt, h and dt/2, h/2 may not converge at second order yet; "
             "docs/fidelity.md, \"Coarse variants\")\n");
      discretisation_said = true;
    }
  }
}

void print_catenary_setup(const Context& ctx, const scene::RunScene& run,
                          const CatenarySetup& setup) {
  print0(ctx, "  catenary model: %s", catenary::fidelity_name(run.catenary.fidelity));
  if (setup.modal)
    print0(ctx, ", %d basis vectors (%d modes below %.1f Hz, %d left out), %s in %.2f s",
           setup.basis_size, setup.eigenmodes, setup.cutoff_hz, setup.dropped_modes,
           setup.basis_kept                            ? "kept in memory from an earlier run"
           : setup.cache_hit && !setup.basis_assembled ? "read from the cache (assembled)"
           : setup.cache_hit                           ? "read from the cache"
                                                       : "computed",
           setup.setup_seconds);
  print0(ctx, "\n");
  if (setup.modal && !run.modal_method_note.empty())
    print0(ctx, "  modal method: %s\n", run.modal_method_note.c_str());
}

void add_fidelity_facts(const scene::RunScene& run, const CatenarySetup& setup,
                        const assembly::CoupledSystem& system, const AccuracyEstimate& estimate,
                        nlohmann::json& facts) {
  facts["catenary_model"] = catenary::fidelity_name(run.catenary.fidelity);
  if (setup.modal) {
    facts["modal"] = setup.facts();
    facts["modal"]["method"] = catenary::modal_method_name(run.catenary.modal.method);
    facts["modal"]["method_note"] = run.modal_method_note;
    if (const auto* modal = dynamic_cast<const assembly::ModalCatenary*>(&system.catenary())) {
      const long steps = facts.value("steps", 0L);
      facts["modal"]["dropper_evaluations_per_step"] =
          steps > 0 ? static_cast<double>(modal->dropper_evaluations()) / steps : 0.0;
      facts["modal"]["single_precision_updates_per_step"] =
          steps > 0 ? static_cast<double>(modal->single_precision_updates()) / steps : 0.0;
      facts["modal"]["half_precision_updates_per_step"] =
          steps > 0 ? static_cast<double>(modal->half_precision_updates()) / steps : 0.0;
      facts["modal"]["exact_updates_per_step"] =
          steps > 0 ? static_cast<double>(modal->exact_anchors()) / steps : 0.0;
      facts["modal"]["line_tries_per_step"] =
          steps > 0 ? static_cast<double>(modal->line_tries()) / steps : 0.0;
      facts["modal"]["tracked_bars"] = modal->slack_bars().size();
    }
  }
  facts["accuracy_estimate"] = estimate.json();
}

namespace {

// Why a pilot that left figures outside the targets raised no further.
const char* why_raises_ended(const PilotEstimate& pilot) {
  if (pilot.cutoff_raise_refused_hz > 0)
    return "where the next raise would not fit in this machine's memory";
  return pilot.cutoff_raises >= kMaxCutoffRaisesWhileCloser
             ? "the most the pilot raises it"
             : "where a raise no longer brought every figure outside the targets closer";
}

// "sigma of 'p', reduction 1.20 % in the pilot (target 1.0 %; hint)"; a
// reduction's loss of contact in samples too (a discretisation's is
// extrapolated: no count of samples).
std::string beyond_target(const PilotEstimate::OutsideTarget& t, bool reduction, const char* hint) {
  const char* error = reduction ? "reduction" : "discretisation";
  const char* unit = pilot_figure_unit(t.figure);
  // A third decimal where two would print the target itself (0.104 pt, not 0.10).
  const int decimals = std::round(t.measured * 100) / 100 <= kPilotTargets[t.figure] ? 3 : 2;
  char line[512];
  std::snprintf(line, sizeof line, "%s of '%s', %s %.*f %s%s in the pilot (target %.1f %s; %s)",
                kPilotFigureLabels[t.figure], t.pantograph.c_str(), error, decimals, t.measured,
                unit, reduction ? loss_samples_note(t).c_str() : "", kPilotTargets[t.figure], unit,
                hint);
  return line;
}

}  // namespace

void print_pilot(const Context& ctx, const PilotEstimate& pilot) {
  if (!pilot.done) return;
  const auto discretisation = pilot.discretisation(), reduction = pilot.reduction();
  const bool modal = !reduction.empty();
  print0(ctx, "  accuracy estimate from the pilot%s (x %.0f-%.0f m; %s):\n",
         pilot.cached ? " (cached)" : "", pilot.from_x, pilot.to_x,
         modal ? "discretisation against converged linear FE, reduction against linear FE"
               : "discretisation against converged linear FE");
  const auto outside = pilot.outside_targets();
  if (modal && pilot.cutoff_raises > 0 && outside.empty())
    print0(ctx, "    modal cut-off raised %d time(s) to %.1f Hz to meet the targets\n",
           pilot.cutoff_raises, pilot.cutoff_hz);
  else if (modal && pilot.cutoff_lowered_from_hz > 0)
    print0(ctx,
           "    modal cut-off raised %d time(s) to %.1f Hz, %s; the run takes %.1f Hz: no figure "
           "there or at a cut-off above it is further from its target than at %.1f Hz\n",
           pilot.cutoff_raises, pilot.cutoff_lowered_from_hz, why_raises_ended(pilot),
           pilot.cutoff_hz, pilot.cutoff_lowered_from_hz);
  else if (modal && pilot.cutoff_raise_refused_hz > 0)
    print0(ctx,
           "    modal cut-off raised %d time(s), to %.1f Hz: its raise to %.1f Hz would not fit "
           "in this machine's memory\n",
           pilot.cutoff_raises, pilot.cutoff_hz, pilot.cutoff_raise_refused_hz);
  else if (modal && pilot.cutoff_raises > 0)
    print0(ctx, "    modal cut-off raised %d time(s) to %.1f Hz, %s\n", pilot.cutoff_raises,
           pilot.cutoff_hz, why_raises_ended(pilot));
  // Where the raises above the run's cut-off brought nothing closer, raising
  // it again is no advice.
  char hint[96] = "catenary.max_frequency_hz raises the cut-off";
  if (pilot.cutoff_raise_refused_hz > 0)
    std::snprintf(hint, sizeof hint, "%.1f Hz would not fit in memory",
                  pilot.cutoff_raise_refused_hz);
  else if (pilot.cutoff_lowered_from_hz > 0)
    std::snprintf(hint, sizeof hint, "no closer up to %.1f Hz", pilot.cutoff_lowered_from_hz);
  for (const auto& t : outside)
    print0(ctx, "    outside the targets at %.1f Hz: %s\n", pilot.cutoff_hz,
           beyond_target(t, true, hint).c_str());
  // The figures the run's dt and h leave unconverged: its linear FE pilots at
  // dt, h and dt/2, h/2 differ beyond the targets (docs/fidelity.md, "The
  // discretisation beyond the targets").
  const char* smaller = pilot.refined_mesh
                            ? "a smaller -ts_dt and catenary.design.element_length"
                            : "a smaller -ts_dt; an explicit design's elements are its own";
  for (const auto& t : pilot.discretisation_outside_targets())
    print0(ctx, "    beyond the targets at the run's dt and h: %s\n",
           beyond_target(t, false, smaller).c_str());
  for (std::size_t p = 0; p < discretisation.size(); ++p) {
    print0(ctx, "    %-16s %16s%s\n", discretisation[p].pantograph.c_str(), "discretisation",
           modal ? "   reduction" : "");
    for (int f = 0; f < kPilotFigures; ++f) {
      const char* unit = pilot_figure_unit(f);
      print0(ctx, "    %-16s %12.2f %-3s", kPilotFigureLabels[f], discretisation[p].value[f], unit);
      if (modal) print0(ctx, " %9.2f %-3s", reduction[p].value[f], unit);
      print0(ctx, "\n");
    }
  }
}

}  // namespace pcsim::simulation
