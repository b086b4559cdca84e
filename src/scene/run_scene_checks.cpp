// Checks of a run scene that need every pantograph or the time step
// (pcsim/scene/run_scene.hpp): each names the scene file and the key.
#include <cmath>
#include <sstream>

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

void check_pantograph_positions(const InputNode& scene, RunScene& run) {
  const auto& mesh = run.catenary.mesh;
  const double x_last = mesh.support_x.back();
  const double travel = run.end_x - run.pantographs.front().start_x;
  for (std::size_t i = 0; i < run.pantographs.size(); ++i) {
    const auto& p = run.pantographs[i];
    for (std::size_t j = 0; j < i; ++j)
      if (run.pantographs[j].name == p.name)
        throw InputError(origin(scene, entry_key(i, "name")), entry_key(i, "name"),
                         "pantograph name '" + p.name + "' is already used by pantographs[" +
                             std::to_string(j) + "] (names label the results)");
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
  for (std::size_t i = 0; i < run.pantographs.size(); ++i)
    for (std::size_t j = 0; j < i; ++j) {
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
