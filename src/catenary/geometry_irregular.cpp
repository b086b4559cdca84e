// Contact-wire irregularities of a parametric line: the height profile
// (prescribed table + random cosines) that the builder adds to the contact
// wires' design heights (and so to the form-finding targets), the contact-gap
// offsets that carry the profile between the held points, and wear.
#include <algorithm>
#include <cmath>
#include <random>

#include "geometry_line.hpp"
#include "pcsim/core/random.hpp"

namespace pcsim::catenary::detail {

namespace {

double linear(const std::vector<double>& x, const std::vector<double>& y, double at) {
  if (x.empty() || at <= x.front()) return x.empty() ? 0.0 : y.front();
  if (at >= x.back()) return y.back();
  const auto it = std::upper_bound(x.begin(), x.end(), at);
  const std::size_t i = static_cast<std::size_t>(it - x.begin()) - 1;
  const double w = (at - x[i]) / (x[i + 1] - x[i]);
  return (1 - w) * y[i] + w * y[i + 1];
}

}  // namespace

// Random part: cosines at the wavenumbers k_n = 2 pi n / Lambda in the band
// (Lambda: the line's length, at least the longest wavelength), amplitudes
// a_n ~ sqrt(PSD(k_n)) (uniform: constant; power law: k_n^(-p/2)), phases
// uniform in [0, 2 pi) from the seed, scaled so that sqrt(sum a_n^2 / 2) is
// the RMS amplitude.
IrregularProfile::IrregularProfile(const IrregularityDesign& in, double line_length) : in_(in) {
  if (in.profile_x.size() >= 2) {
    empty_ = false;
    double spacing = in.profile_x.back() - in.profile_x.front();
    for (std::size_t i = 1; i < in.profile_x.size(); ++i)
      spacing = std::min(spacing, in.profile_x[i] - in.profile_x[i - 1]);
    resolution_ = std::max(0.01, spacing);
  }
  if (!in.random || !(in.random->rms > 0)) return;
  const RandomIrregularity& r = *in.random;
  empty_ = false;
  resolution_ = std::min(in.profile_x.size() >= 2 ? resolution_ : 0.1, r.wavelength_min / 8.0);
  const double Lambda = std::max(line_length, r.wavelength_max);
  const long n_min = std::max(1L, static_cast<long>(std::ceil(Lambda / r.wavelength_max - 1e-9)));
  const long n_max =
      std::max(n_min, static_cast<long>(std::floor(Lambda / r.wavelength_min + 1e-9)));
  std::mt19937_64 gen(static_cast<std::mt19937_64::result_type>(r.seed));
  double power = 0;
  for (long n = n_min; n <= n_max; ++n) {
    const double k = 2.0 * M_PI * n / Lambda;
    const double a =
        r.spectrum == IrregularitySpectrum::uniform ? 1.0 : std::pow(k, -0.5 * r.exponent);
    k_.push_back(k);
    a_.push_back(a);
    phase_.push_back(2.0 * M_PI * unit_random(gen));
    power += 0.5 * a * a;
  }
  const double scale = r.rms / std::sqrt(power);
  for (double& a : a_) a *= scale;
}

double IrregularProfile::dz(double x) const {
  double z = 0;
  if (in_.profile_x.size() >= 2 && x >= in_.profile_x.front() && x <= in_.profile_x.back())
    z = linear(in_.profile_x, in_.profile_dz, x);
  for (std::size_t n = 0; n < k_.size(); ++n) z += a_[n] * std::cos(k_[n] * x + phase_[n]);
  return z;
}

// offset(x) = dz(x) - I(x), I the linear interpolation of dz through the
// wire's held points (where the static wire carries dz: height targets, fixed
// ends): zero at the held points, the profile's content between them.
void add_contact_gap_offsets(CatenaryMesh& mesh, const IrregularProfile& profile,
                             const std::vector<std::vector<double>>& held) {
  if (profile.empty()) return;
  for (std::size_t w = 0; w < held.size(); ++w) {
    std::vector<double> hx = held[w], hz;
    std::sort(hx.begin(), hx.end());
    for (double x : hx) hz.push_back(profile.dz(x));
    ContactGapOffset g;
    const double h = profile.resolution();
    const auto n = static_cast<long>(std::ceil((hx.back() - hx.front()) / h));
    for (long i = 0; i <= n; ++i) {
      const double x = i == n ? hx.back() : hx.front() + i * h;
      g.x.push_back(x);
      g.offset.push_back(profile.dz(x) - linear(hx, hz, x));
    }
    mesh.contact_gap_offsets.push_back(std::move(g));
  }
}

void apply_wear(CatenaryMesh& mesh, const IrregularityDesign& in) {
  for (int w : mesh.contact_wires)
    for (int e : mesh.wires[w].elements) {
      auto& el = mesh.cables[e];
      const double mid = mesh.track.station(
          0.5 * (mesh.nodes[el.nodes[0]].position + mesh.nodes[el.nodes[1]].position).head<2>());
      // Stretches do not overlap (check_wear); [from, to) so that touching
      // ones share no element.
      for (const auto& stretch : in.wear)
        if (mid >= stretch.from && mid < stretch.to) el.section_factor = 1.0 - stretch.section_loss;
    }
}

}  // namespace pcsim::catenary::detail
