// A run's figures judged against its criteria set (pcsim/core/criteria.hpp,
// docs/assessment.md): the verdict of every criterion of every pantograph,
// for the console, summary.json ('assessment') and report.html.
//
// Verdicts: "pass", "fail" (a sourced criterion), "unverified" (a criterion
// whose value is not sourced: never pass or fail), "no limit" (the set gives
// none here, e.g. EN 50318 at a speed without ranges), "no input" (a bound
// on a scene input the scene does not give, e.g. steady_arm_space_mm).
#pragma once

#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "pcsim/core/criteria.hpp"

namespace pcsim::output {

struct JudgedCriterion {
  Criterion criterion;
  double value = 0;  // the figure, in the criterion's unit
  bool has_low = false, has_high = false;
  double low = 0, high = 0;  // the bounds at this run (speed, Fm, inputs)
  std::string verdict;
};

// The values criteria may bound for one pantograph: its statistics (the keys
// of summary.json: force_statistics_json), uplift_mm from the run's largest
// uplift at a support [m], and the scene's inputs (steady_arm_space_mm).
std::map<std::string, double> criteria_values(const nlohmann::json& pantograph_statistics,
                                              double max_uplift_m, const Assessment& assessment);

// Every criterion of the set judged; speed_kmh: the run's.
std::vector<JudgedCriterion> judge(const Assessment& assessment,
                                   const std::map<std::string, double>& values, double speed_kmh);

// One word for a pantograph: "fail" if any criterion fails, else
// "unverified" if any is unverified, else "pass" if any passes, else "none".
std::string overall_verdict(const std::vector<JudgedCriterion>& judged);

// "110 .. 120", "<= 132.3", "> 0", "" (no limit).
std::string limit_text(const JudgedCriterion& judged);

// summary.json's 'assessment': the set, why it was chosen, the inputs, and
// per pantograph its overall verdict and every criterion (value, bounds,
// verdict, clause, source, sourced, note).
nlohmann::json assessment_json(const Assessment& assessment,
                               const std::map<std::string, std::vector<JudgedCriterion>>& judged);

// summary.json's 'line_zones' (output/line_results.hpp): every complete
// tension section of every pantograph judged against the set as its own
// assessed section ('criteria_verdict' and 'criteria': key, value, limit,
// verdict); overlaps are not judged, the uplift only over the analysis
// section.
void judge_line_zones(const Assessment& assessment, double speed_kmh, nlohmann::json& line_zones);

// The console table of one pantograph (lines, each "\n"-ended, indented 4).
std::string assessment_table(const Assessment& assessment,
                             const std::vector<JudgedCriterion>& judged);

}  // namespace pcsim::output
