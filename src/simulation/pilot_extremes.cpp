#include "pcsim/simulation/pilot_extremes.hpp"

#include <cmath>
#include <cstdio>

#include "pcsim/simulation/accuracy_pilot.hpp"

namespace pcsim::simulation {

namespace {

// The stretch [from_x, to_x] of the run's pilot; false where it has none.
bool stretch_in_facts(const nlohmann::json& facts, double& from_x, double& to_x) {
  const auto estimate = facts.find("accuracy_estimate");
  if (estimate == facts.end() || !estimate->is_object()) return false;
  const auto pilot = estimate->find("pilot");
  if (pilot == estimate->end() || !pilot->is_object() || !pilot->contains("from_x") ||
      !pilot->contains("to_x"))
    return false;
  from_x = pilot->at("from_x").get<double>();
  to_x = pilot->at("to_x").get<double>();
  return true;
}

}  // namespace

std::vector<ExtremeOutsidePilot> extremes_outside_pilot(const output::RunStatistics& stats,
                                                        double from_x, double to_x) {
  std::vector<ExtremeOutsidePilot> out;
  // The stretch's ends included, with the section's tolerance for a support:
  // an extreme at a support that ends the stretch is inside.
  constexpr double tol = output::kSupportTolerance;
  const auto outside = [&](double x) { return x < from_x - tol || x > to_x + tol; };
  for (const auto& p : stats.pantographs) {
    if (!p.complete) continue;
    if (outside(p.force.actual_max_x))
      out.push_back({p.name, kActualMaxFigure, p.force.actual_max_x});
    if (outside(p.force.actual_min_x))
      out.push_back({p.name, kActualMinFigure, p.force.actual_min_x});
    // The line's largest uplift at a support: each pantograph's figure (NaN: none rose).
    if (!std::isnan(stats.max_uplift_x) && outside(stats.max_uplift_x))
      out.push_back({p.name, kUpliftFigure, stats.max_uplift_x});
    // The loss of contact: the samples at zero outside the stretch, the first of them.
    ExtremeOutsidePilot loss{p.name, kLossOfContactFigure, 0, 0, p.force.lost_x.size()};
    for (double x : p.force.lost_x)
      if (outside(x) && loss.samples_outside++ == 0) loss.at_x = x;
    if (loss.samples_outside > 0) out.push_back(loss);
  }
  return out;
}

void add_extremes_outside_pilot(const output::RunStatistics& stats, nlohmann::json& facts) {
  double from_x = 0, to_x = 0;
  if (!stretch_in_facts(facts, from_x, to_x)) return;
  nlohmann::json list = nlohmann::json::array();
  for (const auto& e : extremes_outside_pilot(stats, from_x, to_x)) {
    nlohmann::json entry = {
        {"pantograph", e.pantograph}, {"figure", kPilotFigureKeys[e.figure]}, {"at_x_m", e.at_x}};
    if (e.figure == kLossOfContactFigure)
      entry["samples_outside"] = e.samples_outside, entry["samples"] = e.samples;
    list.push_back(entry);
  }
  facts["accuracy_estimate"]["extremes_outside_pilot"] = list;
}

std::string extremes_outside_pilot_text(const nlohmann::json& facts) {
  double from_x = 0, to_x = 0;
  if (!stretch_in_facts(facts, from_x, to_x)) return "";
  const auto& list = facts["accuracy_estimate"].value("extremes_outside_pilot", nlohmann::json());
  std::string text;
  char line[400];
  bool uplift_said = false;  // the line's, once
  for (const auto& e : list) {
    const std::string figure = e["figure"].get<std::string>();
    const bool uplift = figure == kPilotFigureKeys[kUpliftFigure];
    if (uplift && uplift_said) continue;
    uplift_said = uplift_said || uplift;
    const std::string name = "'" + e["pantograph"].get<std::string>() + "'";
    if (figure == kPilotFigureKeys[kLossOfContactFigure]) {
      std::snprintf(line, sizeof line,
                    "  accuracy: the loss of contact of %s has %zu of its %zu samples at zero "
                    "outside the pilot's stretch (x %.0f-%.0f m), the first at x = %.1f m:\n"
                    "    its estimate is from the pilot's spans, not from where they fall "
                    "(docs/fidelity.md, \"Where the extremes fall\")\n",
                    name.c_str(), e["samples_outside"].get<std::size_t>(),
                    e["samples"].get<std::size_t>(), from_x, to_x, e["at_x_m"].get<double>());
      text += line;
      continue;
    }
    const std::string what =
        uplift ? std::string("largest uplift at a support")
               : std::string("actual ") +
                     (figure == kPilotFigureKeys[kActualMaxFigure] ? "maximum" : "minimum") +
                     " of " + name;
    std::snprintf(line, sizeof line,
                  "  accuracy: the %s falls at x = %.1f m, outside the pilot's stretch (x "
                  "%.0f-%.0f m):\n    its estimate is from the pilot's spans, not from where it "
                  "falls (docs/fidelity.md, \"Where the extremes fall\")\n",
                  what.c_str(), e["at_x_m"].get<double>(), from_x, to_x);
    text += line;
  }
  return text;
}

}  // namespace pcsim::simulation
