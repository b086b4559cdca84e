// Static configuration and form-finding of the catenary (thesis 3.1.3) by
// PETSc SNES: Newton with the exact Jacobian of assembly::StaticProblem and a
// direct solve (MUMPS: the form-finding system has zero diagonal entries).
// Every -snes_*, -ksp_*, -pc_* option applies (with the given prefix).
#pragma once

#include <vector>

#include "pcsim/assembly/catenary_system.hpp"
#include "pcsim/catenary/results.hpp"

namespace pcsim::solvers {

// Solves the static problem (form_finding false) or the form-finding problem
// (true; 'system' built with assembly::form_finding_unknowns(mesh) extras).
// On return the mesh of 'system' holds the found unstressed lengths and every
// bar's equilibrium length and force, and 'x' the static configuration.
// Convergence is judged by forces scaled to the loads (max of the total weight
// and the largest design tension): ||R||_2 < 1e-8 of it (or abs_tolerance [N]
// when given: a loaded problem whose round-off floor lies above it can pass a
// larger one), or Newton stagnated at rounding with max |R| < 1e-6 of it;
// otherwise SolverError. After convergence (equilibrium_checks), result.warnings
// names cables and droppers in compression and a tangent that is not positive
// definite (MUMPS LDL^T inertia); a cable in compression after form-finding is
// an InputError on the design's 'wires'.
catenary::StaticResult solve_static(assembly::CatenarySystem& system, Vec x, bool form_finding,
                                    const char* options_prefix = nullptr, double abs_tolerance = 0,
                                    bool equilibrium_checks = true);

}  // namespace pcsim::solvers
