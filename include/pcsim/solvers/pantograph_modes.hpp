// Modes of the linearised pantograph (thesis 2.21–2.28) with SLEPc: all eigenpairs of the
// small dense pencils by the LAPACK EPS on PETSC_COMM_SELF, applied to the shift-and-invert
// operator about a target near zero frequency (accurate low modes next to the flexible
// model's 1e5 Hz beam modes; those far from the target lose ~eps ω²/|σ| relative). The Eigen
// counterparts in pcsim/pantograph/linear.hpp cross-check them.
#pragma once

#include <vector>

#include "pcsim/pantograph/linear.hpp"

namespace pcsim::solvers {

// Undamped: (K − ω² M) φ = 0 (2.23) on the null space of the restrained rows
// (pantograph::reduce_restraints); modes with ω > 0, ascending.
std::vector<pantograph::Mode> undamped_modes_slepc(const pantograph::LinearModel& lin);
// Damped: state-space form [C M; M 0] Ẏ + [K 0; 0 −M] Y = 0 (2.27) on the same null
// space; one mode per complex-conjugate pair (Im λ > 0), ascending in ω.
std::vector<pantograph::Mode> damped_modes_slepc(const pantograph::LinearModel& lin);

}  // namespace pcsim::solvers
