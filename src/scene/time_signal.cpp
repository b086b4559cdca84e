#include "pcsim/scene/time_signal.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <memory>
#include <random>
#include <sstream>

#include "pcsim/core/cubic_spline.hpp"
#include "pcsim/core/limits.hpp"
#include "pcsim/core/random.hpp"

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

namespace {

// The frequencies f_k (strictly increasing, > 0) and one-sided PSD S_k >= 0
// [m^2/Hz] of a `type: psd` node, checked.
void read_psd_table(const InputNode& node, std::vector<double>& f, std::vector<double>& s) {
  f = node["frequency_hz"].as_doubles();
  s = node["psd"].as_doubles();
  if (f.size() < 2) node.fail_key("frequency_hz", "needs at least two frequencies");
  if (s.size() != f.size())
    node.fail_key("psd", "needs one value per frequency (" + std::to_string(f.size()) + "), has " +
                             std::to_string(s.size()));
  for (std::size_t k = 0; k < f.size(); ++k) {
    if (const std::string why = limit_violation(f[k], limits::frequency); !why.empty())
      node.fail_key("frequency_hz", why);
    if (k > 0 && f[k] <= f[k - 1]) node.fail_key("frequency_hz", "frequencies must increase");
    if (!(s[k] >= 0) || s[k] > 1.0)
      node.fail_key("psd", "values must lie in [0, 1] m^2/Hz (roof motion ~1e-8 .. 1e-4)");
  }
}

// z_b(t) = sum_n a_n cos(2 pi f_n t + phi_n): the spectral representation of
// a one-sided PSD S(f) [m^2/Hz] given at points (linear between them, 0
// outside), n = 1..N at the centres f_n of N equal bins of width df over
// [f_first, f_last], a_n = sqrt(2 S(f_n) df) (so that the variance, the sum
// of a_n^2 / 2, is the PSD's integral by the midpoint rule), phases uniform
// in [0, 2 pi) from the seed. Its lines are df apart: a record longer than
// 1 / df (the default 1024 bins over 1-20 Hz: 54 s) resolves them.
pantograph::BaseMotion psd_base_motion(const InputNode& node) {
  node.allow_only({"type", "frequency_hz", "psd", "seed", "components"});
  std::vector<double> f, s;
  read_psd_table(node, f, s);
  const long count = node.get_int("components", 1024);
  if (count < 1 || count > 100000) node.fail_key("components", "must lie in 1 .. 100000");
  const long seed = node.get_int("seed", 1);
  if (seed < 0) node.fail_key("seed", "must not be negative");
  std::mt19937_64 gen(static_cast<std::mt19937_64::result_type>(seed));
  const double df = (f.back() - f.front()) / static_cast<double>(count);
  Samples table{f, s};
  std::vector<double> omega, amplitude, phase;
  double variance = 0;
  for (long n = 0; n < count; ++n) {
    const double fn = f.front() + (static_cast<double>(n) + 0.5) * df;
    omega.push_back(2 * M_PI * fn);
    amplitude.push_back(std::sqrt(2 * table.value(fn) * df));
    phase.push_back(2 * M_PI * unit_random(gen));
    variance += 0.5 * amplitude.back() * amplitude.back();
  }
  if (const std::string why = limit_violation(std::sqrt(variance), limits::base_motion);
      !why.empty())
    node.fail_key("psd", "the motion's standard deviation " + why);
  auto z = [omega, amplitude, phase](double t) {
    double sum = 0;
    for (std::size_t n = 0; n < omega.size(); ++n)
      sum += amplitude[n] * std::cos(omega[n] * t + phase[n]);
    return sum;
  };
  auto v = [omega, amplitude, phase](double t) {
    double sum = 0;
    for (std::size_t n = 0; n < omega.size(); ++n)
      sum -= amplitude[n] * omega[n] * std::sin(omega[n] * t + phase[n]);
    return sum;
  };
  auto a = [omega, amplitude, phase](double t) {
    double sum = 0;
    for (std::size_t n = 0; n < omega.size(); ++n)
      sum -= amplitude[n] * omega[n] * omega[n] * std::cos(omega[n] * t + phase[n]);
    return sum;
  };
  return {z, v, a};
}

}  // namespace

pantograph::BaseMotion load_base_motion(const InputNode& node, bool moving_frame) {
  const std::string type = node.get_choice("type", {"harmonic", "file", "psd"}, "");
  if (type.empty()) node.fail_key("type", "required key is missing (harmonic, file or psd)");
  if (type == "psd") return psd_base_motion(node);
  if (type == "harmonic") {
    node.allow_only({"type", "amplitude", "frequency_hz"});
    const double a = node.get_positive("amplitude", limits::base_motion);
    return pantograph::harmonic_base_motion(a,
                                            node.get_positive("frequency_hz", limits::frequency));
  }
  node.allow_only({"type", "file", "interpolation"});
  const std::string interpolation =
      node.get_choice("interpolation", {"linear", "cubic"}, moving_frame ? "cubic" : "linear");
  if (moving_frame && interpolation == "linear")
    node.fail_key("interpolation",
                  "'linear' is not available for a moving-frame (DSA-380) pantograph model: it "
                  "needs the base's acceleration, which a piecewise-linear z_b lacks (use cubic, "
                  "the default for these models)");
  Samples s = load_samples(node, "z_b");
  for (double z : s.y)
    if (const std::string why = limit_violation(z, limits::base_motion); !why.empty())
      node.fail_key("file", "base displacement " + why);
  if (interpolation == "cubic") {  // C2: z_b, v_b and a_b of a natural cubic spline
    auto spline = std::make_shared<const NaturalCubicSpline>(std::move(s.t), std::move(s.y));
    return {[spline](double t) { return spline->value(t); },
            [spline](double t) { return spline->slope(t); },
            [spline](double t) { return spline->second_derivative(t); }};
  }
  // No acceleration: a piecewise-linear z_b's is a train of impulses.
  return {[s](double t) { return s.value(t); }, [s](double t) { return s.slope(t); }, {}};
}

void apply_base_motion(const InputNode& entry, pantograph::PantographModel& model) {
  if (!entry.has("base_motion")) return;
  if (model.base_support().dof < 0 && !model.moving_frame())
    entry.fail_key("base_motion", "not available for the " + model.kind() +
                                      " pantograph model yet (lumped and DSA-380 models only)");
  model.set_base_motion(load_base_motion(entry["base_motion"], model.moving_frame()));
}

}  // namespace pcsim::scene
