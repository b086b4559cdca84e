#include "pcsim/output/sweep_results.hpp"

#include <cstdio>
#include <fstream>
#include <sstream>

#include "pcsim/output/en50318.hpp"

namespace pcsim::output {

namespace {

using Swept = std::vector<std::pair<std::string, std::vector<std::string>>>;

// One row per pantograph of a case (one row, without figures, for a failed case).
struct Row {
  const SweepCase* c;
  std::string pantograph;
  std::vector<AssessedFigure> figures;
};

std::vector<Row> rows_of(const std::vector<SweepCase>& cases) {
  std::vector<Row> rows;
  for (const auto& c : cases) {
    if (c.status != 0 || !c.summary.is_object()) {
      rows.push_back({&c, "", {}});
      continue;
    }
    const double speed = c.summary.value("speed_kmh", 0.0);
    // EN 50318's ranges only for a case judged against them (docs/assessment.md).
    const auto assessment = c.summary.value("assessment", nlohmann::json::object());
    const bool ranges = assessment.value("criteria", std::string("en50318-2002")) == "en50318-2002";
    for (const auto& p : c.summary.value("pantographs", nlohmann::json::array()))
      rows.push_back({&c, p.value("name", std::string()),
                      p.value("complete", true) ? assess_en50318(c.summary, p, speed, ranges)
                                                : std::vector<AssessedFigure>{}});
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
  s << "\n";
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
    s << "\n";
  }
  return s.str();
}

std::string markdown(const Swept& swept, const std::vector<Row>& rows) {
  std::ostringstream s;
  s << "| case |";
  for (const auto& [key, values] : swept) s << " " << key << " |";
  s << " pantograph | status |";
  for (const auto& f : en50318_reference().figures) s << " " << f.label << " (" << f.unit << ") |";
  s << "\n|";
  for (std::size_t k = 0; k < swept.size() + 3 + en50318_reference().figures.size(); ++k)
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
    s << "\n";
  }
  return s.str();
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

}  // namespace

std::string write_sweep_results(const OutputDir& out, const Swept& swept,
                                const std::vector<SweepCase>& cases, const nlohmann::json& record) {
  const auto rows = rows_of(cases);
  const std::string table = markdown(swept, rows);
  std::ofstream(out.file("sweep.csv")) << csv(swept, rows);
  std::ofstream(out.file("sweep.md")) << table;
  std::ofstream(out.file("summary.json"))
      << summary_json(out, swept, cases, record).dump(2) << "\n";
  return table;
}

}  // namespace pcsim::output
