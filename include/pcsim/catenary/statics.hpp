// Static configuration and form-finding of the catenary (thesis 3.1.3).
//
// Static problem: R(q) = f_elastic(q) - f_gravity = 0 (eq. 3.5), Newton with
// the exact tangent (eqs. 3.6-3.8) through PETSc SNES.
// Form-finding (the "constrained equations" method of the thesis): the
// unstressed lengths of the droppers and one length scale per tension segment
// become unknowns, and the equations gain one row per height target
// (z_node = z_design) and one per tension segment (mean axial force = design
// tension). The augmented system is solved monolithically by the same SNES.
#pragma once

#include <petscsnes.h>

#include <memory>
#include <string>
#include <vector>

#include "pcsim/assembly/catenary_system.hpp"

namespace pcsim::catenary {

struct StaticResult {
  bool converged = false;
  int snes_iterations = 0;
  int linear_iterations = 0;
  std::string converged_reason;
  std::vector<double> residual_history;  // ||R|| per Newton iteration
  double max_height_error_m = 0;         // over the height targets
  double max_tension_error_rel = 0;      // over the tension segments
  std::vector<double> target_heights;    // z of each target node
  std::vector<double> segment_tensions;  // mean axial force of each segment
  std::vector<double> bar_forces;        // axial force of every bar
  std::vector<double> bar_lengths;       // deformed length of every bar
  std::vector<double> node_values;       // 6 per node (r, r'), every rank
  double wall_time_s = 0;
};

// Number of extra unknowns form-finding adds to the catenary system.
PetscInt form_finding_unknowns(const CatenaryMesh& mesh);

// Solves the static problem (form_finding = false) or the form-finding
// problem (true; then 'system' must have been built with
// form_finding_unknowns(mesh) extra DOFs). On return the mesh of 'system'
// holds the found unstressed lengths and every bar's equilibrium length and
// force, and 'x' the static configuration. The SNES takes options with the
// given prefix (default none: -snes_*, -ksp_*, -pc_*).
StaticResult solve_static(assembly::CatenarySystem& system, Vec x, bool form_finding,
                          const char* options_prefix = nullptr);

// Copies node values (6 per node, as StaticResult::node_values) into a
// global state vector of 'system' (whose layout may differ from the one that
// produced them).
void set_state_from_node_values(const assembly::CatenarySystem& system,
                                const std::vector<double>& node_values, Vec x);

}  // namespace pcsim::catenary
