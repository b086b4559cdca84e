// Checks of a run scene that need every pantograph or the time step
// (pcsim/scene/run_scene.hpp): each names the scene file and the key.
#include <algorithm>
#include <cmath>
#include <sstream>
#include <unordered_map>
#include <vector>

#include "pcsim/core/format.hpp"
#include "pcsim/scene/run_scene.hpp"

namespace pcsim::scene {

namespace {

std::string entry_key(std::size_t i, const std::string& key) {
  return "pantographs[" + std::to_string(i) + "]." + key;
}

// What messages name for the value at 'key_path': the scene file, the base
// file it came from, or the --set / 'set' entry that gave it.
std::string origin(const InputNode& scene, const std::string& key_path) {
  return scene.sources().origin_of(key_path).label;
}

// Pantographs closer than this interact through the wire within a few
// milliseconds: allowed (a double unit has 200 m), but rarely meant.
constexpr double kMinPantographSpacing = 10.0;  // [m]
// More time steps than this is far beyond any study of the thesis (an EN 50318
// run at 300 km/h has 7e3): probably a wrong speed or time step.
constexpr double kManySteps = 1e7;
// Samples the zero-phase filter pads each end with (3 (2 sections + 1), order 4)
// and the fewest samples a statistic over the analysis section may rest on.
constexpr long kFilterPadding = 15;
constexpr long kMinSectionSamples = 10;

}  // namespace

std::string pantograph_name_problem(const std::string& name) {
  if (name.empty()) return "must not be empty";
  if (name == "." || name == "..") return "must not be '" + name + "'";
  if (name.find('/') != std::string::npos) return "must not contain '/'";
  for (const char c : name)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
      return "must not contain control characters";
  return "";
}

void check_pantograph_names(const InputNode& scene, const RunScene& run) {
  std::unordered_map<std::string, std::size_t> used;  // name -> first entry
  used.reserve(run.pantographs.size());
  for (std::size_t i = 0; i < run.pantographs.size(); ++i) {
    const std::string& name = run.pantographs[i].name;
    const std::string problem = pantograph_name_problem(name);
    if (!problem.empty())
      throw InputError(origin(scene, entry_key(i, "name")), entry_key(i, "name"),
                       problem + " (got '" + name +
                           "'; a name is one HDF5 group /pantographs/<name> of the results)");
    const auto [it, first] = used.emplace(name, i);
    if (!first)
      throw InputError(origin(scene, entry_key(i, "name")), entry_key(i, "name"),
                       "pantograph name '" + name + "' is already used by pantographs[" +
                           std::to_string(it->second) + "] (names label the results)");
  }
}

void check_pantograph_positions(const InputNode& scene, RunScene& run) {
  const auto& mesh = run.catenary.mesh;
  const double x_last = mesh.support_x.back();
  const double travel = run.end_x - run.pantographs.front().start_x;
  for (std::size_t i = 0; i < run.pantographs.size(); ++i) {
    const auto& p = run.pantographs[i];
    const double x_end = p.start_x + travel;
    if (x_end > x_last)
      throw InputError(origin(scene, entry_key(i, "start_x")), entry_key(i, "start_x"),
                       "pantograph '" + p.name + "' would run from " + format_number(p.start_x) +
                           " to " + format_number(x_end) +
                           " m, past the end of the contact wire at " + format_number(x_last) +
                           " m (the run ends when the first pantograph reaches "
                           "simulation.end_x = " +
                           format_number(run.end_x) + " m)");
  }
  // Close neighbours: sorted by start (ties in list order), each pantograph
  // against the one before it; one warning per pantograph, O(n log n).
  std::vector<std::size_t> order(run.pantographs.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return run.pantographs[a].start_x < run.pantographs[b].start_x;
  });
  for (std::size_t k = 1; k < order.size(); ++k) {
    const std::size_t i = std::max(order[k - 1], order[k]), j = std::min(order[k - 1], order[k]);
    const double gap = std::abs(run.pantographs[i].start_x - run.pantographs[j].start_x);
    if (gap < kMinPantographSpacing)
      run.warnings.push_back({origin(scene, entry_key(i, "start_x")), entry_key(i, "start_x"),
                              "pantograph '" + run.pantographs[i].name + "' starts " +
                                  format_number(gap) + " m from '" + run.pantographs[j].name +
                                  "' (less than " + format_number(kMinPantographSpacing) +
                                  " m: are both meant to be there?)"});
  }
}

void check_time_step(const InputNode& scene, RunScene& run, const std::string& dt_key) {
  const std::string dt_text = dt_key + " = " + format_number(run.dt) + " s";
  const double nyquist = 0.5 / run.dt;
  if (!(run.cutoff_hz < nyquist))
    throw InputError(origin(scene, "analysis.cutoff_hz"), "analysis.cutoff_hz",
                     "the contact-force filter's cut-off " + format_number(run.cutoff_hz) +
                         " Hz is not below the Nyquist frequency " + format_number(nyquist) +
                         " Hz of the time step (" + dt_text + "); use a smaller time step");
  const double duration = run.duration();
  const double steps = duration / run.dt;
  // The time step comes from the scene or from the command line (-ts_dt).
  const std::string dt_file = dt_key[0] == '-' ? "command line" : origin(scene, dt_key);
  const std::string too_few = "the contact-force filter needs more than ";
  if (steps <= kFilterPadding)
    throw InputError(dt_file, dt_key,
                     "the run of " + format_number(duration) + " s takes only " +
                         format_number(std::floor(steps)) + " steps of " + format_number(run.dt) +
                         " s; " + too_few + std::to_string(kFilterPadding));
  const double section_samples = (run.analysis_to_x - run.analysis_from_x) / (run.speed * run.dt);
  if (section_samples < kMinSectionSamples)
    throw InputError(
        dt_file, dt_key,
        "the analysis section (" + format_number(run.analysis_to_x - run.analysis_from_x) +
            " m) holds only " + format_number(std::floor(section_samples)) + " samples at " +
            format_number(run.speed * run.dt) + " m per step (" + dt_text +
            "); the statistics need at least " + std::to_string(kMinSectionSamples));
  if (steps > kManySteps)
    run.warnings.push_back({scene.file(), "simulation",
                            "the run takes " + format_number(steps) + " time steps (" +
                                format_number(duration) +
                                " s simulated: the first pantograph runs " +
                                format_number(run.end_x - run.pantographs.front().start_x) +
                                " m at speed_kmh " + format_number(run.speed * 3.6) + ", " +
                                dt_text + "), more than 1e7: check speed_kmh, end_x and dt"});
}

}  // namespace pcsim::scene
