// Acceptance criteria as data (docs/assessment.md, "Criteria sets").
//
// A criteria set (meshes/criteria/<name>.yaml, or a file a scene names) is a
// list of criteria, each a bound on one figure of a pantograph's contact
// force (or the run's uplift), with the clause and source it comes from. The
// scene reader (scene/criteria_reader.hpp) reads a set and the scene's
// 'assessment' section into these plain types; the output part
// (output/assessment.hpp) judges a run's figures against them.
#pragma once

#include <string>
#include <vector>

namespace pcsim {

// The figures a criterion may bound: a pantograph's statistics (summary.json
// keys), the run's largest uplift at a support in mm, and the scene's inputs.
inline const std::vector<std::string>& criteria_figures() {
  static const std::vector<std::string> figures = {
      "mean_N",   "std_N", "stat_max_N",       "stat_min_N",
      "max_N",    "min_N", "min_unfiltered_N", "loss_of_contact_percent",
      "uplift_mm"};
  return figures;
}

// One side of a criterion: value <= (or >=) bound, where
//   constant:     bound = a
//   speed_curve:  bound = a v^2 + b      (v: the run's speed in km/h)
//   factor:       bound = a * <of>       (another figure, or a scene input)
struct CriterionBound {
  enum class Kind { none, constant, speed_curve, factor } kind = Kind::none;
  double a = 0, b = 0;
  std::string of;       // factor: the figure or input it multiplies
  bool strict = false;  // < or > instead of <= or >=
};

struct Criterion {
  std::string key;     // e.g. "mean_force"
  std::string figure;  // one of criteria_figures()
  std::string label, unit;
  std::string clause;   // e.g. "EN 50318:2002, Table ..."
  std::string source;   // where the value was read
  std::string note;     // what is uncertain or approximated
  bool sourced = true;  // false: verdicts are "unverified", never pass or fail
  CriterionBound lower, upper;
};

struct CriteriaSet {
  std::string name;   // "en50367-ac", or the file's name
  std::string title;  // "EN 50367 / TSI Energy, AC lines"
  std::string file;   // where it was read ("built-in meshes/criteria/<name>.yaml" or a path)
  std::string scope;  // what the set is for (printed)
  std::vector<std::string> electrification;  // the systems it is written for (empty: any)
  std::vector<Criterion> criteria;
};

// A run scene's 'assessment' section, resolved: the set and the inputs.
struct Assessment {
  CriteriaSet set;
  std::string choice;              // why this set: "scene" or the default rule's reason
  std::string electrification;     // "AC", "DC3kV", "DC1.5kV"
  double line_speed_kmh = 0;       // default: the run's speed
  double steady_arm_space_mm = 0;  // 0: not given
};

}  // namespace pcsim
