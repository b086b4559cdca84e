// Helpers of the interaction tests: a coupled system built from a run scene
// by the run pipeline's factory (simulation/catenary_setup.hpp: FE or modal,
// as `pcsim run` builds it), and TS driving.
#pragma once

#include <petscts.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "pcsim/assembly/coupled_system.hpp"
#include "pcsim/core/error.hpp"
#include "pcsim/scene/run_scene.hpp"
#include "pcsim/scene/yaml_input.hpp"
#include "pcsim/simulation/catenary_setup.hpp"
#include "pcsim/simulation/static_start.hpp"
#include "pcsim/simulation/statics.hpp"
#include "pcsim/solvers/dynamics.hpp"
#include "pcsim/solvers/hht.hpp"
#include "pcsim/solvers/statics.hpp"

namespace pcsim::testing {

inline std::string contact_data(const std::string& name) {
  return std::string(PCSIM_SOURCE_DIR) + "/tests/contact/data/" + name;
}
inline std::string pantograph_model(const std::string& name) {
  return std::string(PCSIM_SOURCE_DIR) + "/meshes/pantographs/" + name;
}

// A run scene from YAML text, read as if it were a file in tests/contact/data
// (relative paths resolve there).
inline scene::RunScene scene_from_text(const std::string& text) {
  return scene::load_run_scene(scene::InputNode::load_string(text, contact_data("inline-scene.yaml")));
}

struct StaticCatenary {
  catenary::CatenaryMesh mesh;      // with the form-found lengths
  std::vector<double> node_values;  // 6 per node
};

// The coupled system of a scene and the calls the tests make on it.
class Problem {
 public:
  explicit Problem(std::unique_ptr<assembly::CoupledSystem> system) : system_(std::move(system)) {}
  assembly::CoupledSystem& system() { return *system_; }
  Vec create_vector() const { return system_->create_vector(); }
  Mat create_matrix() const { return system_->create_matrix(); }
  std::vector<assembly::PantographSlot>& pantographs() { return system_->pantographs(); }
  PetscInt pantograph_first_dof(std::size_t p) { return pantographs()[p].first_dof; }
  simulation::StartInfo initial_state(Vec U0, Vec V0) {
    return simulation::initial_state(*system_, U0, V0);
  }
  void residual(double t, Vec U, Vec V, Vec A, Vec F) { system_->residual(t, U, V, A, F); }
  void jacobian(double t, Vec U, Vec V, Vec A, double sv, double sa, Mat J) {
    system_->jacobian(t, U, V, A, {sv, sa}, J);
  }
  contact::StepRecord record(double t, Vec U) { return system_->record(t, U); }
  double energy(double t, Vec U, Vec V) { return system_->energy(t, U, V); }

 private:
  std::unique_ptr<assembly::CoupledSystem> system_;
};

// The coupled problem of a scene (moves the scene's pantographs out);
// optionally returns the static configuration.
inline std::unique_ptr<Problem> make_problem(scene::RunScene& run,
                                             StaticCatenary* statics = nullptr,
                                             simulation::CatenarySetup* setup = nullptr) {
  auto st = simulation::static_configuration(PETSC_COMM_WORLD, run.catenary.mesh,
                                             run.catenary.form_finding, "static_");
  auto ctx = simulation::Context::of(PETSC_COMM_WORLD);
  ctx.quiet = true;
  ctx.cache_dir = "test-modal-cache";  // in the build folder
  simulation::CatenarySetup own;
  auto problem = std::make_unique<Problem>(
      simulation::make_coupled_system(ctx, run, st, setup ? *setup : own));
  if (statics) *statics = {st.mesh, st.result.node_values};
  return problem;
}

// Integrates from (U0, V0, A = 0) with the run's TS (HHT unless options say
// otherwise), leaving U0 and V0 unchanged; calls after_step(t, U, V) after
// every accepted step and at t = 0. Returns the number of steps.
inline PetscInt integrate(Problem& problem, Vec U0, Vec V0, double dt, double duration,
                          PetscInt max_steps, const std::function<void(TS)>& configure,
                          const std::function<void(double, Vec, Vec)>& after_step) {
  solvers::DynamicSolver solver(problem.system(), dt, duration);
  TS ts = solver.ts();
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
  return steps;
}

}  // namespace pcsim::testing
