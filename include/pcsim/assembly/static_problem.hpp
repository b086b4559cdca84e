// The static configuration and form-finding of the catenary as a nonlinear
// system R(x) = 0 (thesis 3.1.3).
//
// Static problem: R(q) = f_elastic(q) - f_gravity = 0 (eq. 3.5), exact
// tangent (eqs. 3.6-3.8).
// Form-finding (the "constrained equations" method of the thesis): the
// unstressed lengths of the droppers and one length scale per tension segment
// (of cable elements, or of the bars of a stitch wire) become unknowns (the
// system's extras), and the equations gain one row per height target
// (z_node = z_design) and one per tension segment (mean axial force = design
// tension), solved monolithically.
// Slack criteria are defined relative to the static equilibrium (3.1.2):
// the problem holds every bar as a plain linear bar (CatenarySystem::kTautBars;
// the mesh's criteria are not touched); finish() stores the equilibrium
// lengths and forces of the bars.
#pragma once

#include <petscmat.h>

#include <vector>

#include "pcsim/assembly/catenary_system.hpp"
#include "pcsim/catenary/results.hpp"

namespace pcsim::assembly {

// Number of extra unknowns form-finding adds to the catenary system.
PetscInt form_finding_unknowns(const catenary::CatenaryMesh& mesh);

// Copies node values (6 per node) into a global state vector of 'system'
// (whose layout may differ from the one that produced them).
void set_state_from_node_values(const CatenarySystem& system,
                                const std::vector<double>& node_values, Vec x);

class StaticProblem {
 public:
  // With form_finding the system must hold form_finding_unknowns() extras.
  StaticProblem(CatenarySystem& system, bool form_finding);
  StaticProblem(const StaticProblem&) = delete;
  StaticProblem& operator=(const StaticProblem&) = delete;

  Mat create_matrix() const;        // with the form-finding couplings
  void initial_guess(Vec x) const;  // form-finding unknowns from the design
  void residual(Vec x, Vec R);
  void jacobian(Vec x, Mat J);
  // At the solution x: unstressed lengths and bar equilibria into the mesh,
  // the result's fields (everything but the solver's own counters).
  catenary::StaticResult finish(Vec x);

  // Size of the loads [N]: max(total weight, largest design tension, 1 N);
  // the solver's force tolerances are fractions of it.
  double force_scale() const;
  // The tangent of the static residual alone at x (form-finding unknowns held
  // fixed: identity rows), into a matrix from create_matrix(). Before finish().
  void static_tangent(Vec x, Mat K);
  // After finish(): cable elements and droppers / stitch wires whose axial
  // force is below -tolerance (collective; the same list on every rank).
  struct Compressed {
    bool cable = true;
    int index = 0;     // cable or bar index
    double force = 0;  // [N], < 0
    double x = 0;      // x of the element's middle [m]
  };
  std::vector<Compressed> compressed_elements(double tolerance) const;

 private:
  void apply_unknowns(Vec x);
  void add_form_finding_terms(Vec R, Mat J);
  void add_bar_segment_terms(Vec R, Mat J);
  CatenarySystem& system_;
  bool form_finding_;
  std::vector<int> target_of_bar_;    // bar -> target index or -1
  std::vector<int> segment_count_;    // elements (or bars) per segment
  std::vector<int> segment_of_bar_;   // bar -> its tension segment or -1
  std::vector<double> height_scale_;  // residual scale of each height row [N/m]
};

}  // namespace pcsim::assembly
