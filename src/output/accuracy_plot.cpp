// The accuracy study's plot (accuracy_study.hpp) as SVG: worst error of the
// EN 50318 figures against ms per step, both logarithmic, one colour per
// fidelity, the Pareto front joined.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>

#include "pcsim/output/accuracy_study.hpp"

namespace pcsim::output {

namespace {

constexpr double kWidth = 760, kHeight = 500, kLeft = 80, kRight = 180, kTop = 30, kBottom = 60;

struct LogAxis {
  double lo, hi;  // decades
  double map(double v, double from, double to) const {
    return from + (std::log10(v) - lo) / (hi - lo) * (to - from);
  }
};

LogAxis axis(const std::vector<double>& values) {
  double lo = 1e300, hi = -1e300;
  for (double v : values) lo = std::min(lo, v), hi = std::max(hi, v);
  return {std::floor(std::log10(lo)),
          std::max(std::ceil(std::log10(hi)), std::floor(std::log10(lo)) + 1)};
}

const char* colour(const std::string& model) {
  static const std::map<std::string, const char*> colours = {
      {"nonlinear", "#d62728"}, {"linear", "#1f77b4"}, {"modal", "#2ca02c"}};
  auto it = colours.find(model);
  return it == colours.end() ? "#7f7f7f" : it->second;
}

void grid(std::ofstream& f, const LogAxis& x, const LogAxis& y) {
  char line[256];
  for (int d = static_cast<int>(x.lo); d <= static_cast<int>(x.hi); ++d) {
    const double px = x.map(std::pow(10.0, d), kLeft, kWidth - kRight);
    std::snprintf(line, sizeof(line),
                  "<line x1='%.1f' y1='%.1f' x2='%.1f' y2='%.1f' stroke='#ddd'/>"
                  "<text x='%.1f' y='%.1f' text-anchor='middle'>%g</text>\n",
                  px, kTop, px, kHeight - kBottom, px, kHeight - kBottom + 18, std::pow(10.0, d));
    f << line;
  }
  for (int d = static_cast<int>(y.lo); d <= static_cast<int>(y.hi); ++d) {
    const double py = y.map(std::pow(10.0, d), kHeight - kBottom, kTop);
    std::snprintf(line, sizeof(line),
                  "<line x1='%.1f' y1='%.1f' x2='%.1f' y2='%.1f' stroke='#ddd'/>"
                  "<text x='%.1f' y='%.1f' text-anchor='end'>%g</text>\n",
                  kLeft, py, kWidth - kRight, py, kLeft - 6, py + 4, std::pow(10.0, d));
    f << line;
  }
}

}  // namespace

void write_accuracy_svg(const std::string& path, const StudyTable& t) {
  constexpr double kFloor = 0.01;  // [%] errors below are drawn at the floor
  std::vector<std::size_t> shown;
  std::vector<double> xs, ys;
  for (std::size_t i = 0; i < t.runs.size(); ++i)
    if (t.errors[i].valid && static_cast<int>(i) != t.reference && t.runs[i].ms_per_step > 0) {
      shown.push_back(i);
      xs.push_back(t.runs[i].ms_per_step);
      ys.push_back(std::max(t.errors[i].worst, kFloor));
    }
  std::ofstream f(path);
  f << "<svg xmlns='http://www.w3.org/2000/svg' width='" << kWidth << "' height='" << kHeight
    << "' font-family='sans-serif' font-size='11'>\n<rect width='100%' height='100%' "
       "fill='white'/>\n";
  if (shown.empty()) {
    f << "<text x='20' y='40'>no run to compare with the reference</text>\n</svg>\n";
    return;
  }
  const LogAxis x = axis(xs), y = axis(ys);
  grid(f, x, y);
  char buffer[512];
  std::snprintf(buffer, sizeof(buffer),
                "<text x='%.1f' y='%.1f' text-anchor='middle'>cost [ms per time step]</text>\n"
                "<text transform='translate(20,%.1f) rotate(-90)' text-anchor='middle'>worst "
                "error of the EN 50318 figures [%%]</text>\n",
                (kLeft + kWidth - kRight) / 2, kHeight - 15, (kTop + kHeight - kBottom) / 2);
  f << buffer;
  std::vector<std::pair<double, double>> front;
  for (std::size_t k = 0; k < shown.size(); ++k) {
    const auto& r = t.runs[shown[k]];
    const double px = x.map(xs[k], kLeft, kWidth - kRight),
                 py = y.map(ys[k], kHeight - kBottom, kTop);
    if (t.pareto[shown[k]]) front.emplace_back(px, py);
    std::snprintf(buffer, sizeof(buffer),
                  "<circle cx='%.1f' cy='%.1f' r='%d' fill='%s' stroke='black' stroke-width='%g'>"
                  "<title>%s</title></circle>\n",
                  px, py, t.pareto[shown[k]] ? 6 : 4, colour(r.model),
                  t.pareto[shown[k]] ? 1.5 : 0.3, r.label().c_str());
    f << buffer;
    if (t.pareto[shown[k]]) {  // the front's runs named on the plot
      std::snprintf(buffer, sizeof(buffer), "<text x='%.1f' y='%.1f' font-size='9'>%s</text>\n",
                    px + 8, py - 6, r.label().c_str());
      f << buffer;
    }
  }
  std::sort(front.begin(), front.end());
  f << "<polyline fill='none' stroke='black' stroke-dasharray='4,3' points='";
  for (const auto& [px, py] : front) f << px << ',' << py << ' ';
  f << "'/>\n";
  double legend = kTop + 10;
  for (const char* model : {"nonlinear", "linear", "modal"}) {
    std::snprintf(
        buffer, sizeof(buffer),
        "<circle cx='%.1f' cy='%.1f' r='5' fill='%s'/><text x='%.1f' y='%.1f'>%s</text>\n",
        kWidth - kRight + 20, legend, colour(model), kWidth - kRight + 32, legend + 4, model);
    f << buffer;
    legend += 18;
  }
  std::snprintf(buffer, sizeof(buffer),
                "<line x1='%.1f' y1='%.1f' x2='%.1f' y2='%.1f' stroke='black' "
                "stroke-dasharray='4,3'/><text x='%.1f' y='%.1f'>Pareto front</text>\n</svg>\n",
                kWidth - kRight + 12, legend, kWidth - kRight + 28, legend, kWidth - kRight + 32,
                legend + 4);
  f << buffer;
}

}  // namespace pcsim::output
