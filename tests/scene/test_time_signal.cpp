// A pantograph base motion from a one-sided PSD (scene/time_signal.hpp,
// `base_motion: {type: psd}`): its spectrum, variance, velocity, seed, and
// the input errors.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <string>

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
