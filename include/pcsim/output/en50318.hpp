// EN 50318 figures of a run and the standard's acceptance ranges.
//
// The figures (order, labels, units) and the ranges by speed live in one data
// file, meshes/en50318-ranges.json, read by the postproc scripts as well; the
// build embeds it in pcsim. A figure is read from a pantograph's entry of
// summary.json ('key'), or from the run's top level ('from', times 'scale').
#pragma once

#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "pcsim/output/statistics.hpp"

namespace pcsim::output {

struct En50318Figure {
  std::string key;    // e.g. "std_N"
  std::string label;  // e.g. "standard deviation sigma"
  std::string unit;   // display unit, e.g. "N", "mm", "%"
  std::string from;   // run-level summary key ("" : the pantograph's 'key')
  double scale = 1;   // display value = scale * summary value
};

struct FigureRange {
  double low = 0, high = 0;
};

struct En50318Reference {
  std::string edition;  // "EN 50318:2002"
  std::vector<En50318Figure> figures;
  std::map<double, std::map<std::string, FigureRange>> ranges;  // speed [km/h] -> key -> range
  // The ranges at this speed (within 0.5 km/h), nullptr where the standard gives none.
  const std::map<std::string, FigureRange>* ranges_at(double speed_kmh) const;
  // "250 and 300 km/h"
  std::string speeds_with_ranges() const;
};

// The embedded meshes/en50318-ranges.json.
const En50318Reference& en50318_reference();

struct AssessedFigure {
  En50318Figure figure;
  double value = 0;  // display unit
  bool has_range = false;
  FigureRange range;
  bool inside = true;  // within the range (bounds included); true without a range
};

// The figures of one pantograph: 'run' is summary.json, 'pantograph' one of its pantographs.
// with_ranges false: the figures without ranges (a run judged against another
// criteria set: pcsim/output/assessment.hpp).
std::vector<AssessedFigure> assess_en50318(const nlohmann::json& run,
                                           const nlohmann::json& pantograph, double speed_kmh,
                                           bool with_ranges = true);

// {"edition", "speed_kmh", "ranges": bool, "figures": [{key, label, unit, value, range, verdict}]};
// "ranges" is false where the standard gives none at this speed or with_ranges is false.
nlohmann::json en50318_json(const std::vector<AssessedFigure>& figures, double speed_kmh,
                            bool with_ranges = true);

// A pantograph's statistics under the keys of summary.json (mean_N, std_N, ...).
nlohmann::json force_statistics_json(const ForceStatistics& statistics);

}  // namespace pcsim::output
