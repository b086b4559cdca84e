// Helpers of the interaction tests: a coupled problem built from a run scene
// exactly as `pcsim run` builds it (src/app/cmd_run.cpp), and TS driving.
#pragma once

#include <petscts.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "pcsim/assembly/catenary_system.hpp"
#include "pcsim/catenary/statics.hpp"
#include "pcsim/contact/interaction.hpp"
#include "pcsim/contact/run_scene.hpp"
#include "pcsim/error.hpp"
#include "pcsim/scene/yaml_input.hpp"
#include "pcsim/solvers/hht.hpp"

namespace pcsim::testing {

inline std::string contact_data(const std::string& name) {
  return std::string(PCSIM_SOURCE_DIR) + "/tests/contact/data/" + name;
}
inline std::string pantograph_model(const std::string& name) {
  return std::string(PCSIM_SOURCE_DIR) + "/meshes/pantographs/" + name;
}

// A run scene from YAML text, read as if it were a file in tests/contact/data
// (relative paths resolve there).
inline contact::RunScene scene_from_text(const std::string& text) {
  return contact::load_run_scene(InputNode::load_string(text, contact_data("inline-scene.yaml")));
}

struct StaticCatenary {
  catenary::CatenaryMesh mesh;      // with the form-found lengths
  std::vector<double> node_values;  // 6 per node
};

// Static configuration with form-finding as the scene says (as `pcsim run`).
inline StaticCatenary solve_catenary_statics(const catenary::CatenaryScene& scene) {
  const PetscInt extra = scene.form_finding ? catenary::form_finding_unknowns(scene.mesh) : 0;
  assembly::CatenarySystem system(PETSC_COMM_WORLD, scene.mesh, extra);
  Vec x = system.create_vector();
  system.design_state(x);
  auto result = catenary::solve_static(system, x, scene.form_finding, "static_");
  PCSIM_PETSC(VecDestroy(&x));
  if (!result.converged) throw SolverError("test statics did not converge");
  return {system.mesh(), result.node_values};
}

// The coupled problem of a scene (moves the scene's pantographs out).
inline std::unique_ptr<contact::InteractionProblem> make_problem(
    contact::RunScene& run, StaticCatenary* statics = nullptr) {
  auto st = solve_catenary_statics(run.catenary);
  auto problem = std::make_unique<contact::InteractionProblem>(
      PETSC_COMM_WORLD, st.mesh, st.node_values, std::move(run.pantographs), run.effects,
      run.contact_stiffness);
  if (statics) *statics = std::move(st);
  return problem;
}

// Integrates from (U0, V0, A = 0) with the problem's TS (HHT unless options
// say otherwise), leaving U0 and V0 unchanged; calls after_step(t, U, V)
// after every accepted step and at t = 0. Returns the number of steps.
inline PetscInt integrate(contact::InteractionProblem& problem, Vec U0, Vec V0, double dt,
                          double duration, PetscInt max_steps,
                          const std::function<void(TS)>& configure,
                          const std::function<void(double, Vec, Vec)>& after_step) {
  TS ts = problem.create_ts(dt, duration);
  PCSIM_PETSC(TSSetMaxSteps(ts, max_steps));
  if (configure) configure(ts);
  // The TS integrates in the vectors it is given: copies keep U0, V0 intact.
  Vec U, V;
  PCSIM_PETSC(VecDuplicate(U0, &U));
  PCSIM_PETSC(VecDuplicate(V0, &V));
  PCSIM_PETSC(VecCopy(U0, U));
  PCSIM_PETSC(VecCopy(V0, V));
  PCSIM_PETSC(TS2SetSolution(ts, U, V));
  PCSIM_PETSC(VecDestroy(&U));  // the TS holds references
  PCSIM_PETSC(VecDestroy(&V));
  Vec A0 = problem.create_vector();
  PCSIM_PETSC(VecSet(A0, 0.0));
  solvers::hht_set_initial_acceleration(ts, A0);
  PCSIM_PETSC(VecDestroy(&A0));
  after_step(0.0, U0, V0);
  PetscInt steps = 0;
  PetscReal t = 0;
  while (steps < max_steps && t < duration - 1e-12) {
    PCSIM_PETSC(TSStep(ts));
    TSConvergedReason reason;
    PCSIM_PETSC(TSGetConvergedReason(ts, &reason));
    if (reason < 0) throw SolverError(std::string("TS failed: ") + TSConvergedReasons[reason]);
    PCSIM_PETSC(TSGetTime(ts, &t));
    PCSIM_PETSC(TS2GetSolution(ts, &U, &V));
    after_step(t, U, V);
    ++steps;
  }
  PCSIM_PETSC(TSDestroy(&ts));
  return steps;
}

}  // namespace pcsim::testing
