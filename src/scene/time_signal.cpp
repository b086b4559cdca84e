#include "pcsim/scene/time_signal.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "pcsim/core/limits.hpp"

namespace pcsim::scene {

namespace {
// Index k of the interval [t_{k-1}, t_k] holding `time` (inside the samples).
std::size_t interval(const std::vector<double>& t, double time) {
  return std::upper_bound(t.begin(), t.end(), time) - t.begin();
}
}  // namespace

double Samples::value(double time) const {
  if (time <= t.front()) return y.front();
  if (time >= t.back()) return y.back();
  const std::size_t k = interval(t, time);
  const double w = (time - t[k - 1]) / (t[k] - t[k - 1]);
  return (1 - w) * y[k - 1] + w * y[k];
}

double Samples::slope(double time) const {
  if (time < t.front() || time >= t.back()) return 0.0;
  const std::size_t k = interval(t, time);
  return (y[k] - y[k - 1]) / (t[k] - t[k - 1]);
}

Samples load_samples(const InputNode& node, const std::string& what) {
  const std::string path = node.get_file_path("file");
  std::ifstream in(path);
  Samples s;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    for (char& c : line)
      if (c == ',') c = ' ';
    std::istringstream ss(line);
    double t, v;
    if (!(ss >> t >> v))
      node.fail_key("file", "bad line '" + line + "' (expected: t, " + what + ")");
    if (!s.t.empty() && t <= s.t.back()) node.fail_key("file", "times must increase");
    s.t.push_back(t);
    s.y.push_back(v);
  }
  if (s.t.empty()) node.fail_key("file", "no samples");
  return s;
}

pantograph::BaseMotion load_base_motion(const InputNode& node) {
  const std::string type = node.get_choice("type", {"harmonic", "file"}, "");
  if (type.empty()) node.fail_key("type", "required key is missing (harmonic or file)");
  if (type == "harmonic") {
    node.allow_only({"type", "amplitude", "frequency_hz"});
    const double a = node.get_positive("amplitude", limits::base_motion),
                 w = 2 * M_PI * node.get_positive("frequency_hz", limits::frequency);
    return {[a, w](double t) { return a * std::sin(w * t); },
            [a, w](double t) { return a * w * std::cos(w * t); }};
  }
  node.allow_only({"type", "file"});
  const Samples s = load_samples(node, "z_b");
  for (double z : s.y)
    if (const std::string why = limit_violation(z, limits::base_motion); !why.empty())
      node.fail_key("file", "base displacement " + why);
  return {[s](double t) { return s.value(t); }, [s](double t) { return s.slope(t); }};
}

void apply_base_motion(const InputNode& entry, pantograph::PantographModel& model) {
  if (!entry.has("base_motion")) return;
  if (model.base_support().dof < 0)
    entry.fail_key("base_motion", "not available for the " + model.kind() +
                                      " pantograph model yet (lumped models only)");
  model.set_base_motion(load_base_motion(entry["base_motion"]));
}

}  // namespace pcsim::scene
