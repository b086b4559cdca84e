#include "pcsim/pantograph/model.hpp"

#include <cmath>
#include <utility>

namespace pcsim::pantograph {

PantographModel::~PantographModel() = default;

void PantographModel::mass(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                           Eigen::Ref<Eigen::MatrixXd> M) const {
  const int n = dof_count();
  Eigen::MatrixXd K(n, n), C(n, n);
  tangents(t, q, qd, Eigen::VectorXd::Zero(n), K, C, M);
}

BaseMotion harmonic_base_motion(double a, double frequency_hz) {
  const double w = 2 * M_PI * frequency_hz;
  return {[a, w](double t) { return a * std::sin(w * t); },
          [a, w](double t) { return a * w * std::cos(w * t); },
          [a, w](double t) { return -a * w * w * std::sin(w * t); }};
}

void MovingFrame::set(BaseMotion motion, const std::string& kind) {
  if (!motion.displacement || !motion.velocity || !motion.acceleration)
    throw SolverError(kind + " pantograph: a base motion needs z_b, v_b and a_b");
  motion_ = std::move(motion);
}

}  // namespace pcsim::pantograph
