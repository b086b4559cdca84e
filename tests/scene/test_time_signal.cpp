// A pantograph base motion from a one-sided PSD (scene/time_signal.hpp,
// `base_motion: {type: psd}`): its spectrum, variance, velocity, seed, and
// the input errors; a roof record read by the natural cubic spline
// (`type: file, interpolation: cubic`): the spline's convergence, continuity
// and ends, and the file's acceleration.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <complex>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "pcsim/core/cubic_spline.hpp"
#include "pcsim/core/error.hpp"
#include "pcsim/scene/time_signal.hpp"
#include "pcsim/scene/yaml_input.hpp"

using pcsim::scene::InputNode;

namespace {

// A roof-like spectrum: 1e-6 m^2/Hz from 1 to 5 Hz falling to 1e-8 at 17 Hz;
// 256 bins of df = 1/16 Hz (so that 2 f_first / df is a whole number: see the
// spectrum test).
const char* kRoof =
    "type: psd\nfrequency_hz: [1, 5, 17]\npsd: [1.0e-6, 1.0e-6, 1.0e-8]\nseed: 7\n"
    "components: 256\n";

pcsim::pantograph::BaseMotion motion(const std::string& text) {
  return pcsim::scene::load_base_motion(InputNode::load_string(text, "scene.yaml"));
}

std::string error_of(const std::string& text) {
  try {
    motion(text);
  } catch (const pcsim::InputError& e) {
    return e.what();
  }
  return "";
}

// The PSD between the table's points (linear), as the generator reads it.
double roof_psd(double f) {
  if (f <= 5) return 1.0e-6;
  return 1.0e-6 + (f - 5) / 12 * (1.0e-8 - 1.0e-6);
}

}  // namespace

// Sampled over T = 1 / df (df = 1/16 Hz) on 8192 points, the motion's
// discrete Fourier coefficient at the n-th bin centre f_n is exactly
// a_n / 2 = sqrt(2 S(f_n) df) / 2: the other lines differ from f_n by whole
// multiples of df and the images at -(f_m + f_n) by whole cycles over T
// (2 f_first / df = 32), all below the 4096 cycles the samples resolve, so
// their sums vanish. Measured to 1.5e-14 of the largest amplitude, asserted
// 1e-10 of it (rounding of 8192 samples of 256 cosines: ~1e-13). The
// variance over T is the sum of a_n^2 / 2 (the cross terms vanish alike), the
// PSD's integral by the midpoint rule: exact on the linear pieces, and the
// PSD's kink at 5 Hz is a bin edge; measured 4.4e-16 relative, asserted
// 1e-12 (the 8192-term sum's rounding, ~1e-13).
TEST(BaseMotionPsd, SpectrumAndVarianceAreThePsds) {
  const auto m = motion(kRoof);
  const double df = 16.0 / 256, period = 1 / df;
  const int samples = 8192;
  std::vector<double> z(samples);
  double variance = 0;
  for (int i = 0; i < samples; ++i) {
    z[i] = m.displacement(period * i / samples);
    variance += z[i] * z[i] / samples;
  }
  const double exact_integral = 4 * 1.0e-6 + 12 * 0.5 * (1.0e-6 + 1.0e-8);
  EXPECT_NEAR(variance / exact_integral, 1.0, 1e-12);
  double worst = 0, largest = 0;
  for (int n : {0, 30, 53, 54, 100, 200, 255}) {
    const double fn = 1 + (n + 0.5) * df;
    const double cycles = fn * period;  // 16.5 + n: half-integer
    std::complex<double> c = 0;
    for (int i = 0; i < samples; ++i)
      c += z[i] * std::exp(std::complex<double>(0, -2 * M_PI * cycles * i / samples));
    const double amplitude = 2 * std::abs(c) / samples;
    const double expected = std::sqrt(2 * roof_psd(fn) * df);
    largest = std::max(largest, expected);
    worst = std::max(worst, std::abs(amplitude - expected));
  }
  std::printf(
      "PSD base motion: variance %.6e m^2 (PSD integral %.6e, relative difference %.1e), "
      "worst bin %.2e m of %.2e m\n",
      variance, exact_integral, variance / exact_integral - 1, worst, largest);
  EXPECT_LT(worst, 1e-10 * largest + 1e-18);
}

