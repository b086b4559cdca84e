// Forces prescribed from outside the model, changed between time steps by
// the caller (a co-simulation or hardware-in-the-loop partner through the
// step-wise interface, simulation/stepper.hpp): a vertical force on each
// pantograph's contact point (head), positive upwards. Constant within a
// step, so the tangent is zero and the term keeps the cheap path; its power
// f q_c' is external work (energy balance). Present only when a step-wise
// run asks for it: what is off is not assembled.
#pragma once

#include <vector>

#include "pcsim/assembly/coupled_state.hpp"
#include "pcsim/assembly/term.hpp"

namespace pcsim::assembly {

class PrescribedHeadForces : public Term {
 public:
  explicit PrescribedHeadForces(const std::vector<PantographSlot>& pantographs);
  std::string name() const override { return "prescribed head forces"; }
  TangentKind tangent_kind() const override { return TangentKind::constant; }
  bool adds_by_set_values() const override { return true; }
  // R[q_c] -= f (on the last rank, where the pantographs' unknowns live).
  void add_residual(const CoupledState& state, Vec F) override;
  TermPower power(const CoupledState& state) const override;

  // The force on pantograph p's head [N, upwards] from the next step on
  // (identical on every rank).
  void set(std::size_t p, double force_N) { force_.at(p) = force_N; }
  double force(std::size_t p) const { return force_.at(p); }

 private:
  const std::vector<PantographSlot>& pantographs_;
  std::vector<double> force_;
};

}  // namespace pcsim::assembly
