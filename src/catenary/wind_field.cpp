#include "pcsim/catenary/wind_field.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <complex>
#include <stdexcept>
#include <unsupported/Eigen/FFT>

namespace pcsim::catenary {

double turbulence_psd(const TurbulenceSpec& s, double f) {
  if (f <= 0) return 0;
  const double fl = f * s.length_scale / s.mean_speed;
  return s.sigma * s.sigma * 6.8 * fl / std::pow(1 + 10.2 * fl, 5.0 / 3.0) / f;
}

double turbulence_coherence(const TurbulenceSpec& s, double f, double dx) {
  return std::exp(-s.coherence_decay * f * std::abs(dx) / s.mean_speed);
}

Bracket station_bracket(double x, double x0, double dx, int nx) {
  const double u = std::clamp((x - x0) / dx, 0.0, static_cast<double>(nx - 1));
  const int i = std::min(static_cast<int>(u), std::max(nx - 2, 0));
  return {i, nx > 1 ? i + 1 : i, nx > 1 ? u - i : 0.0};
}

Bracket sample_bracket(double t, double dt, int nt) {
  const double period = nt * dt;
  double tau = std::fmod(t, period);
  if (tau < 0) tau += period;
  const int k = std::min(static_cast<int>(tau / dt), nt - 1);
  return {k, (k + 1) % nt, tau / dt - k};
}

double WindSeries::interpolate(double x, double t) const {
  if (nx == 0) return 0;
  const Bracket s = station_bracket(x, x0, dx, nx), k = sample_bracket(t, dt, nt);
  const double a = s.w, b = k.w;
  return (1 - a) * ((1 - b) * at(s.lo, k.lo) + b * at(s.lo, k.hi)) +
         a * ((1 - b) * at(s.hi, k.lo) + b * at(s.hi, k.hi));
}

namespace {

// SplitMix64's finaliser (Steele, Lea and Flood, OOPSLA 2014): a bijective mix.
std::uint64_t mix64(std::uint64_t z) {
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

}  // namespace

double turbulence_phase(std::uint64_t seed, int frequency, long station) {
  const std::uint64_t key =
      (static_cast<std::uint64_t>(station) << 21) ^ static_cast<std::uint64_t>(frequency);
  return 2 * M_PI * static_cast<double>(mix64(mix64(seed) ^ key) >> 11) * 0x1.0p-53;
}

TurbulenceGenerator::TurbulenceGenerator(const TurbulenceSpec& s, double dx, double dt, int nt)
    : spec_(s), dt_(dt), nt_(nt) {
  const double df = 1.0 / (nt * dt);
  const int m = nt / 2;  // frequencies l df, l = 1 .. m - 1 (below Nyquist)
  amplitude_.assign(m, 0.0), decay_.assign(m, 0.0), innovation_.assign(m, 0.0);
  state_.assign(m, {0.0, 0.0});
  for (int l = 1; l < m; ++l) {
    const double f = l * df;
    amplitude_[l] = std::sqrt(turbulence_psd(s, f) * 2 * df);
    decay_[l] = turbulence_coherence(s, f, dx);
    innovation_[l] = amplitude_[l] * std::sqrt(1 - decay_[l] * decay_[l]);
  }
}

// B_0 = a e_0, B_i = rho B_(i-1) + a sqrt(1 - rho^2) e_i at each frequency:
// the Cholesky factor of the stations' cross-spectral matrix a^2 rho^|i-j|
// (Davenport's coherence on a regular grid) applied to the random phases
// e_i = exp(i phi_i), one station after the other.
void TurbulenceGenerator::step() {
  for (std::size_t l = 1; l < state_.size(); ++l) {
    const std::complex<double> e =
        std::polar(1.0, turbulence_phase(spec_.seed, static_cast<int>(l), next_));
    state_[l] = next_ == 0 ? amplitude_[l] * e : decay_[l] * state_[l] + innovation_[l] * e;
  }
  ++next_;
}

WindSeries TurbulenceGenerator::stations(long first, int count, double x0, double dx) {
  if (first < next_) {  // overlapping the last stretch: from its start again
    if (first < saved_next_)
      throw std::logic_error("TurbulenceGenerator: a stretch starts before the last one's start");
    state_ = saved_state_;
    next_ = saved_next_;
  }
  WindSeries out{x0,    dx,  dt_,
                 count, nt_, std::vector<double>(static_cast<std::size_t>(count) * nt_)};
  while (next_ < first) step();
  saved_state_ = state_;
  saved_next_ = next_;
  Eigen::FFT<double> fft;
  std::vector<std::complex<double>> in(nt_, {0.0, 0.0}), time(nt_);
  for (int i = 0; i < count; ++i) {
    step();
    std::copy(state_.begin(), state_.end(), in.begin());
    fft.inv(time, in);  // (1/nt) sum_l in_l exp(+2 pi i l p / nt)
    for (int k = 0; k < nt_; ++k)
      out.values[static_cast<std::size_t>(i) * nt_ + k] = nt_ * time[k].real();
  }
  return out;
}

// u_j(t_p) = Re sum_l B_jl exp(2 pi i l p / nt) (TurbulenceGenerator):
// variance sum_l S df, cross-covariance sum_l S_ij df.
WindSeries generate_turbulence(const TurbulenceSpec& s, double x0, double dx, int nx, double dt,
                               int nt) {
  TurbulenceGenerator generator(s, dx, dt, nt);
  return generator.stations(0, nx, x0, dx);
}

void take_line_field(TurbulenceGenerator& line, double offset, WindSeries& window) {
  const double dx = window.dx;
  const int n = window.nx;
  const long first = static_cast<long>(std::floor(offset / dx));
  const double line_x0 = window.x0 + first * dx - offset;  // in the window's coordinates
  const WindSeries field = line.stations(first, n + 1, line_x0, dx);
  for (int j = 0; j < n; ++j) {
    const Bracket b = station_bracket(window.x0 + j * dx, line_x0, dx, n + 1);
    for (int k = 0; k < window.nt; ++k)
      window.values[static_cast<std::size_t>(j) * window.nt + k] =
          b.w == 0 ? field.at(b.lo, k) : (1 - b.w) * field.at(b.lo, k) + b.w * field.at(b.hi, k);
  }
}

}  // namespace pcsim::catenary
