// Time response of the pantograph alone under a prescribed contact force Fc(t) ≥ 0
// (pushing the head down): the options of a run and the recorded history with its
// energy balance (2.30–2.34). The integrators (PETSc TS: RK4 and the project's HHT) are
// in solvers/ (pantograph_time.hpp).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "pcsim/pantograph/model.hpp"

namespace pcsim::pantograph {

struct TimeOptions {
  std::string scheme = "rk4";  // "rk4" | "hht"
  double dt = 1e-3;
  double t_end = 1.0;
  double hht_alpha = 0.05;
  int record_every = 1;  // keep every k-th step in the history
};

struct TimeHistory {
  std::vector<double> t;
  std::vector<Eigen::VectorXd> q, qd;
  std::vector<double> contact_force;  // Fc(t), downward
  std::vector<double> kinetic, potential, work_dissipative, work_external;
  long steps = 0;
  // [T+V]_t − [T+V]_0 − W_diss − W_ext at every recorded time (2.30–2.34).
  std::vector<double> energy_balance() const;
};

// Downward contact force Fc(t) [N].
using ForceHistory = std::function<double(double)>;

}  // namespace pcsim::pantograph
