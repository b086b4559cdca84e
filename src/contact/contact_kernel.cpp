// Penalty contact kernel (thesis 3.2, eqs 3.9–3.13).
#include "pcsim/contact/contact_kernel.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "pcsim/catenary/elements.hpp"

namespace pcsim::contact {

Vector12d shape_row(double chi, double lref, int component) {
  const auto s = catenary::hermite(chi, lref).s;
  Vector12d row = Vector12d::Zero();
  for (int k = 0; k < 4; ++k) row(3 * k + component) = s[k];
  return row;
}

double interpolate(const Vector12d& q, double chi, double lref, int component) {
  // s1 + s3 = 1: written relative to node i so that large track coordinates lose no digits.
  const auto s = catenary::hermite(chi, lref).s;
  const int c = component;
  return q(c) + (s[1] * q(3 + c) + s[2] * (q(6 + c) - q(c)) + s[3] * q(9 + c));
}

ContactLocation locate_contact_point(const Vector12d& q, double lref, double x_c) {
  if (!(lref > 0)) throw std::invalid_argument("locate_contact_point: Lref must be positive");
  auto g = [&](double chi) { return interpolate(q, chi, lref, 0) - x_c; };
  auto dg = [&](double chi) {
    const auto d = catenary::hermite(chi, lref).ds;
    return d[0] * q(0) + d[1] * q(3) + d[2] * q(6) + d[3] * q(9);
  };
  ContactLocation loc;
  double lo = 0, hi = lref, g_lo = g(lo), g_hi = g(hi);
  if (g_lo == 0) return {0.0, true, 0};
  if (g_hi == 0) return {lref, true, 0};
  if ((g_lo > 0) == (g_hi > 0)) {  // x_c outside the element: nearest end
    loc.chi = std::abs(g_lo) < std::abs(g_hi) ? 0.0 : lref;
    loc.inside = false;
    return loc;
  }
  loc.inside = true;
  // Start from the secant (exact for a straight, uniformly parametrised element).
  double chi = lo - g_lo * (hi - lo) / (g_hi - g_lo);
  const double tol_x =
      std::numeric_limits<double>::epsilon() * std::max({std::abs(x_c), lref, 1.0});
  for (int it = 0; it < 200; ++it) {
    loc.iterations = it + 1;
    const double gc = g(chi);
    if (std::abs(gc) <= tol_x) break;
    if ((gc > 0) == (g_lo > 0)) {
      lo = chi;
      g_lo = gc;
    } else {
      hi = chi;
    }
    const double slope = dg(chi);
    double next = slope != 0 ? chi - gc / slope : lo;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);  // Newton left the bracket
    if (next == chi || hi - lo <= 4 * std::numeric_limits<double>::epsilon() * lref) {
      chi = next;
      break;
    }
    chi = next;
  }
  loc.chi = chi;
  return loc;
}

ContactEvaluation evaluate_penalty_contact(const Vector12d& q, double q_head, double chi_c,
                                           double lref, double k_penalty) {
  ContactEvaluation out;
  const Vector12d s_z = shape_row(chi_c, lref, 2);
  out.gap = s_z.dot(q) - q_head;  // (3.9) with z_cc from (3.13)
  if (out.gap >= 0) return out;   // separated: no force (3.10)
  out.force = -k_penalty * out.gap;
  Vector13d b;  // d gap / d [q, q_H]
  b.head<12>() = s_z;
  b(12) = -1;
  out.residual.head<12>() = -out.force * s_z;  // upward force on the wire at chi_c
  out.residual(12) = out.force;                // downward force on the head
  out.tangent = k_penalty * b * b.transpose();
  return out;
}

}  // namespace pcsim::contact
