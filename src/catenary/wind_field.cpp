#include "pcsim/catenary/wind_field.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <complex>
#include <random>
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

// u_j(t_p) = Re sum_l B_jl exp(2 pi i l p / nt), B_jl = sum_k H_jk(f_l)
// sqrt(2 df) exp(i phi_kl): variance sum_l S df, cross-covariance
// sum_l (H H^T)_ij df = sum_l S_ij df.
WindSeries generate_turbulence(const TurbulenceSpec& s, double x0, double dx, int nx, double dt,
                               int nt) {
  WindSeries out{x0, dx, dt, nx, nt, std::vector<double>(static_cast<std::size_t>(nx) * nt, 0.0)};
  const double df = 1.0 / (nt * dt);
  const int m = nt / 2;  // frequencies l df, l = 1 .. m - 1 (below Nyquist)
  std::mt19937_64 rng(s.seed);
  std::uniform_real_distribution<double> phase(0.0, 2 * M_PI);
  Eigen::MatrixXcd B = Eigen::MatrixXcd::Zero(nx, nt);
  Eigen::MatrixXd S(nx, nx);
  for (int l = 1; l < m; ++l) {
    const double f = l * df, psd = turbulence_psd(s, f);
    for (int i = 0; i < nx; ++i)
      for (int j = 0; j < nx; ++j) S(i, j) = psd * turbulence_coherence(s, f, (i - j) * dx);
    const Eigen::LLT<Eigen::MatrixXd> llt(S);
    const Eigen::MatrixXd H = llt.matrixL();
    Eigen::VectorXcd e(nx);
    for (int k = 0; k < nx; ++k) e[k] = std::polar(std::sqrt(2 * df), phase(rng));
    B.col(l) = H * e;
  }
  Eigen::FFT<double> fft;
  std::vector<std::complex<double>> in(nt), time(nt);
  for (int i = 0; i < nx; ++i) {
    for (int k = 0; k < nt; ++k) in[k] = B(i, k);
    fft.inv(time, in);  // (1/nt) sum_l in_l exp(+2 pi i l p / nt)
    for (int k = 0; k < nt; ++k)
      out.values[static_cast<std::size_t>(i) * nt + k] = nt * time[k].real();
  }
  return out;
}

}  // namespace pcsim::catenary
