// Zero-phase Butterworth filtering and EN 50318 contact-force statistics.
#include "pcsim/output/statistics.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace pcsim::output {

std::vector<Biquad> butterworth_lowpass(int order, double cutoff_hz, double sample_rate_hz) {
  if (order < 2 || order > 8 || order % 2 != 0)
    throw std::invalid_argument("butterworth_lowpass: order must be even, 2..8, got " +
                                std::to_string(order));
  if (!(sample_rate_hz > 0) || !(cutoff_hz > 0) || !(cutoff_hz < 0.5 * sample_rate_hz))
    throw std::invalid_argument("butterworth_lowpass: need 0 < cutoff < sample_rate/2");
  // Pre-warped analog cut-off (bilinear transform with T = 1/fs normalised away).
  const double k = std::tan(M_PI * cutoff_hz / sample_rate_hz), k2 = k * k;
  std::vector<Biquad> sections;
  for (int s = 0; s < order / 2; ++s) {
    // Pole pair of the analog prototype: s² + s/q + 1 with 1/q = 2 sin((2s+1)π/(2 order)).
    const double inv_q = 2 * std::sin((2 * s + 1) * M_PI / (2.0 * order));
    const double norm = 1 / (1 + k * inv_q + k2);
    Biquad b;
    b.b0 = k2 * norm;
    b.b1 = 2 * b.b0;
    b.b2 = b.b0;
    b.a1 = 2 * (k2 - 1) * norm;
    b.a2 = (1 - k * inv_q + k2) * norm;
    sections.push_back(b);
  }
  return sections;
}

namespace {

struct SectionState {
  double z1 = 0, z2 = 0;
};

// Filters x in place through all sections starting from the given states.
void run_sections(const std::vector<Biquad>& sections, std::vector<SectionState> state,
                  std::vector<double>& x) {
  for (double& v : x) {
    double in = v;
    for (std::size_t s = 0; s < sections.size(); ++s) {
      const Biquad& b = sections[s];
      SectionState& z = state[s];
      const double out = b.b0 * in + z.z1;
      z.z1 = b.b1 * in - b.a1 * out + z.z2;
      z.z2 = b.b2 * in - b.a2 * out;
      in = out;
    }
    v = in;
  }
}

// States that make the cascade start in steady state for a constant input `level`.
std::vector<SectionState> steady_state(const std::vector<Biquad>& sections, double level) {
  std::vector<SectionState> state(sections.size());
  double u = level;
  for (std::size_t s = 0; s < sections.size(); ++s) {
    const Biquad& b = sections[s];
    const double gain = (b.b0 + b.b1 + b.b2) / (1 + b.a1 + b.a2);
    const double y = gain * u;
    state[s].z1 = y - b.b0 * u;
    state[s].z2 = b.b2 * u - b.a2 * y;
    u = y;
  }
  return state;
}

}  // namespace

std::vector<double> sos_filter(const std::vector<Biquad>& sections, const std::vector<double>& x) {
  std::vector<double> y = x;
  run_sections(sections, std::vector<SectionState>(sections.size()), y);
  return y;
}

std::vector<double> zero_phase_filter(const std::vector<Biquad>& sections,
                                      const std::vector<double>& x) {
  const std::size_t pad = 3 * (2 * sections.size() + 1);
  const std::size_t n = x.size();
  if (n <= pad)
    throw std::invalid_argument("zero_phase_filter: signal of " + std::to_string(n) +
                                " samples, need more than " + std::to_string(pad));
  // Odd extension: 2 x[0] - x[pad..1], x, 2 x[n-1] - x[n-2..n-1-pad].
  std::vector<double> ext;
  ext.reserve(n + 2 * pad);
  for (std::size_t i = pad; i >= 1; --i) ext.push_back(2 * x[0] - x[i]);
  ext.insert(ext.end(), x.begin(), x.end());
  for (std::size_t i = 1; i <= pad; ++i) ext.push_back(2 * x[n - 1] - x[n - 1 - i]);

  run_sections(sections, steady_state(sections, ext.front()), ext);
  std::reverse(ext.begin(), ext.end());
  run_sections(sections, steady_state(sections, ext.front()), ext);
  std::reverse(ext.begin(), ext.end());
  return std::vector<double>(ext.begin() + pad, ext.begin() + pad + n);
}

std::vector<double> zero_phase_lowpass(const std::vector<double>& x, double sample_rate_hz,
                                       double cutoff_hz, int order) {
  return zero_phase_filter(butterworth_lowpass(order, cutoff_hz, sample_rate_hz), x);
}

double loss_of_contact_percent(const std::vector<double>& position, const std::vector<double>& time,
                               const std::vector<double>& raw, double x_start, double x_end,
                               double min_duration) {
  const auto inside = [&](std::size_t i) { return position[i] >= x_start && position[i] <= x_end; };
  std::size_t samples = 0, lost = 0;
  for (std::size_t i = 0; i < raw.size();) {
    if (raw[i] > 0) {
      samples += inside(i) ? 1 : 0;
      ++i;
      continue;
    }
    std::size_t end = i, in = 0;  // the stretch [i, end) of raw <= 0
    for (; end < raw.size() && raw[end] <= 0; ++end) in += inside(end) ? 1 : 0;
    const double lasts = (end < time.size() ? time[end] : time.back()) - time[i];
    samples += in;
    if (lasts >= min_duration * (1 - 1e-9)) lost += in;
    i = end;
  }
  return samples ? 100.0 * static_cast<double>(lost) / static_cast<double>(samples) : 0.0;
}

ForceStatistics force_statistics(const std::vector<double>& position,
                                 const std::vector<double>& filtered,
                                 const std::vector<double>& raw, double x_start, double x_end) {
  if (position.size() != filtered.size() || position.size() != raw.size())
    throw std::invalid_argument("force_statistics: position, filtered and raw sizes differ");
  ForceStatistics st;
  double sum = 0;
  std::size_t lost = 0;
  st.actual_max = -HUGE_VAL;
  st.actual_min = HUGE_VAL;
  st.unfiltered_min = HUGE_VAL;
  for (std::size_t i = 0; i < position.size(); ++i) {
    if (position[i] < x_start || position[i] > x_end) continue;
    ++st.samples;
    sum += filtered[i];
    if (filtered[i] > st.actual_max) st.actual_max = filtered[i], st.actual_max_x = position[i];
    if (filtered[i] < st.actual_min) st.actual_min = filtered[i], st.actual_min_x = position[i];
    st.unfiltered_min = std::min(st.unfiltered_min, raw[i]);
    if (raw[i] <= 0) ++lost, st.lost_x.push_back(position[i]);
  }
  if (st.samples == 0)
    throw std::invalid_argument("force_statistics: no sample in the window [" +
                                std::to_string(x_start) + ", " + std::to_string(x_end) + "]");
  st.mean = sum / st.samples;
  double sq = 0;  // two-pass variance (no cancellation)
  for (std::size_t i = 0; i < position.size(); ++i)
    if (position[i] >= x_start && position[i] <= x_end)
      sq += (filtered[i] - st.mean) * (filtered[i] - st.mean);
  st.std_dev = std::sqrt(sq / st.samples);
  st.statistical_max = st.mean + 3 * st.std_dev;
  st.statistical_min = st.mean - 3 * st.std_dev;
  st.loss_of_contact_percent = 100.0 * lost / st.samples;
  return st;
}

}  // namespace pcsim::output
