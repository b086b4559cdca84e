// A natural cubic spline through samples (t_k, y_k): twice continuously
// differentiable, its second derivative linear between the samples and 0 at
// the first and last. A roof record (`base_motion: {type: file}`) read this
// way has the acceleration a moving-frame pantograph model needs
// (docs/conditions.md, "Vehicle excitation").
//
// The second derivatives M_k solve the tridiagonal system (k = 1 .. n-1)
//   h_{k-1} M_{k-1} + 2 (h_{k-1} + h_k) M_k + h_k M_{k+1}
//     = 6 ((y_{k+1} - y_k) / h_k - (y_k - y_{k-1}) / h_{k-1}),  M_0 = M_n = 0,
// symmetric positive definite (strictly diagonally dominant), solved by a
// sparse LDL^T in O(n). (Eigen's SplineFitting would build a dense n x n
// matrix: a record of 10^4 samples is common.)
#pragma once

#include <vector>

namespace pcsim {

class NaturalCubicSpline {
 public:
  // t strictly increasing, as many y; one sample gives a constant.
  NaturalCubicSpline(std::vector<double> t, std::vector<double> y);

  // On [t_0, t_n] the spline, its first and its second derivative; outside,
  // held at the first or last value with derivatives 0.
  double value(double time) const;
  double slope(double time) const;
  double second_derivative(double time) const;

 private:
  // The interval [t_{k-1}, t_k] holding `time` (t_0 < time < t_n), and the
  // weights A = (t_k - time) / h, B = 1 - A.
  struct Place {
    std::size_t k;
    double h, a, b;
  };
  Place place(double time) const;
  bool outside(double time) const {
    return t_.size() < 2 || time <= t_.front() || time >= t_.back();
  }

  std::vector<double> t_, y_, m_;  // m_: second derivatives at the samples
};

}  // namespace pcsim
