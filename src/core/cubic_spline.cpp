#include "pcsim/core/cubic_spline.hpp"

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <stdexcept>

namespace pcsim {

NaturalCubicSpline::NaturalCubicSpline(std::vector<double> t, std::vector<double> y)
    : t_(std::move(t)), y_(std::move(y)), m_(t_.size(), 0.0) {
  if (t_.empty() || t_.size() != y_.size())
    throw std::invalid_argument("NaturalCubicSpline: as many values as times, at least one");
  for (std::size_t k = 1; k < t_.size(); ++k)
    if (!(t_[k] > t_[k - 1]))
      throw std::invalid_argument("NaturalCubicSpline: times must increase");
  const long interior = static_cast<long>(t_.size()) - 2;  // M_1 .. M_{n-1}
  if (interior < 1) return;                                // two samples: a straight line
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::VectorXd rhs(interior);
  for (long i = 0; i < interior; ++i) {
    const std::size_t k = static_cast<std::size_t>(i) + 1;
    const double h0 = t_[k] - t_[k - 1], h1 = t_[k + 1] - t_[k];
    entries.emplace_back(i, i, 2 * (h0 + h1));
    if (i > 0) entries.emplace_back(i, i - 1, h0);
    if (i + 1 < interior) entries.emplace_back(i, i + 1, h1);
    rhs[i] = 6 * ((y_[k + 1] - y_[k]) / h1 - (y_[k] - y_[k - 1]) / h0);
  }
  Eigen::SparseMatrix<double> system(interior, interior);
  system.setFromTriplets(entries.begin(), entries.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(system);
  const Eigen::VectorXd second = ldlt.solve(rhs);
  for (long i = 0; i < interior; ++i) m_[static_cast<std::size_t>(i) + 1] = second[i];
}

NaturalCubicSpline::Place NaturalCubicSpline::place(double time) const {
  const std::size_t k = std::upper_bound(t_.begin(), t_.end(), time) - t_.begin();
  const double h = t_[k] - t_[k - 1];
  const double a = (t_[k] - time) / h;
  return {k, h, a, 1 - a};
}

double NaturalCubicSpline::value(double time) const {
  if (outside(time)) return time <= t_.front() ? y_.front() : y_.back();
  const Place p = place(time);
  const double mk0 = m_[p.k - 1], mk1 = m_[p.k];
  return p.a * y_[p.k - 1] + p.b * y_[p.k] +
         ((p.a * p.a * p.a - p.a) * mk0 + (p.b * p.b * p.b - p.b) * mk1) * p.h * p.h / 6;
}

double NaturalCubicSpline::slope(double time) const {
  if (outside(time)) return 0.0;
  const Place p = place(time);
  return (y_[p.k] - y_[p.k - 1]) / p.h - (3 * p.a * p.a - 1) / 6 * p.h * m_[p.k - 1] +
         (3 * p.b * p.b - 1) / 6 * p.h * m_[p.k];
}

double NaturalCubicSpline::second_derivative(double time) const {
  if (outside(time)) return 0.0;
  const Place p = place(time);
  return p.a * m_[p.k - 1] + p.b * m_[p.k];
}

}  // namespace pcsim
