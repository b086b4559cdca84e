// The pilot runs of the accuracy estimate (accuracy_pilot.hpp).
#include "pcsim/simulation/accuracy_pilot.hpp"

#include <malloc.h>
#include <petscsys.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>

#include "cache_written.hpp"
#include "pcsim/catenary/reduced_basis.hpp"
#include "pcsim/core/error.hpp"
#include "pcsim/core/profiling.hpp"
#include "pcsim/core/vec_root.hpp"
#include "pcsim/core/version.hpp"
#include "pcsim/output/output_dir.hpp"
#include "pcsim/simulation/catenary_setup.hpp"
#include "pcsim/simulation/memory_estimate.hpp"
#include "pcsim/simulation/run.hpp"
#include "pcsim/simulation/run_checkpoint.hpp"
#include "pilot_process.hpp"

namespace pcsim::simulation {

namespace {

void apply_stretch(const PilotStretch& s, scene::RunScene& run) {
  run.end_x = s.end_x;
  run.analysis_from_span = s.from_span;
  run.analysis_to_span = s.to_span;
  run.analysis_from_x = s.from_x;
  run.analysis_to_x = s.to_x;
  run.energy = false;
  run.checkpoint_every = 0;
}

constexpr const char* kPilotCommand = "run (accuracy pilot)";

// A leftover "<dir>.partial" of a pilot run (its manifest's command is a
// pilot's): a pilot or its second process ended by a signal or killed. It is
// pcsim's scratch, replaced; the folder's lock keeps a pilot that still runs
// from losing it. Anything else is refused as OutputDir refuses it.
output::OutputRequest::Leftover pilot_leftover(const std::string& partial, std::string&) {
  std::ifstream in(partial + "/" + output::OutputDir::kManifestName);
  const auto manifest = nlohmann::json::parse(in, nullptr, false);
  const bool pilot = manifest.is_object() && manifest.value("command", "") == kPilotCommand;
  return pilot ? output::OutputRequest::Leftover::replace : output::OutputRequest::Leftover::refuse;
}

// One pilot run, quietly, in a folder of the cache that is removed after.
PilotFigures run_pilot(const Context& ctx, const SceneSource& source, const StudyVariant& variant,
                       const PilotStretch& stretch, double dt, double cutoff_hz,
                       const std::string& dir) {
  const double h = design_element_length(source.scene) * variant.h_factor;
  auto run = variant_scene(source, variant, h);
  apply_stretch(stretch, run);
  run.dt = dt;
  if (cutoff_hz > 0) run.catenary.modal.max_frequency_hz = cutoff_hz;
  output::OutputRequest request{dir,         "command line",   "--cache",        kPilotCommand,
                                source.path, "accuracy pilot", source.provenance};
  request.overwrite = true;  // the pilot's own folder of an earlier, killed pilot
  request.leftover = pilot_leftover;
  output::OutputDir out(ctx.comm, request);
  RunRequest what;
  what.name = "accuracy-pilot";
  what.scene_path = source.path;
  what.stop_on_signal = false;
  what.scene_dt = true;
  Context quiet = ctx;
  quiet.quiet = true;
  const auto outcome = simulation::run(quiet, run, what, out);
  PilotFigures figures;  // 'out' is not committed: its folder is removed
  on_rank0(ctx, [&] {
    figures.uplift_m = outcome.stats.max_uplift_m;
    for (const auto& p : outcome.stats.pantographs) {
      if (!p.complete)
        throw SolverError("the accuracy pilot: pantograph '" + p.name +
                          "' did not cross its stretch (-pcsim_accuracy_pilot false skips it)");
      figures.names.push_back(p.name);
      figures.force.push_back(p.force);
    }
  });
  return broadcast_figures(ctx.comm, figures);  // (rank 0's: the raises decided alike)
}

double relative_percent(double value, double reference) {
  return reference != 0 ? 100 * std::abs(value - reference) / std::abs(reference) : 0.0;
}

// |a - b| per figure and pantograph, b the reference; 'scale' multiplies.
std::vector<FigureErrors> differences(const PilotFigures& a, const PilotFigures& b, double scale) {
  std::vector<FigureErrors> out;
  for (std::size_t p = 0; p < b.force.size(); ++p) {
    const auto &x = a.force[p], &r = b.force[p];
    FigureErrors e;
    e.pantograph = b.names[p];
    e.samples = r.samples;
    const double fm = std::abs(r.mean) > 0 ? std::abs(r.mean) : 1.0;
    e.value = {relative_percent(x.mean, r.mean),
               relative_percent(x.std_dev, r.std_dev),
               relative_percent(x.statistical_max, r.statistical_max),
               relative_percent(x.actual_max, r.actual_max),
               relative_percent(a.uplift_m, b.uplift_m),
               100 * std::abs(x.statistical_min - r.statistical_min) / fm,
               100 * std::abs(x.actual_min - r.actual_min) / fm,
               std::abs(x.loss_of_contact_percent - r.loss_of_contact_percent)};
    for (double& v : e.value) v *= scale;
    out.push_back(e);
  }
  return out;
}

std::vector<FigureErrors> with_margin(std::vector<FigureErrors> measured) {
  for (auto& e : measured)
    for (int f = 0; f < kPilotFigures; ++f)
      e.value[f] = std::max(kPilotSafety * e.value[f],
                            f == kLossOfContactFigure ? kPilotLossFloor : kPilotForceFloor);
  return measured;
}

nlohmann::json errors_json(const std::vector<FigureErrors>& errors) {
  nlohmann::json j = nlohmann::json::array();
  for (const auto& e : errors) {
    nlohmann::json p = {{"pantograph", e.pantograph}, {"samples", e.samples}};
    for (int f = 0; f < kPilotFigures; ++f) p[kPilotFigureKeys[f]] = e.value[f];
    j.push_back(p);
  }
  return j;
}

std::vector<FigureErrors> errors_from_json(const nlohmann::json& j) {
  std::vector<FigureErrors> out;
  for (const auto& p : j) {
    FigureErrors e;
    e.pantograph = p.at("pantograph").get<std::string>();
    e.samples = p.value("samples", std::size_t{0});
    for (int f = 0; f < kPilotFigures; ++f) e.value[f] = p.at(kPilotFigureKeys[f]).get<double>();
    out.push_back(e);
  }
  return out;
}

// Options that only observe a run (logs, monitors, viewers, help, the
// pilot's own switch) or stop it (RunStopsSetAside: not the pilot's): they
// change no figure of the pilot, so they stay out of the key (a run with
// -log_view or -ts_max_steps reads the cache of the same run without it).
bool observing_option(const std::string& name) {
  const auto ends_with = [&](const std::string& tail) {
    return name.size() >= tail.size() &&
           name.compare(name.size() - tail.size(), tail.size(), tail) == 0;
  };
  const auto starts_with = [&](const std::string& head) { return name.rfind(head, 0) == 0; };
  return starts_with("log_") || starts_with("malloc") || starts_with("options_") ||
         starts_with("on_error") || name == "info" || name == "help" || name == "version" ||
         name == "memory_view" || name == "pcsim_accuracy_pilot" || name == "pcsim_pilot_process" ||
         ends_with("_view") || name.find("_monitor") != std::string::npos ||
         ends_with("_converged_reason") || run_stop_option(name);
}

// The options database without the observing options: "-name [value]" pairs,
// a value being a word that does not start with '-' and a letter.
std::string numerics_options() {
  char* all = nullptr;
  PCSIM_PETSC(PetscOptionsGetAll(nullptr, &all));
  std::istringstream words(all ? all : "");
  PCSIM_PETSC(PetscFree(all));
  std::string kept, word;
  bool keep = false;
  while (words >> word) {
    const bool name =
        word.size() > 1 && word[0] == '-' && std::isalpha(static_cast<unsigned char>(word[1]));
    if (name) keep = !observing_option(word.substr(1));
    if (keep) kept += word + " ";
  }
  return kept;
}

// The cache key: the scene's inputs as read, the run's numerics (time step,
// HHT α, fidelity, cut-off given, the options database but its observing
// options) and pcsim's version.
std::string pilot_key(const SceneSource& source, const scene::RunScene& run) {
  char numerics[256];
  std::snprintf(numerics, sizeof numerics,
                "accuracy-pilot v2 %s %s dt=%.17g alpha=%.17g model=%s "
                "cutoff=%.17g given=%d",
                version(), git_commit(), run.dt, run.hht_alpha,
                catenary::fidelity_name(run.catenary.fidelity), run.catenary.modal.max_frequency_hz,
                run.catenary.modal_cutoff_given ? 1 : 0);
  const std::string command = std::string(numerics) + " options: " + numerics_options();
  return inputs_fingerprint(command, recorded_inputs(source.path, source.scene));
}

std::string cache_file(const Context& ctx, const std::string& key) {
  return ctx.cache_dir + "/accuracy-pilot-" + key.substr(0, 24) + ".json";
}

bool read_cached(const Context& ctx, const std::string& key, PilotEstimate& pilot) {
  int found = 0;
  std::string text;
  if (ctx.rank == 0) {
    std::ifstream in(cache_file(ctx, key));
    if (in) {
      text.assign(std::istreambuf_iterator<char>(in), {});
      try {
        const auto j = nlohmann::json::parse(text);
        found = j.at("key").get<std::string>() == key;
        if (found) pilot = PilotEstimate::from_json(j.at("estimate"));
      } catch (const std::exception&) {
        found = 0;  // unreadable: a miss
      }
    }
  }
  MPI_Bcast(&found, 1, MPI_INT, 0, ctx.comm);
  if (!found) return false;
  text = broadcast_text(ctx.comm, text);
  pilot = PilotEstimate::from_json(nlohmann::json::parse(text).at("estimate"));
  pilot.cached = true;
  return true;
}

// Rank 0, atomically (a temporary file renamed over); a cache that cannot be
// written is only a warning: the run goes on.
void write_cached(const Context& ctx, const std::string& key, const PilotEstimate& pilot) {
  if (ctx.rank != 0) return;
  const std::string file = cache_file(ctx, key);
  const std::string tmp = file + ".tmp-" + std::to_string(getpid());
  std::error_code ec;
  std::filesystem::create_directories(ctx.cache_dir, ec);
  {
    std::ofstream out(tmp);
    out << nlohmann::json{{"key", key}, {"estimate", pilot.json()}}.dump(1) << "\n";
    if (!out.flush()) {
      out.close();
      std::filesystem::remove(tmp, ec);
      std::fprintf(stderr, "pcsim: warning: the accuracy pilot could not be cached in %s\n",
                   file.c_str());
      return;
    }
  }
  std::filesystem::rename(tmp, file, ec);
  if (ec) std::filesystem::remove(tmp, ec);
}

}  // namespace

std::vector<FigureErrors> PilotEstimate::discretisation() const {
  return with_margin(discretisation_measured);
}

std::vector<FigureErrors> PilotEstimate::reduction() const {
  return with_margin(reduction_measured);
}

std::vector<PilotEstimate::OutsideTarget> PilotEstimate::outside_targets() const {
  return figures_outside_targets(reduction_measured);
}

std::vector<PilotEstimate::OutsideTarget> PilotEstimate::discretisation_outside_targets() const {
  return figures_outside_targets(discretisation_measured);
}

nlohmann::json PilotEstimate::json() const {
  nlohmann::json j = {{"cached", cached},
                      {"seconds", seconds},
                      {"runs", runs},
                      {"from_x", from_x},
                      {"to_x", to_x},
                      {"refined_mesh", refined_mesh},
                      {"second_process", second_process},
                      {"second_process_peak_memory_mb", second_process_peak_mb},
                      {"safety_factor", kPilotSafety},
                      {"floor", kPilotForceFloor},
                      {"loss_of_contact_floor", kPilotLossFloor},
                      {"discretisation", errors_json(discretisation())},
                      {"discretisation_measured", errors_json(discretisation_measured)}};
  j["discretisation_outside_targets"] = outside_targets_json(discretisation_outside_targets());
  if (cutoff_hz > 0) {
    j["cutoff_hz"] = cutoff_hz;
    j["cutoff_raises"] = cutoff_raises;
    j["cutoff_lowered_from_hz"] = cutoff_lowered_from_hz;
    j["cutoff_raise_refused_hz"] = cutoff_raise_refused_hz;
    j["reduction"] = errors_json(reduction());
    j["reduction_measured"] = errors_json(reduction_measured);
    j["reduction_outside_targets"] = outside_targets_json(outside_targets());
  }
  return j;
}

PilotEstimate PilotEstimate::from_json(const nlohmann::json& j) {
  PilotEstimate p;
  p.done = true;
  p.seconds = j.at("seconds").get<double>();
  p.runs = j.at("runs").get<int>();
  p.from_x = j.at("from_x").get<double>();
  p.to_x = j.at("to_x").get<double>();
  p.refined_mesh = j.at("refined_mesh").get<bool>();
  p.second_process = j.value("second_process", false);
  p.second_process_peak_mb = j.value("second_process_peak_memory_mb", 0.0);
  p.discretisation_measured = errors_from_json(j.at("discretisation_measured"));
  if (j.contains("cutoff_hz")) {
    p.cutoff_hz = j.at("cutoff_hz").get<double>();
    p.cutoff_raises = j.at("cutoff_raises").get<int>();
    p.cutoff_lowered_from_hz = j.value("cutoff_lowered_from_hz", 0.0);
    p.cutoff_raise_refused_hz = j.value("cutoff_raise_refused_hz", 0.0);
    p.reduction_measured = errors_from_json(j.at("reduction_measured"));
  }
  return p;
}

PilotChoice accuracy_pilot_choice() {
  return read_auto_option("pcsim run", "-pcsim_accuracy_pilot",
                          "pilot runs of the accuracy estimate before the run, and a modal cut-off "
                          "chosen by them (auto: modal runs; true; false; docs/fidelity.md)");
}

bool wants_accuracy_pilot(PilotChoice choice, const scene::RunScene& run) {
  return choice == PilotChoice::on || (choice == PilotChoice::automatic &&
                                       run.catenary.fidelity == catenary::CatenaryFidelity::modal);
}

namespace {

// The pilot's runs: here, each timed, or in the second process, collected.
struct PilotRuns {
  const Context& ctx;
  const SceneSource& source;
  const PilotStretch& stretch;
  const std::string dir;
  PilotEstimate& pilot;
  std::unique_ptr<PilotProcess> second;

