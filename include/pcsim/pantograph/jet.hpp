// Third-order jets in one variable: a value together with its first three
// derivatives with respect to a scalar parameter (here the frame angle θ).
// Arithmetic follows the Leibniz and Faà di Bruno rules, so that the closed-loop
// kinematics of the DSA-380 (thesis A.1–A.5) and every quantity built on it carry
// exact derivatives d/dθ, d²/dθ², d³/dθ³ without hand-derived formulas.
#pragma once

#include <cmath>

namespace pcsim::pantograph {

struct Jet {
  double d[4] = {0, 0, 0, 0};  // f, f', f'', f'''

  Jet() = default;
  Jet(double value) { d[0] = value; }  // NOLINT: constants convert implicitly
  static Jet variable(double value) {
    Jet j(value);
    j.d[1] = 1.0;
    return j;
  }
  double operator[](int k) const { return d[k]; }
  // Derivative as a jet; its third derivative is unknown and set to 0, so only
  // entries 0..2 of the result (and of anything computed from it) are valid.
  Jet derivative() const {
    Jet j;
    j.d[0] = d[1];
    j.d[1] = d[2];
    j.d[2] = d[3];
    return j;
  }
  // Jet whose derivative is 'rate' (entries 0..2 used) and whose value is 'value'.
  static Jet integral(double value, const Jet& rate) {
    Jet j(value);
    j.d[1] = rate.d[0];
    j.d[2] = rate.d[1];
    j.d[3] = rate.d[2];
    return j;
  }
};

inline Jet operator+(const Jet& a, const Jet& b) {
  Jet r;
  for (int k = 0; k < 4; ++k) r.d[k] = a.d[k] + b.d[k];
  return r;
}
inline Jet operator-(const Jet& a, const Jet& b) {
  Jet r;
  for (int k = 0; k < 4; ++k) r.d[k] = a.d[k] - b.d[k];
  return r;
}
inline Jet operator-(const Jet& a) {
  Jet r;
  for (int k = 0; k < 4; ++k) r.d[k] = -a.d[k];
  return r;
}
inline Jet operator*(const Jet& a, const Jet& b) {
  Jet r;
  r.d[0] = a.d[0] * b.d[0];
  r.d[1] = a.d[1] * b.d[0] + a.d[0] * b.d[1];
  r.d[2] = a.d[2] * b.d[0] + 2 * a.d[1] * b.d[1] + a.d[0] * b.d[2];
  r.d[3] = a.d[3] * b.d[0] + 3 * a.d[2] * b.d[1] + 3 * a.d[1] * b.d[2] + a.d[0] * b.d[3];
  return r;
}
inline Jet& operator+=(Jet& a, const Jet& b) {
  return a = a + b;
}
inline Jet& operator-=(Jet& a, const Jet& b) {
  return a = a - b;
}

// φ(f) from φ and its first three derivatives at f.
inline Jet compose(const Jet& f, double p0, double p1, double p2, double p3) {
  Jet r;
  const double f1 = f.d[1], f2 = f.d[2], f3 = f.d[3];
  r.d[0] = p0;
  r.d[1] = p1 * f1;
  r.d[2] = p2 * f1 * f1 + p1 * f2;
  r.d[3] = p3 * f1 * f1 * f1 + 3 * p2 * f1 * f2 + p1 * f3;
  return r;
}

inline Jet sin(const Jet& f) {
  const double s = std::sin(f.d[0]), c = std::cos(f.d[0]);
  return compose(f, s, c, -s, -c);
}
inline Jet cos(const Jet& f) {
  const double s = std::sin(f.d[0]), c = std::cos(f.d[0]);
  return compose(f, c, -s, -c, s);
}
inline Jet sqrt(const Jet& f) {
  const double x = f.d[0], s = std::sqrt(x);
  return compose(f, s, 0.5 / s, -0.25 / (s * x), 0.375 / (s * x * x));
}
inline Jet reciprocal(const Jet& f) {
  const double x = f.d[0];
  return compose(f, 1 / x, -1 / (x * x), 2 / (x * x * x), -6 / (x * x * x * x));
}
inline Jet operator/(const Jet& a, const Jet& b) {
  return a * reciprocal(b);
}
inline Jet acos(const Jet& f) {
  const double x = f.d[0], w = 1 - x * x, sw = std::sqrt(w);
  return compose(f, std::acos(x), -1 / sw, -x / (w * sw), -(1 + 2 * x * x) / (w * w * sw));
}
// atan2(y, x): derivative (x y' − y x') / (x² + y²).
inline Jet atan2(const Jet& y, const Jet& x) {
  const Jet rate = (x * y.derivative() - y * x.derivative()) / (x * x + y * y);
  return Jet::integral(std::atan2(y.d[0], x.d[0]), rate);
}

}  // namespace pcsim::pantograph
