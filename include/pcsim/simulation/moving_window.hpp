// The moving window of `pcsim run` (scene key 'window'; catenary/window.hpp,
// docs/scaling.md): after every accepted step, when the leading pantograph
// (the one furthest along; the only one, or the front of a train) has left
// its two spans (scene::RunWindow::shift_spans), the catenary's dynamic state
// (displacement from the static configuration, velocity, acceleration) moves
// back by two spans, the two new front spans start static, and every
// pantograph's contact point moves back with it. Records are turned into line
// coordinates. The FE state moves DOF by DOF; the modal state by the
// basis' shift (eta' = P eta: catenary::ReducedBasis::shift).
#pragma once

#include <petscvec.h>

#include <memory>
#include <vector>

#include "pcsim/assembly/coupled_system.hpp"
#include "pcsim/assembly/fe_catenary.hpp"
#include "pcsim/assembly/modal_catenary.hpp"
#include "pcsim/contact/records.hpp"
#include "pcsim/output/run_stream.hpp"
#include "pcsim/scene/run_scene.hpp"
#include "pcsim/solvers/dynamics.hpp"

namespace pcsim::simulation {

class SpinningHelper;  // spinning_helper.hpp

class MovingWindow {
 public:
  // system: built on the window's mesh (ends released). line_support_x: the
  // line's supports. Collective.
  MovingWindow(const scene::RunWindow& window, assembly::CoupledSystem& system,
               std::vector<double> line_support_x);
  ~MovingWindow();
  // After an accepted step at time t (collective): shifts if due.
  void after_step(double t, solvers::DynamicSolver& solver);
  // A record of the window as the line's: contact stations, every line support.
  void to_line(contact::StepRecord& record) const;
  // The layout's supports: the line's, with static heights of the window's.
  void set_line_supports(output::RunLayout& layout) const;
  int shifts() const { return shifts_; }
  // A restart (before the checkpoint's state is restored; collective): the
  // window as the checkpointed run left it after 'shifts' shifts (0 to
  // RunWindow::max_shifts()).
  void resume(int shifts);
  // A core to spare (collective choice, RunSession): a large modal shift's
  // pass over P on two threads, the second started a few milliseconds ahead
  // of the shift. Each row is one thread's: the state is the same bits.
  void use_spare_core(bool spare);
  double offset() const { return 2.0 * span_length_ * shifts_; }

 private:
  void shift(solvers::DynamicSolver& solver);
  void moved(int count);
  void fe_source(const assembly::FECatenary& fe);
  void shift_fe(solvers::DynamicState& s) const;
  void shift_modal(solvers::DynamicState& s) const;
  void wake_helper_ahead(double x);
  void set_pins();

  assembly::CoupledSystem& system_;
  assembly::FECatenary* fe_ = nullptr;  // one of the two
  assembly::ModalCatenary* modal_ = nullptr;
  int line_spans_ = 0, window_spans_ = 0;
  double span_length_ = 0;
  double shift_at_x_ = 0;  // window station where the leading pantograph leaves its spans
  std::size_t lead_ = 0;   // the leading pantograph (largest start_x)
  int max_shifts_ = 0, shifts_ = 0;
  std::unique_ptr<SpinningHelper> helper_;  // rank 0 of a modal window with a core to spare
  double last_x_ = 0, last_wall_ = 0;       // the leading contact point and the wall time [s]
  int window_supports_ = 0;
  std::vector<double> line_support_x_, line_static_z_, window_static_z_;
  // Rank 0: catenary DOF g takes the displacement of source_[g] (-1: static);
  // static_U_ the static configuration in the global order.
  std::vector<PetscInt> source_;
  std::vector<double> static_U_;
};

}  // namespace pcsim::simulation