  // A run here, its line printed before it starts and its time after.
  PilotFigures here(const std::string& label, const StudyVariant& variant, double dt,
                    double cutoff_hz) {
    print0(ctx, "    %s ... ", label.c_str());
    std::fflush(stdout);
    const double t0 = wall_clock_s();
    auto figures = run_pilot(ctx, source, variant, stretch, dt, cutoff_hz, dir);
    // What the run freed goes back to the system: the next run's larger
    // basis would otherwise be laid beside its fragments (a first run's peak).
    malloc_trim(0);
    print0(ctx, "%.1f s\n", wall_clock_s() - t0);
    ++pilot.runs;
    return figures;
  }
  // The second process's next run, when it has ended.
  PilotFigures collected(const std::string& label) {
    const auto result = second->next();
    print0(ctx, "    %s (second process) ... %.1f s\n", label.c_str(), result.seconds);
    ++pilot.runs;
    return result.figures;
  }
  // The FE runs in a second process: the one at dt/2 (and h/2), and a modal
  // pilot's run at dt and h too (its modal runs need it only after the
  // first); their figures are those of the same runs here.
  void start_second_process(const StudyVariant& linear, const StudyVariant& fine, double dt,
                            bool modal) {
    std::vector<PilotProcess::Run> runs;
    const std::string fe_dir = dir + "-fe";
    if (modal)
      runs.push_back([=] { return run_pilot(ctx, source, linear, stretch, dt, 0, fe_dir); });
    runs.push_back([=] { return run_pilot(ctx, source, fine, stretch, dt / 2, 0, fe_dir); });
    print0(ctx, "    linear FE %s in a second process, beside the %s\n",
           modal ? "at dt and h and at dt/2" : "at dt/2", modal ? "modal runs" : "run at dt and h");
    second = std::make_unique<PilotProcess>(std::move(runs));
    pilot.second_process = true;
  }
};

// Under a modal pilot run's line: the figures outside the targets there.
void print_outside(const Context& ctx, double cutoff, const std::vector<FigureErrors>& measured) {
  const std::string list = outside_targets_list(measured);
  if (!list.empty())
    print0(ctx, "      outside the targets at %.1f Hz: %s\n", cutoff, list.c_str());
}

// The modal runs: the cut-off 'run' has, raised until the reduction is
// within the targets (kMaxCutoffRaises at most, kMaxCutoffRaisesWhileCloser
// while each raise brings the figures outside closer; kept if the scene set
// it). A raise beyond kMaxCutoffRaises computes its modes afresh: the third
// raise frees what the modes were computed with (a 1000-span window's peak
// memory), since most pilots end there.
// 'reference' (linear FE at dt and h) is collected after the first.
double choose_cutoff(PilotRuns& runs, const scene::RunScene& run,
                     std::optional<PilotFigures>& reference, const std::string& reference_label) {
  auto& pilot = runs.pilot;
  StudyVariant reduced;
  reduced.model = catenary::CatenaryFidelity::modal;
  ModalExtensionScope raises;  // a raised cut-off computes only the modes above
  double cutoff = run.catenary.modal.max_frequency_hz;
  std::vector<double> cutoffs;
  std::vector<std::vector<FigureErrors>> tried;
  for (;;) {
    if (run.catenary.modal_cutoff_given || pilot.cutoff_raises >= kMaxCutoffRaises)
      raises.last_computation_next();
    char label[96];
    std::snprintf(label, sizeof label, "modal at %.1f Hz (its modes computed unless cached)",
                  cutoff);
    const long before = last_modal_computation().serial;
    PilotFigures figures;
    try {
      figures = runs.here(label, reduced, run.dt, cutoff);
    } catch (const ModalMemoryError& e) {  // a raise the machine cannot hold: raised no further
      if (cutoffs.empty()) {               // the first: the run's error (its line ended first)
        print0(runs.ctx, "\n");
        throw;
      }
      print0(runs.ctx, "not raised: %s\n", e.needed().c_str());
      --pilot.cutoff_raises;
      pilot.cutoff_raise_refused_hz = cutoff;
      return settle_cutoff(pilot, cutoffs, tried);
    }
    const auto modes = last_modal_computation();
    if (modes.serial != before && modes.kept > 0)
      print0(runs.ctx, "      %ld modes computed, the %ld below %.1f Hz kept from the last\n",
             modes.computed, modes.kept, modes.kept_below_hz);
    if (modes.serial != before && modes.again_below_hz > 0)
      print0(runs.ctx, "      %ld modes computed, those below %.1f Hz again: %s\n", modes.computed,
             modes.again_below_hz, "their rows are not in the cache file this process wrote");
    if (!reference) reference = runs.collected(reference_label);
    pilot.reduction_measured = differences(figures, *reference, 1.0);
    cutoffs.push_back(cutoff);
    tried.push_back(pilot.reduction_measured);
    if (!run.catenary.modal_cutoff_given)  // else listed under the estimate alone
      print_outside(runs.ctx, cutoff, pilot.reduction_measured);
    if (run.catenary.modal_cutoff_given ||
        figures_outside_targets(pilot.reduction_measured).empty() || cutoff <= 0)
      return cutoff;
    const bool may_raise =
        pilot.cutoff_raises < kMaxCutoffRaises ||
        (pilot.cutoff_raises < kMaxCutoffRaisesWhileCloser && last_raise_closer(tried));
    if (!may_raise) return settle_cutoff(pilot, cutoffs, tried);
    cutoff *= kCutoffRaise;
    ++pilot.cutoff_raises;
  }
}

}  // namespace

PilotEstimate run_accuracy_pilot(const Context& ctx, const SceneSource& source,
                                 scene::RunScene& run) {
  const bool modal = run.catenary.fidelity == catenary::CatenaryFidelity::modal;
  const std::string key = pilot_key(source, run);
  PilotEstimate pilot;
  if (read_cached(ctx, key, pilot)) {
    if (modal) run.catenary.modal.max_frequency_hz = pilot.cutoff_hz;
    return pilot;
  }
  const double start = wall_clock_s();
  const PilotStretch stretch = pilot_stretch(run);
  check_pilot_without_jacobian_test();
  const RunStopsSetAside run_stops;
  pilot.done = true;
  pilot.from_x = stretch.from_x;
  pilot.to_x = stretch.to_x;
  print0(ctx, "  accuracy pilot: spans %d-%d (x %.0f-%.0f m)%s\n", stretch.from_span,
         stretch.to_span, stretch.from_x, stretch.to_x, pilot_stretch_note(stretch, run).c_str());
  PilotRuns runs{ctx,   source, stretch, ctx.cache_dir + "/accuracy-pilot-" + key.substr(0, 12),
                 pilot, nullptr};
  StudyVariant linear;  // the run's dt and element length
  StudyVariant fine;
  pilot.refined_mesh = design_element_length(source.scene) > 0;
  fine.h_factor = pilot.refined_mesh ? 0.5 : 1.0;
  const std::string reference_label = "linear FE at the run's dt and h";
  const std::string fine_label = pilot.refined_mesh ? "linear FE at dt/2 and h/2"
                                                    : "linear FE at dt/2 (explicit design: h kept)";
  if (use_pilot_process(ctx)) runs.start_second_process(linear, fine, run.dt, modal);
  std::optional<PilotFigures> reference, converged;
  if (!runs.second || !modal) reference = runs.here(reference_label, linear, run.dt, 0);
  if (!runs.second) converged = runs.here(fine_label, fine, run.dt / 2, 0);
  if (modal) {
    pilot.cutoff_hz = choose_cutoff(runs, run, reference, reference_label);
    run.catenary.modal.max_frequency_hz = pilot.cutoff_hz;
    remove_superseded_files(ctx, pilot.cutoff_hz);  // the raises' cut-offs below
  }
  if (!converged) {
    converged = runs.collected(fine_label);
    pilot.second_process_peak_mb = runs.second->finish();
  }
  // Second order in dt and h: the error of the coarse run is 4/3 of its
  // difference to the run at half both.
  pilot.discretisation_measured = differences(*reference, *converged, 4.0 / 3.0);
  pilot.seconds = wall_clock_s() - start;
  print0(ctx, "    %d pilot runs in %.1f s", pilot.runs, pilot.seconds);
  if (pilot.second_process)
    print0(ctx, " (the second process's peak memory %.0f MB)", pilot.second_process_peak_mb);
  print0(ctx, "\n");
  if (pilot.cutoff_raise_refused_hz <= 0) write_cached(ctx, key, pilot);  // (else this machine's)
  return pilot;
}

}  // namespace pcsim::simulation
