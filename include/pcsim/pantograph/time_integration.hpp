// Time response of the pantograph alone under a prescribed contact force Fc(t) ≥ 0
// (pushing the head down), as a PETSc TS problem on PETSC_COMM_SELF:
//  - rk4: first-order form y = {q, q̇, W_diss, W_ext}, ẏ = {q̇, M⁻¹(−R(t,q,q̇,0) − Fc e_c),
//    P_diss, P_ext}, TSRK/TSRK4; the work integrals ride along for the energy balance;
//  - hht: second-order form F(t,U,V,A) = R + Fc e_c with TSSetI2Function/I2Jacobian and
//    the project's "hht" TS type (thesis 3.3.2); works by the trapezoidal rule.
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

using ForceHistory = std::function<double(double)>;

TimeHistory integrate_pantograph(const PantographModel& model, const Eigen::VectorXd& q0,
                                 const Eigen::VectorXd& qd0, const ForceHistory& contact_force,
                                 const TimeOptions& options);

}  // namespace pcsim::pantograph