// The velocity is the displacement's derivative: central differences with
// h = 1e-6 s have truncation error ~h^2 |z'''| / 6 ~ 1e-12 x (2 pi 20)^3 x
// 2e-3 m ~ 4e-9 m/s and rounding ~1e-16 x 2e-3 / 1e-6 = 2e-13 m/s against
// velocities ~0.05 m/s; asserted 1e-7 m/s.
TEST(BaseMotionPsd, VelocityIsTheDerivative) {
  const auto m = motion(kRoof);
  const double h = 1e-6;
  for (double t : {0.0, 0.123, 1.7, 9.9}) {
    const double fd = (m.displacement(t + h) - m.displacement(t - h)) / (2 * h);
    EXPECT_NEAR(m.velocity(t), fd, 1e-7) << "t = " << t;
  }
}

TEST(BaseMotionPsd, TheSeedChoosesThePhases) {
  const auto a = motion(kRoof), b = motion(kRoof);
  std::string other = kRoof;
  other.replace(other.find("seed: 7"), 7, "seed: 8");
  const auto c = motion(other);
  EXPECT_EQ(a.displacement(0.37), b.displacement(0.37));
  EXPECT_NE(a.displacement(0.37), c.displacement(0.37));
}

TEST(BaseMotionPsd, BadTablesNameTheKey) {
  const std::string head = "type: psd\n";
  EXPECT_NE(error_of(head + "frequency_hz: [1]\npsd: [1e-6]\n").find("frequency_hz"),
            std::string::npos);
  EXPECT_NE(error_of(head + "frequency_hz: [1, 2]\npsd: [1e-6]\n").find("one value per"),
            std::string::npos);
  EXPECT_NE(error_of(head + "frequency_hz: [2, 1]\npsd: [1e-6, 1e-6]\n").find("increase"),
            std::string::npos);
  EXPECT_NE(error_of(head + "frequency_hz: [1, 2]\npsd: [1e-6, -1]\n").find("'psd'"),
            std::string::npos);
  EXPECT_NE(error_of(head + "frequency_hz: [1, 2]\npsd: [1e-6, 1e-6]\ncomponents: 0\n")
                .find("components"),
            std::string::npos);
  EXPECT_NE(error_of(head + "frequency_hz: [1, 2]\npsd: [1e-6, 1e-6]\nsede: 1\n").find("sede"),
            std::string::npos);
}

// --- A roof record read by the natural cubic spline (core/cubic_spline.hpp) ---

// Largest errors of the spline through z = sin(2 pi t) sampled every h on
// [0, 1] (curvature 0 at both ends, as the natural spline's), and of its
// first and second derivatives, at 50 points per interval.
static std::array<double, 3> spline_errors(int intervals) {
  std::vector<double> t, y;
  for (int k = 0; k <= intervals; ++k) {
    t.push_back(static_cast<double>(k) / intervals);
    y.push_back(std::sin(2 * M_PI * t.back()));
  }
  const pcsim::NaturalCubicSpline s(t, y);
  std::array<double, 3> worst{};
  const double w = 2 * M_PI;
  for (int i = 0; i < 50 * intervals; ++i) {
    const double x = (i + 0.5) / (50.0 * intervals);
    worst[0] = std::max(worst[0], std::abs(s.value(x) - std::sin(w * x)));
    worst[1] = std::max(worst[1], std::abs(s.slope(x) - w * std::cos(w * x)));
    worst[2] = std::max(worst[2], std::abs(s.second_derivative(x) + w * w * std::sin(w * x)));
  }
  return worst;
}

TEST(NaturalCubicSpline, ConvergesAtTheCubicSplineRates) {
  // Halving h divides the errors by 2^4, 2^3 and 2^2 (a cubic spline's
  // orders, end conditions matching). Measured from 40 to 80 intervals:
  // 16.04, 8.01, 4.003 (printed); asserted within 2 % of 16, 8, 4 (one
  // order less would halve the ratio).
  const auto e20 = spline_errors(20), e40 = spline_errors(40), e80 = spline_errors(80);
  const double expected[3] = {16, 8, 4};
  for (int d = 0; d < 3; ++d) {
    const double r1 = e20[d] / e40[d], r2 = e40[d] / e80[d];
    std::printf("derivative %d: errors %.3g %.3g %.3g, ratios %.3f %.3f\n", d, e20[d], e40[d],
                e80[d], r1, r2);
    EXPECT_NEAR(r2, expected[d], 0.02 * expected[d]) << "derivative " << d;
  }
  // At 1 ms samples of a 5 Hz roof motion (h f = 1/200), a_b is within
  // 0.1 % of its amplitude (the 80-interval case has h f = 1/80).
  EXPECT_LT(e80[2] / (4 * M_PI * M_PI), 1e-3);
}

