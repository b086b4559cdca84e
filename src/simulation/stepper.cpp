#include "pcsim/simulation/stepper.hpp"

#include <petscts.h>

#include <array>
#include <cmath>

#include "pcsim/assembly/coupled_system.hpp"
#include "pcsim/assembly/prescribed_forces.hpp"
#include "pcsim/core/error.hpp"
#include "pcsim/simulation/catenary_setup.hpp"
#include "pcsim/simulation/moving_window.hpp"
#include "pcsim/simulation/run_session.hpp"
#include "pcsim/simulation/run_setup.hpp"
#include "pcsim/simulation/static_start.hpp"
#include "pcsim/simulation/statics.hpp"
#include "pcsim/solvers/dynamics.hpp"

namespace pcsim::simulation {

namespace {
// A base motion set step-wise: (z_b, v_b, a_b) before and after the time it
// was set, so that the step's residual at its end time reads the new values
// and the HHT alpha-term at its start (t <= since) the old ones, as a
// scene's base_motion would be read.
struct HeldBase {
  std::array<double, 3> before{}, after{};
  double since = -1e300;
  const std::array<double, 3>& at(double t) const { return t > since ? after : before; }
};
}  // namespace

struct Stepper::Impl {
  Context ctx;
  scene::RunScene& scene;
  RunSetup prepared;  // statics, catenary facts
  assembly::CoupledSystem* system = nullptr;
  assembly::PrescribedHeadForces* forces = nullptr;
  std::vector<std::shared_ptr<HeldBase>> bases;  // per pantograph
  std::unique_ptr<solvers::DynamicSolver> solver;
  std::unique_ptr<MovingWindow> window;  // the scene's 'window' (or the modal level's)
  Impl(const Context& c, scene::RunScene& s) : ctx(c), scene(s) {}
  // After every accepted step: the moving window shifts when due (collective).
  static PetscErrorCode window_after_step(TS ts);
};

PetscErrorCode Stepper::Impl::window_after_step(TS ts) {
  PCSIM_CALLBACK_BEGIN
  Impl* s;
  PCSIM_PETSC(TSGetApplicationContext(ts, &s));
  PetscReal t;
  PCSIM_PETSC(TSGetTime(ts, &t));
  s->window->after_step(t, *s->solver);
  PCSIM_CALLBACK_END
}

Stepper::Stepper(const Context& ctx, scene::RunScene& scene)
    : impl_(std::make_unique<Impl>(ctx, scene)) {
  auto& s = *impl_;
  s.prepared = set_up_run(ctx, scene, nullptr);
  s.system = s.prepared.system.get();
  if (scene.window)  // as simulation::run: the line's supports for the records
    s.window =
        std::make_unique<MovingWindow>(*scene.window, *s.system, scene.catenary.mesh.support_x);
  s.forces = static_cast<assembly::PrescribedHeadForces*>(&s.system->add_load_term(
      std::make_unique<assembly::PrescribedHeadForces>(s.system->pantographs())));
  Vec U0 = s.system->create_vector(), V0 = s.system->create_vector();
  initial_state(*s.system, U0, V0);
  s.solver = make_run_solver(scene, *s.system);
  s.solver->set_initial_state(U0, V0);
  if (s.window) {
    PCSIM_PETSC(TSSetApplicationContext(s.solver->ts(), impl_.get()));
    PCSIM_PETSC(TSSetPostStep(s.solver->ts(), Impl::window_after_step));
  }
  PCSIM_PETSC(VecDestroy(&U0));
  PCSIM_PETSC(VecDestroy(&V0));
  read();
}

Stepper::~Stepper() = default;

double Stepper::end_time() const {
  return impl_->scene.duration();
}

bool Stepper::finished() const {
  return reading_.t >= end_time() * (1 - 1e-12);
}

long Stepper::advance(long n) {
  TS ts = impl_->solver->ts();
  const long before = reading_.step;
  if (n <= 0 || finished()) return 0;
  PCSIM_PETSC(TSSetMaxSteps(ts, static_cast<PetscInt>(before + n)));
  const PetscErrorCode solved = TSSolve(ts, nullptr);
  raise_if_step_failed(ts, solved, reading_.t, ", and the forces set on the heads");
  read();
  return reading_.step - before;
}

void Stepper::read() {
  TS ts = impl_->solver->ts();
  PetscInt step;
  PetscReal t;
  Vec U;
  PCSIM_PETSC(TSGetStepNumber(ts, &step));
  PCSIM_PETSC(TSGetTime(ts, &t));
  PCSIM_PETSC(TSGetSolution(ts, &U));
  auto record = impl_->system->record(t, U);          // complete on rank 0
  if (impl_->window) impl_->window->to_line(record);  // the line's stations
  const int n = static_cast<int>(impl_->system->pantographs().size());
  std::vector<double> values(3 * n, 0.0);
  if (impl_->ctx.rank == 0)
    for (int p = 0; p < n; ++p) {
      values[p] = record.contact_force.at(p);
      values[n + p] = record.contact_x.at(p);
      values[2 * n + p] = record.head_z.empty() ? 0.0 : record.head_z.at(p);
    }
  MPI_Bcast(values.data(), 3 * n, MPI_DOUBLE, 0, impl_->ctx.comm);
  reading_.t = t;
  reading_.step = step;
  reading_.contact_force.assign(values.begin(), values.begin() + n);
  reading_.contact_x.assign(values.begin() + n, values.begin() + 2 * n);
  reading_.head_z.assign(values.begin() + 2 * n, values.end());
}

std::vector<std::string> Stepper::pantograph_names() const {
  std::vector<std::string> names;
  for (const auto& slot : impl_->system->pantographs()) names.push_back(slot.run.name);
  return names;
}

namespace {
void check_index(std::size_t pantograph, std::size_t count) {
  if (pantograph >= count)
    throw InputError("step-wise run", "pantograph",
                     "index " + std::to_string(pantograph) + " out of range (" +
                         std::to_string(count) + " pantographs)");
}
}  // namespace

void Stepper::set_head_force(std::size_t pantograph, double force_N) {
  check_index(pantograph, impl_->system->pantographs().size());
  impl_->forces->set(pantograph, force_N);
  impl_->solver->residual_changed();  // the next step's alpha-term reads the new force
}

// The model reads the held values (pantograph::BaseMotion): a lumped model a
// load k z_b + c v_b on the lowest stage, a DSA-380 model (moving frame) the
// inertial load of a_b on its bodies and z_b in the head's height; the power
// counted as external work.
void Stepper::set_base_motion(std::size_t pantograph, double displacement_m, double velocity_m_s,
                              double acceleration_m_s2) {
  auto& slots = impl_->system->pantographs();
  check_index(pantograph, slots.size());
  auto& slot = slots[pantograph];
  const bool moving_frame = slot.model->moving_frame();
  if (slot.model->base_support().dof < 0 && !moving_frame)
    throw InputError("step-wise run", "pantograph",
                     "'" + slot.run.name + "': its " + slot.model->kind() +
                         " model takes no base motion (lumped and DSA-380 models do)");
  if (moving_frame && std::isnan(acceleration_m_s2))
    throw InputError("step-wise run", "base motion",
                     "'" + slot.run.name + "': its " + slot.model->kind() +
                         " model's moving frame needs the base's acceleration too");
  if (!std::isfinite(displacement_m) || !std::isfinite(velocity_m_s) ||
      (moving_frame && !std::isfinite(acceleration_m_s2)))
    throw InputError("step-wise run", "base motion", "not a finite number");
  auto& bases = impl_->bases;
  if (bases.size() < slots.size()) bases.resize(slots.size());
  if (!bases[pantograph]) {
    auto held = std::make_shared<HeldBase>();
    bases[pantograph] = held;
    pantograph::BaseMotion motion;  // held values
    motion.displacement = [held](double t) { return held->at(t)[0]; };
    motion.velocity = [held](double t) { return held->at(t)[1]; };
    if (moving_frame) motion.acceleration = [held](double t) { return held->at(t)[2]; };
    slot.model->set_base_motion(std::move(motion));
  }
  HeldBase& held = *bases[pantograph];
  held.before = held.at(reading_.t);
  held.after = {displacement_m, velocity_m_s, moving_frame ? acceleration_m_s2 : 0.0};
  held.since = reading_.t;
}

double Stepper::head_force(std::size_t pantograph) const {
  return impl_->forces->force(pantograph);
}

}  // namespace pcsim::simulation
