// Uplift characteristic of the DSA-380 bellows: target torque, pressure loop, energies.
#include "pcsim/pantograph/bellows.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "pcsim/core/error.hpp"
#include "pcsim/pantograph/dsa380.hpp"

namespace pcsim::pantograph {

namespace {
// Linear interpolation of (x, y), constant beyond the ends; slope in *dy.
double interpolate(const std::vector<double>& x, const std::vector<double>& y, double v,
                   double* dy) {
  if (v <= x.front() || v >= x.back()) {
    *dy = 0;
    return v <= x.front() ? y.front() : y.back();
  }
  const std::size_t k = std::upper_bound(x.begin(), x.end(), v) - x.begin();
  *dy = (y[k] - y[k - 1]) / (x[k] - x[k - 1]);
  return y[k - 1] + *dy * (v - x[k - 1]);
}
}  // namespace

Bellows::Bellows(BellowsParameters params, bool follows_characteristic, double aero_force)
    : b_(std::move(params)), on_(follows_characteristic), aero_(aero_force) {}

void Bellows::set_reference(const Dsa380Parameters& p, double theta0, double contact_force,
                            double working_height) {
  force0_ = contact_force;
  scale_ = 1;
  if (!b_.heights.empty()) {
    double slope;
    scale_ = contact_force / interpolate(b_.heights, b_.forces, working_height, &slope);
  }
  torque0_ = holding_torque(p, theta0, nullptr, nullptr);
  referenced_ = true;
}

double Bellows::force(double h, double* dforce) const {
  if (b_.heights.empty()) {
    if (dforce) *dforce = 0;
    return force0_;
  }
  double slope;
  const double f = interpolate(b_.heights, b_.forces, h, &slope);
  if (dforce) *dforce = scale_ * slope;
  return scale_ * f;
}

double Bellows::height_below(const Dsa380Parameters& p, double top) const {
  // h = y5(θ) + L7p − z(m7 g + F(h) − F_aero) by Newton (z' F' is small: ~1e-2).
  const double weight = p.m[6] * p.g - aero_;
  double h = top - dsa380_head_descent(p, weight + force0_, nullptr);
  for (int it = 0; it < 50; ++it) {
    double dF, dz;
    const double z = dsa380_head_descent(p, weight + force(h, &dF), &dz);
    const double g = h - top + z;
    if (std::abs(g) < 1e-13) return h;
    h -= g / (1 + dz * dF);
  }
  throw SolverError("bellows: height on the uplift characteristic did not converge");
}

double Bellows::holding_torque(const Dsa380Parameters& p, double theta, double* derivative,
                               const Dsa380Kinematics* at) const {
  std::optional<Dsa380Kinematics> own;  // constructed only when none is given
  const Dsa380Kinematics& k = at ? *at : own.emplace(dsa380_kinematics(p, theta));
  double dF = 0, dz = 0, F = force0_;
  if (!b_.heights.empty()) {
    F = force(height_below(p, k.y5[0] + p.L7p), &dF);  // k: not computed again
    dsa380_head_descent(p, p.m[6] * p.g + F - aero_, &dz);
  }
  const double load = p.m[6] * p.g + F - aero_;  // carried by the head springs (2.12)
  if (derivative) {
    const double dh = k.y5[1] / (1 + dz * dF);  // dh/dθ along the characteristic
    *derivative = p.kr + k.gravity_energy[2] + load * k.y5[2] + dF * dh * k.y5[1];
  }
  return p.kr * (theta - p.theta_r0) + k.gravity_energy[1] + load * k.y5[1];  // (2.14)
}

double Bellows::torque_change(const Dsa380Parameters& p, double theta, double* derivative,
                              const Dsa380Kinematics* at) const {
  if (!on_ || !referenced_) {
    if (derivative) *derivative = 0;
    return 0;
  }
  return holding_torque(p, theta, derivative, at) - torque0_;
}

void Bellows::add_residual(const Dsa380Parameters& p, int theta, int m, const Eigen::VectorXd& q,
                           const Eigen::VectorXd& qd, const Eigen::VectorXd& qdd,
                           Eigen::Ref<Eigen::VectorXd> R, const Dsa380Kinematics* at) const {
  if (!on_) return;
  const double dM = torque_change(p, q[theta], nullptr, at);
  if (m < 0) {
    R[theta] -= dM;
    return;
  }
  const double t1 = b_.time_constant, t2 = b_.valve_time_constant;
  R[theta] -= q[m];
  R[m] = t1 * t2 * qdd[m] + (t1 + t2) * qd[m] + q[m] - dM;
}

double Bellows::kinetic_energy(int m, const Eigen::VectorXd& qd) const {
  return m < 0 ? 0.0 : 0.5 * b_.time_constant * b_.valve_time_constant * qd[m] * qd[m];
}

double Bellows::potential_energy(int m, const Eigen::VectorXd& q) const {
  return m < 0 ? 0.0 : 0.5 * q[m] * q[m];
}

void Bellows::add_power(const Dsa380Parameters& p, int theta, int m, const Eigen::VectorXd& q,
                        const Eigen::VectorXd& qd, PowerSplit* power) const {
  if (!on_) return;
  const double dM = torque_change(p, q[theta], nullptr);
  power->external += (m < 0 ? dM : q[m]) * qd[theta];
  if (m < 0) return;
  power->external += qd[m] * dM;
  power->dissipative -= (b_.time_constant + b_.valve_time_constant) * qd[m] * qd[m];
}

}  // namespace pcsim::pantograph