TEST(NaturalCubicSpline, InterpolatesIsTwiceContinuousAndNaturalAtTheEnds) {
  const std::vector<double> t = {0.0, 0.1, 0.25, 0.3, 0.7, 1.0};  // uneven steps
  const std::vector<double> y = {0.0, 2e-3, -1e-3, 4e-3, 0.5e-3, 1e-3};
  const pcsim::NaturalCubicSpline s(t, y);
  const double eps = 1e-9;
  for (std::size_t k = 0; k < t.size(); ++k) {
    EXPECT_DOUBLE_EQ(s.value(t[k]), y[k]);
    if (k == 0 || k + 1 == t.size()) continue;
    // the one-sided values at an interior sample agree to O(eps)
    EXPECT_NEAR(s.slope(t[k] - eps), s.slope(t[k] + eps), 1e-6);
    EXPECT_NEAR(s.second_derivative(t[k] - eps), s.second_derivative(t[k] + eps), 1e-6);
  }
  EXPECT_NEAR(s.second_derivative(eps), 0.0, 1e-6);
  EXPECT_NEAR(s.second_derivative(1.0 - eps), 0.0, 1e-6);
  // outside the samples: held, at rest
  EXPECT_EQ(s.value(-1.0), 0.0);
  EXPECT_EQ(s.value(2.0), 1e-3);
  EXPECT_EQ(s.slope(2.0), 0.0);
  EXPECT_EQ(s.second_derivative(-1.0), 0.0);
  // two samples: the straight line; one sample: a constant
  const pcsim::NaturalCubicSpline line({0.0, 2.0}, {1.0, 3.0});
  EXPECT_DOUBLE_EQ(line.value(0.5), 1.5);
  EXPECT_DOUBLE_EQ(line.slope(0.5), 1.0);
  EXPECT_DOUBLE_EQ(line.second_derivative(0.5), 0.0);
  EXPECT_EQ(pcsim::NaturalCubicSpline({1.0}, {4.0}).value(3.0), 4.0);
  EXPECT_THROW(pcsim::NaturalCubicSpline({0.0, 0.0}, {1.0, 2.0}), std::invalid_argument);
  EXPECT_THROW(pcsim::NaturalCubicSpline({0.0, 1.0}, {1.0}), std::invalid_argument);
}

// A roof file next to the scene: z_b = 2 mm sin(2 pi 5 t) every 1 ms over 1 s.
static std::string roof_file() {
  const std::string path = "roof-test-time-signal.csv";
  std::ofstream out(path);
  out.precision(17);
  for (int k = 0; k <= 1000; ++k)
    out << k * 1e-3 << ", " << 2e-3 * std::sin(2 * M_PI * 5 * k * 1e-3) << "\n";
  return path;
}

TEST(BaseMotionFile, CubicGivesTheAccelerationLinearNone) {
  const std::string file = "type: file\nfile: " + roof_file() + "\n";
  const auto linear = motion(file);
  EXPECT_FALSE(static_cast<bool>(linear.acceleration));  // lumped models' default
  const auto cubic = motion(file + "interpolation: cubic\n");
  ASSERT_TRUE(static_cast<bool>(cubic.acceleration));
  const double w = 2 * M_PI * 5, t = 0.4321;
  // the sampled harmonic's a_b to 0.1 % of its amplitude (h f = 1/200)
  EXPECT_NEAR(cubic.acceleration(t), -2e-3 * w * w * std::sin(w * t), 2e-6 * w * w);
  EXPECT_NEAR(cubic.velocity(t), 2e-3 * w * std::cos(w * t), 2e-7 * w);
  // a moving-frame model (DSA-380) reads the file by the spline by default
  const auto framed = pcsim::scene::load_base_motion(InputNode::load_string(file, "scene.yaml"),
                                                     /*moving_frame=*/true);
  ASSERT_TRUE(static_cast<bool>(framed.acceleration));
  EXPECT_EQ(framed.acceleration(t), cubic.acceleration(t));
}

TEST(BaseMotionFile, InterpolationErrorsNameTheKey) {
  const std::string file = "type: file\nfile: " + roof_file() + "\n";
  EXPECT_NE(error_of(file + "interpolation: spline\n").find("interpolation"), std::string::npos);
  std::string why;
  try {
    pcsim::scene::load_base_motion(
        InputNode::load_string(file + "interpolation: linear\n", "scene.yaml"), true);
  } catch (const pcsim::InputError& e) {
    why = e.what();
  }
  EXPECT_NE(why.find("interpolation"), std::string::npos) << why;
  EXPECT_NE(why.find("acceleration"), std::string::npos) << why;
}
