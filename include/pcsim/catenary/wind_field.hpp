// Turbulent wind along the line (docs/conditions.md, "Turbulence"): the
// fluctuations u' (along the mean wind, horizontal) and w' (vertical) as a
// seeded Gaussian random field on a coarse grid of stations along x and
// times, by the spectral representation method (Shinozuka and Deodatis,
// Appl. Mech. Rev. 44, 1991; Deodatis, J. Eng. Mech. 122, 1996): at every
// frequency the cross-spectral matrix S(f) C(dx, f) of the stations is
// factored (Cholesky) and the stations' series are sums of cosines with
// random phases, evaluated by FFT. Periodic in time with the grid's period.
// Davenport's coherence on a regular grid makes that matrix S rho^|i-j|,
// whose Cholesky factor is a recursion from one station to the next: the
// stations are generated in order along the line, O(1) per station and
// frequency, and each station's phases come from a counter-based generator
// of (seed, frequency, station), so that any stretch of the line's stations
// (a moving window's) is the same field as the whole line's.
//
// Spectrum: EN 1991-1-4 Annex B (B.1), f S(f) / sigma^2 = 6.8 fL / (1 + 10.2 fL)^(5/3),
// fL = f L / V (its integral over f is exactly sigma^2). Coherence along the
// track: Davenport's exp(-C f dx / V).
#pragma once

#include <complex>
#include <cstdint>
#include <vector>

namespace pcsim::catenary {

struct TurbulenceSpec {
  double mean_speed = 0;        // V [m/s]
  double sigma = 0;             // standard deviation of the component [m/s]
  double length_scale = 0;      // L [m]
  double coherence_decay = 10;  // C [1]
  std::uint64_t seed = 1;
};

// One-sided power spectral density of the EN 1991-1-4 form [m^2/s^2 per Hz].
double turbulence_psd(const TurbulenceSpec& s, double f);
// Davenport's coherence (root-coherence, real) between stations dx apart.
double turbulence_coherence(const TurbulenceSpec& s, double f, double dx);

// Linear interpolation between two grid points: value = (1 - w) v[lo] + w v[hi].
struct Bracket {
  int lo = 0, hi = 0;
  double w = 0;
};
// Between stations x0 + i dx (i < nx), held beyond the ends.
Bracket station_bracket(double x, double x0, double dx, int nx);
// Between samples k dt (k < nt), periodic with period nt dt.
Bracket sample_bracket(double t, double dt, int nt);

// Samples of a component at stations x0 + i dx (i < nx) and times k dt
// (k < nt, nt a power of two: period nt dt), row i = station.
struct WindSeries {
  double x0 = 0, dx = 1, dt = 1;
  int nx = 0, nt = 0;
  std::vector<double> values;  // values[i * nt + k]
  double at(int i, int k) const { return values[static_cast<std::size_t>(i) * nt + k]; }
  // Bilinear in x (held beyond the ends) and t (periodic).
  double interpolate(double x, double t) const;
};

// The random phase of frequency l at station i of the line [rad, 0..2 pi).
double turbulence_phase(std::uint64_t seed, int frequency, long station);

// The line's stations 0, 1, 2, ... (dx apart) along the line: stations()
// gives the series of stations first .. first + count - 1, first at least the
// last stretch's first (a moving window's stretches overlap), passing over
// the ones before in O(frequencies) each.
class TurbulenceGenerator {
 public:
  TurbulenceGenerator(const TurbulenceSpec& s, double dx, double dt, int nt);
  // x0: the x at which to place station 'first' in the series returned.
  WindSeries stations(long first, int count, double x0, double dx);

 private:
  void step();  // the amplitudes of station next_
  TurbulenceSpec spec_;
  double dt_;
  int nt_;
  std::vector<double> amplitude_, decay_, innovation_;     // a_l, rho_l, a_l sqrt(1 - rho_l^2)
  std::vector<std::complex<double>> state_, saved_state_;  // B_(next_-1), B_(saved_next_-1)
  long next_ = 0, saved_next_ = 0;  // the next station; the last stretch's first
};

WindSeries generate_turbulence(const TurbulenceSpec& s, double x0, double dx, int nx, double dt,
                               int nt);

// A moving window's stations (window.x0 + j window.dx, in the window's
// coordinates; the line's station 0 at window x0 when offset = 0) take the
// line's field at x + offset: a line station's series bit for bit when the
// offset is a multiple of dx, else linear between the two around it.
// Offsets never decrease (TurbulenceGenerator::stations).
void take_line_field(TurbulenceGenerator& line, double offset, WindSeries& window);

}  // namespace pcsim::catenary
