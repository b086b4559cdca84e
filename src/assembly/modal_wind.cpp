#include "pcsim/assembly/modal_wind.hpp"

#include <cmath>

#include "pcsim/assembly/coupled_state.hpp"
#include "pcsim/catenary/wind.hpp"
#include "pcsim/core/error.hpp"

namespace pcsim::assembly {

ModalWindTurbulence::ModalWindTurbulence(ModalCatenary& catenary)
    : catenary_(catenary), field_(turbulence_field(catenary.mesh())) {
  const auto& t = catenary.mesh().conditions.wind.turbulence;
  const TurbulenceSpecs specs = turbulence_specs(catenary.mesh());
  const double dx = field_.u.dx;
  u_generator_ =
      std::make_unique<catenary::TurbulenceGenerator>(specs.u, dx, t.time_step, t.time_points);
  w_generator_ =
      std::make_unique<catenary::TurbulenceGenerator>(specs.w, dx, t.time_step, t.time_points);
  const auto keys = catenary::turbulence_row_keys(catenary.mesh());
  const long m = catenary.catenary_dofs();
  R_.resize(static_cast<long>(keys.size()), m);
  for (std::size_t j = 0; j < keys.size(); ++j)
    R_.row(static_cast<long>(j)) = catenary.key_row(keys[j]);
  force_.setZero(m);
}

// The basis's rows belong to the window's stations x0 + j dx: each takes the
// line's field at x0 + j dx + offset, linear between the line's stations
// (exactly a line station's when the shift is a multiple of dx).
void ModalWindTurbulence::follow(double offset) {
  const double x0 = field_.u.x0, dx = field_.u.dx;
  const int n = field_.u.nx;
  const long first = static_cast<long>(std::floor(offset / dx));
  const int count = n + 1;  // covers x0 + offset .. x0 + (n - 1) dx + offset
  const double line_x0 = x0 + first * dx - offset;  // in the window's coordinates
  const auto take = [&](catenary::TurbulenceGenerator& generator, catenary::WindSeries& series) {
    const catenary::WindSeries line = generator.stations(first, count, line_x0, dx);
    for (int j = 0; j < n; ++j) {
      const catenary::Bracket b = catenary::station_bracket(x0 + j * dx, line_x0, dx, count);
      for (int k = 0; k < series.nt; ++k)
        series.values[static_cast<std::size_t>(j) * series.nt + k] =
            b.w == 0 ? line.at(b.lo, k) : (1 - b.w) * line.at(b.lo, k) + b.w * line.at(b.hi, k);
    }
  };
  take(*u_generator_, field_.u);
  take(*w_generator_, field_.w);
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
