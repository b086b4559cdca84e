// The wind's turbulence on the modal catenary (docs/conditions.md,
// "Turbulence"): the FE level's load L [u'(t); w'(t)] on the cable elements
// (assembly/wind_terms.hpp) projected on the basis, f(t) = Phi^T L s(t), s
// the field's values at its stations. The basis keeps R = (Phi^T L)^T as
// rows (catenary::turbulence_row_keys), computed with the modes from the
// whole vectors. The field is linear in time between its samples (every
// turbulence.time_step), so f(t) = (1 - b) f_k + b f_k+1 with f_k = R^T s_k
// formed once per sample: a vector operation per residual. A load of time
// only: no tangent (the cheap path stays), its power f . eta' external work.
// The mean wind's aerodynamic damping is on the modal level as the diagonal
// of its projection (ModalOscillators, catenary::ReducedBasis::wind_damping).
#pragma once

#include <Eigen/Core>
#include <memory>

#include "pcsim/assembly/modal_catenary.hpp"
#include "pcsim/assembly/term.hpp"
#include "pcsim/assembly/wind_terms.hpp"

namespace pcsim::assembly {

class ModalWindTurbulence : public Term {
 public:
  explicit ModalWindTurbulence(ModalCatenary& catenary);
  std::string name() const override { return "wind turbulence"; }
  TangentKind tangent_kind() const override { return TangentKind::constant; }
  void add_residual(const CoupledState& state, Vec F) override;
  TermPower power(const CoupledState& state) const override;
  // The generalised force f(t) (every rank).
  const Eigen::VectorXd& force(double t) const;
  // A moving window whose x = 0 is the line's x = offset: its stations take
  // the line's field there (WindTurbulence::follow; offsets never decrease).
  void follow(double offset);

 private:
  const Eigen::VectorXd& sample(int k) const;
  ModalCatenary& catenary_;
  LineTurbulence field_;
  ModalCatenary::RowMatrix R_;  // 2 stations x modes: u' rows, then w' rows
  // The last two samples f_k (slot k % 2) and the last f(t).
  mutable int sample_index_[2] = {-1, -1};
  mutable Eigen::VectorXd samples_[2], force_;
  mutable double force_time_ = -1e300;
};

}  // namespace pcsim::assembly
