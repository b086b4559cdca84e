// EN 50318 statistics: zero-phase Butterworth low-pass and section statistics.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include "pcsim/output/statistics.hpp"

namespace {

std::vector<double> sine(double freq, double fs, std::size_t n, double amplitude = 1.0) {
  std::vector<double> x(n);
  for (std::size_t i = 0; i < n; ++i) x[i] = amplitude * std::sin(2 * M_PI * freq * i / fs);
  return x;
}

// Least-squares amplitude and phase of a sinusoid of known frequency over [i0, i1).
void fit_sine(const std::vector<double>& y, double freq, double fs, std::size_t i0, std::size_t i1,
              double* amplitude, double* phase) {
  double ss = 0, sc = 0, cc = 0, ys = 0, yc = 0;
  for (std::size_t i = i0; i < i1; ++i) {
    const double s = std::sin(2 * M_PI * freq * i / fs), c = std::cos(2 * M_PI * freq * i / fs);
    ss += s * s;
    sc += s * c;
    cc += c * c;
    ys += y[i] * s;
    yc += y[i] * c;
  }
  const double det = ss * cc - sc * sc;
  const double a = (ys * cc - yc * sc) / det, b = (yc * ss - ys * sc) / det;
  *amplitude = std::hypot(a, b);
  *phase = std::atan2(b, a);
}

double rms(const std::vector<double>& y, std::size_t i0, std::size_t i1) {
  double s = 0;
  for (std::size_t i = i0; i < i1; ++i) s += y[i] * y[i];
  return std::sqrt(s / (i1 - i0));
}

}  // namespace

TEST(Statistics, FilterPassesConstantExactly) {
  for (int order : {2, 4}) {
    const std::vector<double> x(3000, 117.25);
    const auto y = pcsim::output::zero_phase_lowpass(x, 1000.0, 20.0, order);
    ASSERT_EQ(y.size(), x.size());
    for (double v : y) EXPECT_NEAR(v, 117.25, 1e-10);
  }
}

TEST(Statistics, FilterAttenuates100HzByMoreThan40dB) {
  for (int order : {2, 4}) {
    const double fs = 1000, fc = 20;
    const auto x = sine(100.0, fs, 5000);
    const auto y = pcsim::output::zero_phase_lowpass(x, fs, fc, order);
    // Away from the ends (edge transients), the remaining amplitude ratio.
    const double gain_db = 20 * std::log10(rms(y, 500, 4500) / rms(x, 500, 4500));
    std::cout << "[ measured ] order " << order << ": 100 Hz gain " << gain_db << " dB\n";
    EXPECT_LT(gain_db, -40.0);
    // Analytic squared magnitude of the bilinear Butterworth: 1/(1 + (tan(πf/fs)/tan(πfc/fs))^2n)
    const double ratio = std::tan(M_PI * 100 / fs) / std::tan(M_PI * fc / fs);
    const double expected_db = 20 * std::log10(1 / (1 + std::pow(ratio, 2 * order)));
    EXPECT_NEAR(gain_db, expected_db, 0.5);
  }
}

TEST(Statistics, FilterHasZeroPhaseAtLowFrequency) {
  const double fs = 1000, f = 2.0;
  const auto x = sine(f, fs, 8000, 30.0);
  for (int order : {2, 4}) {
    const auto y = pcsim::output::zero_phase_lowpass(x, fs, 20.0, order);
    double amplitude, phase;
    fit_sine(y, f, fs, 1000, 7000, &amplitude, &phase);
    EXPECT_LT(std::abs(amplitude - 30.0) / 30.0, 1e-3);
    EXPECT_LT(std::abs(phase), 1e-6);  // no lag (a 1-sample lag would be 0.0126 rad)
    // Pointwise: the filtered signal lies on the input (no shift) in the interior.
    for (std::size_t i = 1000; i < 7000; i += 37) EXPECT_NEAR(y[i], x[i], 1e-3 * 30.0);
  }
}

TEST(Statistics, CausalFilterHasLagZeroPhaseFilterNot) {
  // Guard that the phase test can fail: the causal (one-pass) filter lags a 2 Hz sine.
  const double fs = 1000, f = 2.0;
  const auto x = sine(f, fs, 8000);
  const auto y = pcsim::output::sos_filter(pcsim::output::butterworth_lowpass(4, 20.0, fs), x);
  double amplitude, phase;
  fit_sine(y, f, fs, 1000, 7000, &amplitude, &phase);
  EXPECT_LT(phase, -0.05);
}

