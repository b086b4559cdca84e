#include "pcsim/assembly/modal_wind.hpp"

#include "pcsim/assembly/coupled_state.hpp"
#include "pcsim/catenary/wind.hpp"
#include "pcsim/core/error.hpp"

namespace pcsim::assembly {

ModalWindTurbulence::ModalWindTurbulence(ModalCatenary& catenary)
    : catenary_(catenary), field_(catenary.mesh()) {
  const auto keys = catenary::turbulence_row_keys(catenary.mesh());
  const long m = catenary.catenary_dofs();
  R_.resize(static_cast<long>(keys.size()), m);
  for (std::size_t j = 0; j < keys.size(); ++j)
    R_.row(static_cast<long>(j)) = catenary.key_row(keys[j]);
  force_.setZero(m);
}

// The basis's rows belong to the window's stations: they take the line's
// field at their new place.
void ModalWindTurbulence::follow(double offset) {
  field_.follow(offset);
  sample_index_[0] = sample_index_[1] = -1;
  force_time_ = -1e300;
}

// f_k = R^T s_k: the stations' u' (rows 0..n-1) and w' (n..2n-1) at sample k.
const Eigen::VectorXd& ModalWindTurbulence::sample(int k) const {
  Eigen::VectorXd& f = samples_[k % 2];
  if (sample_index_[k % 2] == k) return f;
  const int n = field_.u.nx;
  Eigen::VectorXd s(2 * n);
  for (int i = 0; i < n; ++i) s[i] = field_.u.at(i, k), s[n + i] = field_.w.at(i, k);
  f.noalias() = R_.transpose() * s;
  sample_index_[k % 2] = k;
  return f;
}

// As catenary::WindSeries::interpolate in time (periodic).
const Eigen::VectorXd& ModalWindTurbulence::force(double t) const {
  if (t == force_time_) return force_;
  const catenary::Bracket k = catenary::sample_bracket(t, field_.u.dt, field_.u.nt);
  const Eigen::VectorXd& f0 = sample(k.lo);
  const Eigen::VectorXd& f1 = sample(k.hi);
  force_ = (1 - k.w) * f0 + k.w * f1;
  force_time_ = t;
  return force_;
}

void ModalWindTurbulence::add_residual(const CoupledState& state, Vec F) {
  if (!catenary_.on_owner()) return;
  const Eigen::VectorXd& f = force(state.t);
  PetscScalar* a;
  PCSIM_PETSC(VecGetArray(F, &a));
  Eigen::Map<Eigen::VectorXd>(a, f.size()) -= f;  // a load lowers the residual
  PCSIM_PETSC(VecRestoreArray(F, &a));
}

TermPower ModalWindTurbulence::power(const CoupledState& state) const {
  TermPower p;
  if (!state.V) return p;
  const Eigen::VectorXd& f = force(state.t);
  if (catenary_.on_owner()) {
    const PetscScalar* v;
    PCSIM_PETSC(VecGetArrayRead(state.V, &v));
    p.external = f.dot(Eigen::Map<const Eigen::VectorXd>(v, f.size()));
    PCSIM_PETSC(VecRestoreArrayRead(state.V, &v));
  }
  MPI_Allreduce(MPI_IN_PLACE, &p.external, 1, MPI_DOUBLE, MPI_SUM, catenary_.comm());
  return p;
}

}  // namespace pcsim::assembly
