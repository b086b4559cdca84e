#include "pcsim/output/en50318.hpp"

#include <cmath>
#include <sstream>

namespace pcsim::output {

extern const char* const kEn50318RangesJson;  // generated from meshes/en50318-ranges.json

namespace {

En50318Reference parse_reference() {
  const auto j = nlohmann::json::parse(kEn50318RangesJson);
  En50318Reference r;
  r.edition = j.at("edition").get<std::string>();
  for (const auto& f : j.at("figures")) {
    En50318Figure figure;
    figure.key = f.at("key").get<std::string>();
    figure.label = f.at("label").get<std::string>();
    figure.unit = f.at("unit").get<std::string>();
    figure.from = f.value("from", std::string());
    figure.scale = f.value("scale", 1.0);
    r.figures.push_back(figure);
  }
  for (const auto& [speed, figures] : j.at("ranges_by_speed_kmh").items()) {
    auto& ranges = r.ranges[std::stod(speed)];
    for (const auto& [key, range] : figures.items())
      ranges[key] = {range.at(0).get<double>(), range.at(1).get<double>()};
  }
  return r;
}

}  // namespace

const std::map<std::string, FigureRange>* En50318Reference::ranges_at(double speed_kmh) const {
  for (const auto& [speed, figures] : ranges)
    if (std::abs(speed - speed_kmh) < 0.5) return &figures;
  return nullptr;
}

std::string En50318Reference::speeds_with_ranges() const {
  std::ostringstream s;
  std::size_t k = 0;
  for (const auto& entry : ranges) {
    if (k > 0) s << (k + 1 == ranges.size() ? " and " : ", ");
    s << entry.first;
    ++k;
  }
  s << " km/h";
  return s.str();
}

const En50318Reference& en50318_reference() {
  static const En50318Reference reference = parse_reference();
  return reference;
}

std::vector<AssessedFigure> assess_en50318(const nlohmann::json& run,
                                           const nlohmann::json& pantograph, double speed_kmh,
                                           bool with_ranges) {
  const auto& reference = en50318_reference();
  const auto* ranges = with_ranges ? reference.ranges_at(speed_kmh) : nullptr;
  std::vector<AssessedFigure> out;
  for (const auto& figure : reference.figures) {
    const auto& source = figure.from.empty() ? pantograph : run;
    const std::string& key = figure.from.empty() ? figure.key : figure.from;
    if (!source.contains(key)) continue;
    AssessedFigure a;
    a.figure = figure;
    a.value = figure.scale * source.at(key).get<double>();
    if (ranges && ranges->count(figure.key)) {
      a.has_range = true;
      a.range = ranges->at(figure.key);
      // Bounds included; 1e-9 absorbs the round-off of an exact bound (0 % loss of contact).
      a.inside = a.value >= a.range.low - 1e-9 && a.value <= a.range.high + 1e-9;
    }
    out.push_back(a);
  }
  return out;
}

nlohmann::json en50318_json(const std::vector<AssessedFigure>& figures, double speed_kmh,
                            bool with_ranges) {
  const auto& reference = en50318_reference();
  nlohmann::json j = {{"edition", reference.edition},
                      {"speed_kmh", speed_kmh},
                      {"ranges", with_ranges && reference.ranges_at(speed_kmh) != nullptr},
                      {"figures", nlohmann::json::array()}};
  for (const auto& a : figures) {
    nlohmann::json f = {{"key", a.figure.key},
                        {"label", a.figure.label},
                        {"unit", a.figure.unit},
                        {"value", a.value}};
    if (a.has_range) {
      f["range"] = {a.range.low, a.range.high};
      f["verdict"] = a.inside ? "pass" : "fail";
    }
    j["figures"].push_back(f);
  }
  return j;
}

nlohmann::json force_statistics_json(const ForceStatistics& st) {
  return {{"mean_N", st.mean},
          {"std_N", st.std_dev},
          {"stat_max_N", st.statistical_max},
          {"stat_min_N", st.statistical_min},
          {"max_N", st.actual_max},
          {"min_N", st.actual_min},
          {"max_at_x_m", st.actual_max_x},
          {"min_at_x_m", st.actual_min_x},
          {"min_unfiltered_N", st.unfiltered_min},
          {"loss_of_contact_percent", st.loss_of_contact_percent},
          {"samples", st.samples}};
}

}  // namespace pcsim::output
