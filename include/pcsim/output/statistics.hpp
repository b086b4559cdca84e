// Contact-force statistics as EN 50318 asks for them (thesis 3.4): zero-phase low-pass
// filtering of the whole history, then statistics over a section of track.
#pragma once

#include <cstddef>
#include <vector>

namespace pcsim::output {

// One second-order section y[n] = b0 x[n] + b1 x[n-1] + b2 x[n-2] - a1 y[n-1] - a2 y[n-2].
struct Biquad {
  double b0 = 1, b1 = 0, b2 = 0, a1 = 0, a2 = 0;
};

// Digital Butterworth low-pass (bilinear transform with pre-warped cut-off, as
// scipy.signal.butter) as a cascade of order/2 sections. order: even, 2..8;
// 0 < cutoff_hz < sample_rate_hz / 2. Throws std::invalid_argument otherwise.
std::vector<Biquad> butterworth_lowpass(int order, double cutoff_hz, double sample_rate_hz);

// Causal filtering (direct form II transposed, like scipy.signal.sosfilt) from rest.
std::vector<double> sos_filter(const std::vector<Biquad>& sections, const std::vector<double>& x);

// Zero-phase filtering: forward then backward pass over the signal extended at both ends by
// its odd reflection (3 (2 sections + 1) samples) and with steady-state initial conditions,
// as scipy.signal.filtfilt / sosfiltfilt with their defaults. The signal must be longer than
// the padding. The result has the squared magnitude response and no phase shift.
std::vector<double> zero_phase_filter(const std::vector<Biquad>& sections,
                                      const std::vector<double>& x);

// Uniformly sampled signal low-pass filtered forward and backward at cutoff_hz.
std::vector<double> zero_phase_lowpass(const std::vector<double>& x, double sample_rate_hz,
                                       double cutoff_hz, int order = 4);

struct ForceStatistics {
  std::size_t samples = 0;     // samples with x_start <= position <= x_end
  double mean = 0;             // Fm
  double std_dev = 0;          // σ, population (divides by N)
  double statistical_max = 0;  // Fm + 3σ
  double statistical_min = 0;  // Fm - 3σ
  double actual_max = 0;       // of the filtered force
  double actual_min = 0;
  double actual_max_x = 0;             // position of the first sample at actual_max [m]
  double actual_min_x = 0;             // ... at actual_min
  double loss_of_contact_percent = 0;  // samples with UNFILTERED force <= 0, in %
  std::vector<double> lost_x;          // the positions of those samples [m], in order
  // Of the UNFILTERED force: never below 0 (the penalty force is clipped at
  // zero while the head is off the wire), where the filtered minimum can be
  // (the low-pass smooths the clipped edge; docs/assessment.md).
  double unfiltered_min = 0;
};

// Statistics of `filtered` over the samples whose position lies in [x_start, x_end]; loss of
// contact counted on `raw`. All three vectors have the same length. Throws
// std::invalid_argument if the sizes differ or the window holds no sample.
ForceStatistics force_statistics(const std::vector<double>& position,
                                 const std::vector<double>& filtered,
                                 const std::vector<double>& raw, double x_start, double x_end);

// Loss of contact in % of the samples in [x_start, x_end] (by position),
// counting only the stretches of consecutive samples with raw <= 0 that last
// at least min_duration [s] (from the first such sample to the next in
// contact, by 'time'; a stretch cut by the section's edge counts what lies
// inside). min_duration 0: every such sample, as force_statistics counts.
double loss_of_contact_percent(const std::vector<double>& position, const std::vector<double>& time,
                               const std::vector<double>& raw, double x_start, double x_end,
                               double min_duration);

}  // namespace pcsim::output