// Compares with scipy.signal.filtfilt(b, a, x) (default odd padding, padlen 3 max(len(a),
// len(b))) for b, a = scipy.signal.butter(order, fc, fs=fs), and with sosfiltfilt on the
// second-order-section design, both run by /usr/bin/python3.
TEST(Statistics, MatchesScipyFiltfilt) {
  const double fs = 1000;
  std::mt19937 rng(42);
  std::normal_distribution<double> noise(0.0, 20.0);
  std::vector<double> x(2500);
  for (std::size_t i = 0; i < x.size(); ++i)
    x[i] = 115 + 30 * std::sin(2 * M_PI * 1.3 * i / fs) + 10 * std::sin(2 * M_PI * 45 * i / fs) +
           noise(rng);
  char dir_template[] = "/tmp/pcsim_filtfilt_XXXXXX";
  ASSERT_NE(mkdtemp(dir_template), nullptr);
  const std::string dir = dir_template, in_path = dir + "/x.txt", out_path = dir + "/y.txt";
  {
    std::ofstream out(in_path);
    out.precision(17);
    for (double v : x) out << v << "\n";
  }
  for (int order : {2, 4}) {
    for (double fc : {20.0, 5.0}) {
      std::ostringstream cmd;
      cmd << "/usr/bin/python3 -c \"import numpy as np, scipy.signal as s; "
          << "x = np.loadtxt('" << in_path << "'); b, a = s.butter(" << order << ", " << fc
          << ", fs=" << fs << "); np.savetxt('" << out_path
          << "', np.c_[s.filtfilt(b, a, x), s.sosfiltfilt(s.butter(" << order << ", " << fc
          << ", fs=" << fs << ", output='sos'), x)], fmt='%.17g')\"";
      ASSERT_EQ(std::system(cmd.str().c_str()), 0) << cmd.str();
      std::ifstream in(out_path);
      std::vector<double> ref_tf, ref_sos;
      for (double a, b; in >> a >> b;) {
        ref_tf.push_back(a);
        ref_sos.push_back(b);
      }
      ASSERT_EQ(ref_tf.size(), x.size());
      const auto y = pcsim::output::zero_phase_lowpass(x, fs, fc, order);
      double diff_tf = 0, diff_sos = 0;
      for (std::size_t i = 0; i < x.size(); ++i) {
        diff_tf = std::max(diff_tf, std::abs(y[i] - ref_tf[i]));
        diff_sos = std::max(diff_sos, std::abs(y[i] - ref_sos[i]));
      }
      std::cout << "[ measured ] order " << order << ", fc " << fc
                << " Hz: max |ours - filtfilt| = " << diff_tf
                << " N, max |ours - sosfiltfilt| = " << diff_sos << " N\n";
      // Same filter, padding and initial conditions: only round-off differs (the
      // transfer-function form of filtfilt is the less accurate one at low cut-off).
      EXPECT_LT(diff_sos, 1e-10 * 115);
      EXPECT_LT(diff_tf, 1e-8 * 115);
    }
  }
  std::remove(in_path.c_str());
  std::remove(out_path.c_str());
  rmdir(dir.c_str());
}

TEST(Statistics, RejectsBadParameters) {
  EXPECT_THROW(pcsim::output::butterworth_lowpass(3, 20, 1000), std::invalid_argument);
  EXPECT_THROW(pcsim::output::butterworth_lowpass(4, 600, 1000), std::invalid_argument);
  EXPECT_THROW(pcsim::output::zero_phase_lowpass(std::vector<double>(10, 1.0), 1000, 20, 4),
               std::invalid_argument);
  EXPECT_THROW(pcsim::output::force_statistics({0, 1}, {1, 2}, {1}, 0, 1), std::invalid_argument);
  EXPECT_THROW(pcsim::output::force_statistics({0, 1}, {1, 2}, {1, 2}, 5, 6),
               std::invalid_argument);
}

TEST(Statistics, SectionStatistics) {
  // Position 0..99 m; inside [20, 59]: force 100 + 10 (-1)^i -> mean 100, σ 10 (population).
  std::vector<double> pos, filt, raw;
  for (int i = 0; i < 100; ++i) {
    pos.push_back(i);
    const bool inside = i >= 20 && i <= 59;
    filt.push_back(inside ? 100 + ((i % 2) ? 10.0 : -10.0) : 1000.0);
    raw.push_back(inside && (i == 25 || i == 30) ? 0.0 : (inside ? 50.0 : -5.0));
  }
  filt[40] = 100;  // one sample at the mean: mean 100.25, not symmetric any more
  const auto st = pcsim::output::force_statistics(pos, filt, raw, 20.0, 59.0);
  EXPECT_EQ(st.samples, 40u);
  double mean = 0, var = 0;
  for (int i = 20; i <= 59; ++i) mean += filt[i] / 40;
  for (int i = 20; i <= 59; ++i) var += (filt[i] - mean) * (filt[i] - mean) / 40;
  EXPECT_NEAR(st.mean, mean, 1e-12);
  EXPECT_NEAR(st.std_dev, std::sqrt(var), 1e-12);
  EXPECT_NEAR(st.statistical_max, mean + 3 * std::sqrt(var), 1e-12);
  EXPECT_NEAR(st.statistical_min, mean - 3 * std::sqrt(var), 1e-12);
  EXPECT_EQ(st.actual_max, 110.0);
  EXPECT_EQ(st.actual_min, 90.0);
  EXPECT_NEAR(st.loss_of_contact_percent, 100.0 * 2 / 40, 1e-12);  // raw <= 0, not filtered
  // Where: the section's samples at zero only (raw is -5 outside it).
  EXPECT_EQ(st.lost_x, (std::vector<double>{25.0, 30.0}));
}

