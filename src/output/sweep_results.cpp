#include "pcsim/output/sweep_results.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "pcsim/core/error.hpp"
#include "pcsim/output/en50318.hpp"
#include "pcsim/output/h5_file.hpp"

namespace pcsim::output {

namespace {

using Swept = std::vector<std::pair<std::string, std::vector<std::string>>>;

// One row per pantograph of a case (one row, without figures, for a failed case).
struct Row {
  const SweepCase* c;
  std::string pantograph;
  std::vector<AssessedFigure> figures;
  std::string criteria, verdict;  // the case's criteria set and its overall verdict
};

std::vector<Row> rows_of(const std::vector<SweepCase>& cases) {
  std::vector<Row> rows;
  for (const auto& c : cases) {
    if (c.status != 0 || !c.summary.is_object()) {
      rows.push_back({&c, "", {}, "", ""});
      continue;
    }
    const double speed = c.summary.value("speed_kmh", 0.0);
    // EN 50318's ranges only for a case judged against them (docs/assessment.md).
    const auto assessment = c.summary.value("assessment", nlohmann::json::object());
    const bool ranges = assessment.value("criteria", std::string("en50318-2002")) == "en50318-2002";
    const std::string set = assessment.value("criteria", std::string());
    const auto judged = assessment.value("pantographs", nlohmann::json::object());
    for (const auto& p : c.summary.value("pantographs", nlohmann::json::array())) {
      const std::string name = p.value("name", std::string());
      const auto it = judged.find(name);
      const std::string verdict =
          it != judged.end() ? it->value("verdict", std::string()) : std::string();
      rows.push_back({&c, name,
                      p.value("complete", true) ? assess_en50318(c.summary, p, speed, ranges)
                                                : std::vector<AssessedFigure>{},
                      set, verdict});
    }
  }
  return rows;
}

std::string number(double v) {
  char s[32];
  std::snprintf(s, sizeof s, "%.6g", v);
  return s;
}

std::string status_text(const Row& r) {
  if (r.c->status != 0) return "failed (exit " + std::to_string(r.c->status) + ")";
  return r.figures.empty() ? "no statistics" : "ok";
}

std::string csv(const Swept& swept, const std::vector<Row>& rows) {
  std::ostringstream s;
  s << "case";
  for (const auto& [key, values] : swept) s << "," << key;
  s << ",pantograph,status,speed_kmh";
  for (const auto& f : en50318_reference().figures) s << "," << f.key << "," << f.key << "_verdict";
  s << ",criteria,criteria_verdict\n";
  for (const auto& r : rows) {
    s << r.c->name;
    for (const auto& v : r.c->values) s << "," << v.second;
    s << "," << r.pantograph << "," << status_text(r) << ",";
    if (r.c->summary.is_object()) s << number(r.c->summary.value("speed_kmh", 0.0));
    for (const auto& f : en50318_reference().figures) {
      const AssessedFigure* a = nullptr;
      for (const auto& x : r.figures)
        if (x.figure.key == f.key) a = &x;
      s << "," << (a ? number(a->value) : "") << ","
        << (a && a->has_range ? (a->inside ? "pass" : "fail") : "");
    }
    s << "," << r.criteria << "," << r.verdict << "\n";
  }
  return s.str();
}

std::string markdown(const Swept& swept, const std::vector<Row>& rows) {
  std::ostringstream s;
  s << "| case |";
  for (const auto& [key, values] : swept) s << " " << key << " |";
  s << " pantograph | status |";
  for (const auto& f : en50318_reference().figures) s << " " << f.label << " (" << f.unit << ") |";
  s << " criteria: verdict |\n|";
  for (std::size_t k = 0; k < swept.size() + 4 + en50318_reference().figures.size(); ++k)
    s << "---|";
  s << "\n";
  for (const auto& r : rows) {
    s << "| " << r.c->name << " |";
    for (const auto& v : r.c->values) s << " " << v.second << " |";
    s << " " << r.pantograph << " | " << status_text(r) << " |";
    for (const auto& f : en50318_reference().figures) {
      std::string cell;
      for (const auto& a : r.figures)
        if (a.figure.key == f.key)
          cell = number(a.value) + (a.has_range ? (a.inside ? " pass" : " **fail**") : "");
      s << " " << cell << " |";
    }
    s << " " << (r.criteria.empty() ? "" : r.criteria + ": ")
      << (r.verdict == "fail" ? "**fail**" : r.verdict) << " |\n";
  }
  return s.str();
}

// Per pantograph, the highest swept speed up to which every case passes its
// criteria set (every case at that speed or below: pass), when the cases
// run at two speeds or more; null where the lowest speed does not pass.
nlohmann::json highest_passing_speeds(const std::vector<Row>& rows) {
  std::map<std::string, std::map<double, bool>> passes;  // pantograph -> speed -> all pass
  std::set<double> speeds;
  for (const auto& r : rows) {
    if (r.pantograph.empty()) continue;
    const double v = r.c->summary.value("speed_kmh", 0.0);
    speeds.insert(v);
    auto [it, fresh] = passes[r.pantograph].emplace(v, true);
    it->second = it->second && r.verdict == "pass";
  }
  if (speeds.size() < 2) return nullptr;
  nlohmann::json j = nlohmann::json::object();
  for (const auto& [pantograph, by_speed] : passes) {
    nlohmann::json highest = nullptr;
    for (const auto& [v, pass] : by_speed) {
      if (!pass) break;
      highest = v;
    }
    j[pantograph] = highest;
  }
  return j;
}

std::string speed_line(const nlohmann::json& highest) {
  if (highest.is_null()) return "";
  std::string s = "\nHighest speed up to which every case passes its criteria set:";
  for (const auto& [pantograph, v] : highest.items())
    s += " " + pantograph + " " +
         (v.is_null() ? std::string("none") : number(v.get<double>()) + " km/h") + ";";
  s.back() = '\n';
  return s;
}

nlohmann::json summary_json(const OutputDir& out, const Swept& swept,
                            const std::vector<SweepCase>& cases, const nlohmann::json& record) {
  nlohmann::json j = record.is_object() ? record : nlohmann::json::object();
  j["swept"] = nlohmann::json::object();
  for (const auto& [key, values] : swept) j["swept"][key] = values;
  j["cases"] = nlohmann::json::array();
  for (const auto& c : cases) {
    nlohmann::json values = nlohmann::json::object();
    for (const auto& [key, value] : c.values) values[key] = value;
    nlohmann::json summary = c.summary;
    if (summary.is_object()) summary.erase("provenance");  // in cases/<case>/summary.json
    j["cases"].push_back({{"name", c.name},
                          {"values", values},
                          {"status", c.status},
                          {"error", c.error},
                          {"wall_s", c.wall_s},
                          {"cpu_s", c.cpu_s},
                          {"summary", summary}});
  }
  const auto& reference = en50318_reference();
  j["en50318"] = {{"edition", reference.edition}, {"figures", nlohmann::json::array()}};
  for (const auto& f : reference.figures)
    j["en50318"]["figures"].push_back({{"key", f.key}, {"label", f.label}, {"unit", f.unit}});
  j["provenance"] = out.provenance();
  return j;
}

// A swept key as an HDF5 dataset name (no '/').
std::string dataset_name(std::string key) {
  for (char& c : key)
    if (c == '/') c = '_';
  return key;
}

// The figures of one column: value (NaN where none) and verdict of each row.
void write_figure_columns(H5File& h5, const En50318Figure& f, const std::vector<Row>& rows) {
  std::vector<double> values;
  std::vector<std::string> verdicts;
  for (const auto& r : rows) {
    const AssessedFigure* a = nullptr;
    for (const auto& x : r.figures)
      if (x.figure.key == f.key) a = &x;
    values.push_back(a ? a->value : std::nan(""));
    verdicts.push_back(a && a->has_range ? (a->inside ? "pass" : "fail") : "");
  }
  h5.write("/figures/" + f.key, values, DatasetInfo(f.unit, f.label + " (NaN: none)"));
  h5.write_strings("/verdicts/" + f.key, verdicts,
                   DatasetInfo("none", f.label + ": pass, fail or empty (no range)"));
}

void write_h5_table(const std::string& file, const Swept& swept, const std::vector<Row>& rows) {
  H5File h5(file);
  std::vector<std::string> names, pantographs, statuses, errors;
  std::vector<long> exit_statuses;
  std::vector<double> speeds;
  for (const auto& r : rows) {
    names.push_back(r.c->name);
    pantographs.push_back(r.pantograph);
    statuses.push_back(status_text(r));
    exit_statuses.push_back(r.c->status);
    errors.push_back(r.c->error);
    speeds.push_back(r.c->summary.is_object() ? r.c->summary.value("speed_kmh", 0.0)
                                              : std::nan(""));
  }
  h5.write_strings("/case", names, DatasetInfo("none", "case (its folder under cases/)"));
  for (std::size_t i = 0; i < swept.size(); ++i) {
    std::vector<std::string> values;
    for (const auto& r : rows) values.push_back(r.c->values[i].second);
    h5.write_strings("/values/" + dataset_name(swept[i].first), values,
                     DatasetInfo("none", "the case's value of scene key " + swept[i].first));
  }
  h5.write_strings("/pantograph", pantographs, DatasetInfo("none", "pantograph of the row"));
  h5.write_strings("/status", statuses, DatasetInfo("none", "ok, no statistics or failed"));
  h5.write_int("/exit_status", exit_statuses, DatasetInfo("1", "exit status of the case's run"));
  h5.write_strings("/error", errors, DatasetInfo("none", "a failed case's error"));
  h5.write("/speed_kmh", speeds, DatasetInfo("km/h", "train speed (NaN: failed case)"));
  std::vector<std::string> sets, verdicts;
  for (const auto& r : rows) sets.push_back(r.criteria), verdicts.push_back(r.verdict);
  h5.write_strings("/criteria", sets, DatasetInfo("none", "the case's criteria set"));
  h5.write_strings("/criteria_verdict", verdicts,
                   DatasetInfo("none", "overall verdict under it: pass, fail, unverified, none"));
  for (const auto& f : en50318_reference().figures) write_figure_columns(h5, f, rows);
  h5.close();
}

}  // namespace

std::string write_sweep_results(const OutputDir& out, const Swept& swept,
                                const std::vector<SweepCase>& cases, const nlohmann::json& record) {
  const auto rows = rows_of(cases);
  const nlohmann::json highest = highest_passing_speeds(rows);
  const std::string table = markdown(swept, rows) + speed_line(highest);
  std::ofstream(out.file("sweep.csv")) << csv(swept, rows);
  std::ofstream(out.file("sweep.md")) << table;
  nlohmann::json summary = summary_json(out, swept, cases, record);
  summary["highest_passing_speed_kmh"] = highest;
  std::ofstream(out.file("summary.json")) << summary.dump(2) << "\n";
  // sweep.h5 whole or not at all: written under another name, then renamed.
  const std::string h5 = out.file(kSweepH5Name), tmp = h5 + ".tmp";
  write_h5_table(tmp, swept, rows);
  if (std::rename(tmp.c_str(), h5.c_str()) != 0) throw OutputError(h5, std::strerror(errno));
  return table;
}

}  // namespace pcsim::output
