// Time integration of the pantograph alone under a prescribed contact force Fc(t) ≥ 0
// (pushing the head down), as a PETSc TS problem on PETSC_COMM_SELF:
//  - rk4: first-order form y = {q, q̇, W_diss, W_ext}, ẏ = {q̇, M⁻¹(−R(t,q,q̇,0) − Fc e_c),
//    P_diss, P_ext}, TSRK/TSRK4; the work integrals ride along for the energy balance;
//  - hht: second-order form F(t,U,V,A) = R + Fc e_c with TSSetI2Function/I2Jacobian and
//    the project's "hht" TS type (thesis 3.3.2), or with -pantograph_ts_type alpha2
//    PETSc's generalised-α set to the same HHT; works by the trapezoidal rule.
// Options prefix "pantograph_".
#pragma once

#include <string>

#include "pcsim/pantograph/model.hpp"
#include "pcsim/pantograph/time_history.hpp"

namespace pcsim::solvers {

// The TS type of the hht scheme from -pantograph_ts_type: "hht" (default) or
// "alpha2"; any other is an InputError naming the option.
std::string pantograph_ts_type();

pantograph::TimeHistory integrate_pantograph(const pantograph::PantographModel& model,
                                             const Eigen::VectorXd& q0, const Eigen::VectorXd& qd0,
                                             const pantograph::ForceHistory& contact_force,
                                             const pantograph::TimeOptions& options);

}  // namespace pcsim::solvers
