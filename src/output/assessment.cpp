#include "pcsim/output/assessment.hpp"

#include <cstdio>

namespace pcsim::output {

namespace {

// Bounds included (strict: excluded); 1e-9 absorbs the round-off of an exact
// bound (0 % loss of contact), as the EN 50318 ranges always did.
constexpr double kTolerance = 1e-9;

// The bound's value at this run, false where an input it needs is missing.
bool bound_value(const CriterionBound& b, const std::map<std::string, double>& values,
                 double speed_kmh, double& out) {
  switch (b.kind) {
    case CriterionBound::Kind::constant:
      out = b.a;
      return true;
    case CriterionBound::Kind::speed_curve:
      out = b.a * speed_kmh * speed_kmh + b.b;
      return true;
    case CriterionBound::Kind::factor: {
      const auto it = values.find(b.of);
      if (it == values.end() || it->second <= 0) return false;
      out = b.a * it->second;
      return true;
    }
    case CriterionBound::Kind::none:
      break;
  }
  return false;
}

bool inside(const JudgedCriterion& j) {
  const auto& c = j.criterion;
  if (j.has_low && (c.lower.strict ? !(j.value > j.low) : j.value < j.low - kTolerance))
    return false;
  if (j.has_high && (c.upper.strict ? !(j.value < j.high) : j.value > j.high + kTolerance))
    return false;
  return true;
}

std::string number(double v) {
  char s[32];
  std::snprintf(s, sizeof s, "%.4g", v);
  return s;
}

const char* shown(const std::string& verdict) {
  if (verdict == "fail") return "FAIL";
  return verdict.c_str();
}

}  // namespace

std::map<std::string, double> criteria_values(const nlohmann::json& pantograph_statistics,
                                              double max_uplift_m, const Assessment& assessment) {
  std::map<std::string, double> values;
  for (const auto& [key, value] : pantograph_statistics.items())
    if (value.is_number()) values[key] = value.get<double>();
  values["uplift_mm"] = 1000.0 * max_uplift_m;
  if (assessment.steady_arm_space_mm > 0)
    values["steady_arm_space_mm"] = assessment.steady_arm_space_mm;
  return values;
}

std::vector<JudgedCriterion> judge(const Assessment& assessment,
                                   const std::map<std::string, double>& values, double speed_kmh) {
  std::vector<JudgedCriterion> out;
  for (const auto& c : assessment.set.criteria) {
    const auto it = values.find(c.figure);
    if (it == values.end()) continue;
    JudgedCriterion j;
    j.criterion = c;
    j.value = it->second;
    const bool lower_given = c.lower.kind != CriterionBound::Kind::none;
    const bool upper_given = c.upper.kind != CriterionBound::Kind::none;
    j.has_low = lower_given && bound_value(c.lower, values, speed_kmh, j.low);
    j.has_high = upper_given && bound_value(c.upper, values, speed_kmh, j.high);
    if ((lower_given && !j.has_low) || (upper_given && !j.has_high))
      j.verdict = "no input";
    else if (!j.has_low && !j.has_high)
      j.verdict = "no limit";
    else if (!c.sourced)
      j.verdict = "unverified";
    else
      j.verdict = inside(j) ? "pass" : "fail";
    out.push_back(j);
  }
  return out;
}

std::string overall_verdict(const std::vector<JudgedCriterion>& judged) {
  bool unverified = false, passed = false;
  for (const auto& j : judged) {
    if (j.verdict == "fail") return "fail";
    unverified = unverified || j.verdict == "unverified";
    passed = passed || j.verdict == "pass";
  }
  return unverified ? "unverified" : passed ? "pass" : "none";
}

std::string limit_text(const JudgedCriterion& j) {
  if (j.has_low && j.has_high) return number(j.low) + " .. " + number(j.high);
  if (j.has_high) return (j.criterion.upper.strict ? "< " : "<= ") + number(j.high);
  if (j.has_low) return (j.criterion.lower.strict ? "> " : ">= ") + number(j.low);
  return "";
}

nlohmann::json assessment_json(const Assessment& a,
                               const std::map<std::string, std::vector<JudgedCriterion>>& judged) {
  nlohmann::json j = {{"criteria", a.set.name},
                      {"title", a.set.title},
                      {"file", a.set.file},
                      {"scope", a.set.scope},
                      {"choice", a.choice},
                      {"electrification", a.electrification},
                      {"line_speed_kmh", a.line_speed_kmh},
                      {"pantographs", nlohmann::json::object()}};
  if (a.steady_arm_space_mm > 0) j["steady_arm_space_mm"] = a.steady_arm_space_mm;
  for (const auto& [name, list] : judged) {
    nlohmann::json p = {{"verdict", overall_verdict(list)}, {"criteria", nlohmann::json::array()}};
    for (const auto& c : list) {
      nlohmann::json f = {{"key", c.criterion.key},
                          {"figure", c.criterion.figure},
                          {"label", c.criterion.label},
                          {"unit", c.criterion.unit},
                          {"value", c.value},
                          {"limit", limit_text(c)},
                          {"verdict", c.verdict},
                          {"clause", c.criterion.clause},
                          {"source", c.criterion.source},
                          {"sourced", c.criterion.sourced}};
      if (c.has_low) f["low"] = c.low;
      if (c.has_high) f["high"] = c.high;
      if (!c.criterion.note.empty()) f["note"] = c.criterion.note;
      p["criteria"].push_back(f);
    }
    j["pantographs"][name] = p;
  }
  return j;
}

std::string assessment_table(const Assessment& a, const std::vector<JudgedCriterion>& judged) {
  std::string out;
  char line[512];
  std::snprintf(line, sizeof line, "    %-32s %-4s %9s  %14s  %-10s  %s\n", "figure", "unit",
                "value", "limit", "verdict", "clause");
  out += line;
  for (const auto& j : judged) {
    std::snprintf(line, sizeof line, "    %-32s %-4s %9.2f  %14s  %-10s  %s\n",
                  j.criterion.label.c_str(), j.criterion.unit.c_str(), j.value,
                  limit_text(j).c_str(), shown(j.verdict), j.criterion.clause.c_str());
    out += line;
  }
  std::snprintf(line, sizeof line, "    overall: %s (criteria set %s)\n",
                shown(overall_verdict(judged)), a.set.name.c_str());
  return out + line;
}

// Each complete tension section (not the overlaps) of every pantograph:
// its statistics against the set, the uplift judged over the analysis
// section only (the zones have no support uplift of their own).
void judge_line_zones(const Assessment& a, double speed_kmh, nlohmann::json& line_zones) {
  for (auto& pantograph : line_zones)
    for (auto& zone : pantograph["zones"]) {
      if (!zone.value("complete", false) || zone.value("overlap", false)) continue;
      auto values = criteria_values(zone, 0.0, a);
      values.erase("uplift_mm");
      const auto judged = judge(a, values, speed_kmh);
      zone["criteria_verdict"] = overall_verdict(judged);
      nlohmann::json list = nlohmann::json::array();
      for (const auto& c : judged)
        list.push_back({{"key", c.criterion.key},
                        {"value", c.value},
                        {"limit", limit_text(c)},
                        {"verdict", c.verdict}});
      zone["criteria"] = list;
    }
}

}  // namespace pcsim::output