// Where the extremes fall: the position of the first sample at the section's
// largest and smallest force, not of larger ones outside the section nor of
// a later sample at the same value.
TEST(Statistics, ExtremesArePlacedAtTheirFirstSampleInsideTheSection) {
  std::vector<double> pos, filt, raw;
  for (int i = 0; i < 200; ++i) {
    pos.push_back(0.5 * i);  // [m]
    filt.push_back(100 +
                   20 * std::sin(0.1 * i));  // peaks at i = 16, 79, 141; troughs at 47, 110, 173
    raw.push_back(filt.back());
  }
  filt[5] = 500;          // outside the section [20, 80] m: not its maximum
  filt[190] = -50;        // outside: not its minimum
  filt[150] = filt[141];  // inside, later, the same value: the first sample's position stays
  const auto st = pcsim::output::force_statistics(pos, filt, raw, 20.0, 80.0);
  EXPECT_EQ(st.actual_max, filt[141]);
  EXPECT_EQ(st.actual_max_x, 70.5);  // i = 141
  EXPECT_EQ(st.actual_min, filt[110]);
  EXPECT_EQ(st.actual_min_x, 55.0);  // i = 110
}

TEST(Statistics, FilteredMinimumOfAClippedForceIsNegativeTheUnfilteredOneIsNot) {
  // A contact force that leaves the wire: 100 + 150 sin(2π 5 t), clipped at 0
  // (the penalty force while the head is off the wire), sampled at 1 kHz. The
  // 20 Hz low-pass smooths the clipped edges below zero (docs/assessment.md);
  // the unfiltered minimum is the clip, 0, and the loss of contact the share
  // of clipped samples.
  std::vector<double> pos, raw;
  for (int i = 0; i < 4000; ++i) {
    pos.push_back(0.1 * i);
    raw.push_back(std::max(0.0, 100 + 150 * std::sin(2 * M_PI * 5 * 1e-3 * i)));
  }
  const auto filtered = pcsim::output::zero_phase_lowpass(raw, 1000.0, 20.0, 4);
  const auto st = pcsim::output::force_statistics(pos, filtered, raw, 50.0, 350.0);
  EXPECT_EQ(st.unfiltered_min, 0.0);
  // Measured -2.26 N: the undershoot of the 4th-order Butterworth at the
  // clipped edges, a few newtons, not the unclipped sine's -50 N.
  EXPECT_LT(st.actual_min, -1.0);
  EXPECT_GT(st.actual_min, -10.0);
  // sin < -2/3 over 2 (π/2 - asin(2/3)) / 2π = 26.8 % of a period; counted
  // in samples, within one of the 200 per period (0.5 %; measured 26.5 %).
  EXPECT_NEAR(st.loss_of_contact_percent, 100 * (M_PI / 2 - std::asin(2.0 / 3)) / M_PI, 0.5);
}

TEST(Statistics, LossOfContactWithAMinimumDuration) {
  // 1 kHz samples, 1 m apart; in the section [100, 899]: losses of 2, 4, 5
  // and 12 samples (2, 4, 5, 12 ms), and one of 6 samples that starts 3
  // samples before the section (3 inside, lasting 6 ms).
  std::vector<double> pos, time, raw(1000, 100.0);
  for (int i = 0; i < 1000; ++i) pos.push_back(i), time.push_back(1e-3 * i);
  const auto lose = [&](int from, int count) {
    for (int i = from; i < from + count; ++i) raw[i] = 0.0;
  };
  lose(200, 2), lose(300, 4), lose(400, 5), lose(500, 12), lose(97, 6);
  const auto all = pcsim::output::force_statistics(pos, raw, raw, 100.0, 899.0);
  // Every lost sample (min 0): 3 + 2 + 4 + 5 + 12 = 26 of 800; as output::force_statistics.
  EXPECT_NEAR(pcsim::output::loss_of_contact_percent(pos, time, raw, 100.0, 899.0, 0.0),
              all.loss_of_contact_percent, 1e-12);
  EXPECT_NEAR(all.loss_of_contact_percent, 100.0 * 26 / 800, 1e-12);
  // From 5 ms on: the 5-, 12- and the 6-sample stretch (3 inside): 20 of 800.
  EXPECT_NEAR(pcsim::output::loss_of_contact_percent(pos, time, raw, 100.0, 899.0, 5e-3),
              100.0 * 20 / 800, 1e-12);
  // From 10 ms on: the 12-sample one only.
  EXPECT_NEAR(pcsim::output::loss_of_contact_percent(pos, time, raw, 100.0, 899.0, 10e-3),
              100.0 * 12 / 800, 1e-12);
}
