#include "pcsim/assembly/interaction_terms.hpp"

#include <mpi.h>

#include <Eigen/Dense>

#include "pcsim/core/error.hpp"
#include "pcsim/core/profiling.hpp"

namespace pcsim::assembly {

namespace {
using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

std::vector<PetscInt> dof_range(const PantographSlot& slot) {
  std::vector<PetscInt> idx(slot.dof_count());
  for (int i = 0; i < slot.dof_count(); ++i) idx[i] = slot.first_dof + i;
  return idx;
}

double sum_over_ranks(MPI_Comm comm, double local) {
  double total = 0;
  MPI_Allreduce(&local, &total, 1, MPI_DOUBLE, MPI_SUM, comm);
  return total;
}
}  // namespace

// ------------------------------------------------------- pantograph ----

void PantographTerm::add_residual(const CoupledState& state, Vec F) {
  if (!state.on_last_rank()) return;
  const auto& model = *slot_.model;
  Eigen::VectorXd R(model.dof_count());
  model.residual(state.t, state.q(index_), state.qd(index_), state.qdd(index_), R);
  // Ramp-up (thesis 3.3.1): the head carries (1 - ramp) F0 downwards.
  R[model.contact_dof()] += (1.0 - slot_.run.ramp_factor(state.t)) * slot_.run.static_force;
  const auto idx = dof_range(slot_);
  PCSIM_PETSC(VecSetValues(F, model.dof_count(), idx.data(), R.data(), ADD_VALUES));
}

// dF/dA A = M q'' on the pantograph's own unknowns (owned by one rank); a
// nonlinear model's M(q) at the state (thesis 3.27-3.30: the DSA-380's
// residual is affine in q'', M its tangent in q'').
void PantographTerm::add_inertia(const CoupledState& state, Vec A, Vec F) const {
  PetscInt begin = 0, end = 0;
  PCSIM_PETSC(VecGetOwnershipRange(A, &begin, &end));
  if (slot_.first_dof < begin || slot_.first_dof >= end) return;
  const auto& model = *slot_.model;
  const int n = model.dof_count();
  const auto idx = dof_range(slot_);
  Eigen::VectorXd qdd(n), force(n);
  PCSIM_PETSC(VecGetValues(A, n, idx.data(), qdd.data()));
  if (model.sparse_mass(state.t, state.q(index_), state.qd(index_), sparse_mass_)) {
    force = sparse_mass_ * qdd;  // the flexible DSA-380: no dense 150 x 150 at every step
  } else {
    if (!model.is_linear() || mass_.rows() != n) {  // a linear model's is constant
      mass_.resize(n, n);
      model.mass(state.t, state.q(index_), state.qd(index_), mass_);
    }
    force = mass_ * qdd;
  }
  PCSIM_PETSC(VecSetValues(F, n, idx.data(), force.data(), ADD_VALUES));
}

void PantographTerm::block_tangent(const CoupledState& state, Shifts shifts, bool change,
                                   std::vector<double>& values) const {
  const auto& model = *slot_.model;
  const int n = model.dof_count();
  tangent_k_.resize(n, n);  // allocated once: a flexible model's blocks are 150 x 150
  tangent_c_.resize(n, n);
  tangent_m_.resize(n, n);
  model.tangents(state.t, state.q(index_), state.qd(index_), state.qdd(index_), tangent_k_,
                 tangent_c_, tangent_m_);
  values.resize(static_cast<std::size_t>(n) * n);
  Eigen::Map<RowMatrix> J(values.data(), n, n);
  if (change)
    J = tangent_k_ + shifts.v * tangent_c_ + shifts.a * tangent_m_ -
        Eigen::Map<const RowMatrix>(reference_.data(), n, n);
  else
    J = tangent_k_ + shifts.v * tangent_c_ + shifts.a * tangent_m_;
}

void PantographTerm::add_tangent(const CoupledState& state, Shifts shifts, Mat J) {
  if (!state.on_last_rank()) return;
  std::vector<double> values;
  block_tangent(state, shifts, false, values);
  const auto idx = dof_range(slot_);
  const auto n = static_cast<PetscInt>(idx.size());
  PCSIM_PETSC(MatSetValues(J, n, idx.data(), n, idx.data(), values.data(), ADD_VALUES));
}

// The reference is kept: block_change() reports the difference to it.
void PantographTerm::add_reference_tangent(const CoupledState& state, Shifts shifts, Mat J) {
  if (!state.on_last_rank()) return;
  block_tangent(state, shifts, false, reference_);
  const auto idx = dof_range(slot_);
  const auto n = static_cast<PetscInt>(idx.size());
  PCSIM_PETSC(MatSetValues(J, n, idx.data(), n, idx.data(), reference_.data(), ADD_VALUES));
}

void PantographTerm::block_change(const CoupledState& state, Shifts shifts,
                                  std::vector<BlockChange>& blocks) {
  if (slot_.model->is_linear()) return;
  BlockChange change;
  change.first = slot_.first_dof;
  change.size = slot_.dof_count();
  if (state.on_last_rank()) {
    if (reference_.empty()) throw SolverError("pantograph block change before its reference");
    const auto& model = *slot_.model;
    if (!model.sparse_step_tangent(state.t, state.q(index_), state.qd(index_), state.qdd(index_),
                                   shifts.v, shifts.a, change.value))
      block_tangent(state, shifts, true, change.delta);
  }
  blocks.push_back(std::move(change));
}

void PantographTerm::insert_pattern(Mat J) const {
  PetscMPIInt rank, size;
  MPI_Comm_rank(PetscObjectComm(reinterpret_cast<PetscObject>(J)), &rank);
  MPI_Comm_size(PetscObjectComm(reinterpret_cast<PetscObject>(J)), &size);
  if (rank != size - 1) return;
  const int n = slot_.dof_count();
  const auto idx = dof_range(slot_);
  const std::vector<double> zeros(n * n, 0.0);
  PCSIM_PETSC(MatSetValues(J, n, idx.data(), n, idx.data(), zeros.data(), ADD_VALUES));
}

double PantographTerm::energy(const CoupledState& state) const {
  double local = 0;
  if (state.on_last_rank()) {
    const auto& model = *slot_.model;
    const Eigen::VectorXd q = state.q(index_), qd = state.qd(index_);
    const int n = model.dof_count();
    double external_potential = 0;
    for (int i = 0; i < n; ++i)
      external_potential -= model.power(state.t, q, Eigen::VectorXd::Unit(n, i)).external * q[i];
    local =
        model.kinetic_energy(q, qd) + model.potential_energy(q) + external_potential +
        (1.0 - slot_.run.ramp_factor(state.t)) * slot_.run.static_force * q[model.contact_dof()];
  }
  return sum_over_ranks(state.catenary().comm(), local);
}

// The model's constant external forces (uplift, bellows torque, aerodynamic
// force) are potentials in energy(): only their explicit change with time,
// the ramp (1 - ramp(t)) F0 q_c, and a base motion's load do work here.
TermPower PantographTerm::power(const CoupledState& state) const {
  TermPower p;
  if (state.on_last_rank()) {
    const Eigen::VectorXd q = state.q(index_);
    const auto model_power = slot_.model->power(state.t, q, state.qd(index_));
    p.dissipative = model_power.dissipative;
    // d/dt of (1 - ramp(t)) F0 q_c at fixed q: the same ramp as the residual's; plus the
    // work of a prescribed base motion (no potential).
    const auto& run = slot_.run;
    p.external = -run.ramp_rate(state.t) * run.static_force * q[slot_.model->contact_dof()] +
                 model_power.base;
  }
  MPI_Comm comm = state.catenary().comm();
  p.dissipative = sum_over_ranks(comm, p.dissipative);
  p.external = sum_over_ranks(comm, p.external);
  return p;
}

// ---------------------------------------------------------- contact ----

PenaltyContact::Evaluation PenaltyContact::evaluate(const CoupledState& state) const {
  const ScopedEvent timed(log_events().contact);
  Evaluation e;
  e.x = slot_.run.contact_x(state.t);
  e.wire = &state.catenary().wire_point(e.x, wire_);
  e.head = state.head_height(index_);
  // A reduced catenary's residual flexibility r in series: kH / (1 + kH r).
  e.stiffness = kH_ / (1.0 + kH_ * e.wire->residual_flexibility);
  if (e.wire->on_wire && e.wire->owned) {
    e.gap = e.wire->z - e.head;
    e.force = e.gap < 0 ? -e.stiffness * e.gap : 0.0;
  }
  return e;
}

// -Fc dz/dU on the wire, +Fc on the head. The entries this rank owns are
// added into F's array directly (what VecSetValues with ADD_VALUES does for
// them, without its per-entry checks: a modal wire point has every mode).
void PenaltyContact::add_residual(const CoupledState& state, Vec F) {
  const Evaluation e = evaluate(state);
  if (e.force <= 0) return;
  const auto& index = e.wire->index;
  const auto& weight = e.wire->weight;
  PetscInt lo, hi;
  PCSIM_PETSC(VecGetOwnershipRange(F, &lo, &hi));
  remote_index_.clear();
  remote_value_.clear();
  PetscScalar* f;
  PCSIM_PETSC(VecGetArray(F, &f));
  const auto n = static_cast<PetscInt>(index.size());
  if (e.wire->contiguous && n > 0 && index[0] >= lo && index[0] + n <= hi) {  // one block here
    Eigen::Map<Eigen::ArrayXd>(f + index[0] - lo, n) +=
        Eigen::Map<const Eigen::ArrayXd>(weight.data(), n) * -e.force;
  } else {
    for (std::size_t i = 0; i < index.size(); ++i) {
      if (index[i] >= lo && index[i] < hi) {
        f[index[i] - lo] += weight[i] * -e.force;
      } else {
        remote_index_.push_back(index[i]);
        remote_value_.push_back(weight[i] * -e.force);
      }
    }
  }
  PCSIM_PETSC(VecRestoreArray(F, &f));
  PCSIM_PETSC(VecSetValues(F, static_cast<PetscInt>(remote_index_.size()), remote_index_.data(),
                           remote_value_.data(), ADD_VALUES));
  PCSIM_PETSC(VecSetValue(F, slot_.contact_dof(), e.force, ADD_VALUES));
}

void PenaltyContact::add_tangent(const CoupledState& state, Shifts, Mat J) {
  const Evaluation e = evaluate(state);
  if (e.force <= 0) return;
  std::vector<PetscInt> idx = e.wire->index;
  std::vector<double> u = e.wire->weight;
  idx.push_back(slot_.contact_dof());
  u.push_back(-1.0);
  const Eigen::Map<const Eigen::VectorXd> uv(u.data(), static_cast<long>(u.size()));
  const RowMatrix K = e.stiffness * uv * uv.transpose();
  const auto n = static_cast<PetscInt>(idx.size());
  PCSIM_PETSC(MatSetValues(J, n, idx.data(), n, idx.data(), K.data(), ADD_VALUES));
}

void PenaltyContact::append_low_rank_sums(const CoupledState& state,
                                          std::vector<double>& local) const {
  const Evaluation e = evaluate(state);
  local.push_back(e.wire->owned && e.force > 0 ? 1.0 : 0.0);
}

void PenaltyContact::take_low_rank_sums(const double* sums) {
  summed_in_contact_ = sums[0];
}

namespace {

bool contiguous_run(const std::vector<PetscInt>& index, bool said) {
  const std::size_t n = index.size();
  return said && n > 0 && index[n - 1] == index[0] + static_cast<PetscInt>(n) - 1;
}

// kept equals the wire's indices followed by the head's; two contiguous wire
// parts are equal by their first entry and size (the modal wire's every mode).
bool same_indices(const SharedEntries<PetscInt>& kept, bool kept_contiguous,
                  const std::vector<PetscInt>& wire, bool contiguous, PetscInt head) {
  const std::size_t n = wire.size();
  if (kept.size() != n + 1 || kept[n] != head) return false;
  if (n == 0) return true;
  if (kept_contiguous && contiguous_run(wire, contiguous)) return kept[0] == wire[0];
  return std::equal(wire.begin(), wire.end(), kept.begin());
}

}  // namespace

// u = [dz/dU; -1] (known on every rank), coefficient kH while in contact: the
// owner of the contact point decides. Evaluated again, not kept from
// append_low_rank_sums(): the wire point is valid only until the next
// wire_point() of the same wire, which another pantograph's contact makes.
bool PenaltyContact::low_rank_change(const CoupledState& state, std::vector<RankOne>& terms) {
  const Evaluation e = evaluate(state);
  const double in_contact = summed_in_contact_;  // take_low_rank_sums(), just before
  if (!e.wire->on_wire) return true;
  RankOne term;
  term.key = 0;
  const auto& wire_index = e.wire->index;
  const std::size_t size = wire_index.size() + 1;
  std::vector<double> weight;
  weight.reserve(size);  // room for the head: no reallocation
  weight.assign(e.wire->weight.begin(), e.wire->weight.end());
  weight.push_back(-1.0);
  term.weight = std::move(weight);
  if (!same_indices(term_index_, term_index_contiguous_, wire_index, e.wire->contiguous,
                    slot_.contact_dof())) {
    std::vector<PetscInt> index;
    index.reserve(size);
    index.assign(wire_index.begin(), wire_index.end());
    index.push_back(slot_.contact_dof());
    term_index_ = std::move(index);
    term_index_contiguous_ = contiguous_run(wire_index, e.wire->contiguous);
  }
  term.index = term_index_;
  term.coefficient = in_contact > 0.5 ? e.stiffness : 0.0;
  term.reuse_columns = e.wire->reuse_columns;
  // Contiguous only if the head's unknown follows the wire's (the first
  // pantograph of a modal catenary; not the others).
  const std::size_t n = term.index.size();
  term.contiguous = e.wire->contiguous && (n == 1 || term.index[n - 1] == term.index[n - 2] + 1);
  terms.push_back(std::move(term));
  return true;
}

// The contact point moves along the wire: at fixed state the penalty energy
// 1/2 k dz^2 changes at the rate (k dz (dz_wire/dx) + 1/2 dz^2 dk/dx) v (work
// of the moving contact on the system; k = kH / (1 + kH r) with a reduced
// catenary's residual flexibility r(x), dk/dx = -k^2 dr/dx); a moving
// frame's head rises with its base: + Fc v_b.
TermPower PenaltyContact::power(const CoupledState& state) const {
  const Evaluation e = evaluate(state);
  const double k = e.stiffness, dk_dx = -k * k * e.wire->residual_flexibility_slope;
  const double slope = e.force > 0 ? state.catenary().wire_slope(e.x, wire_) : 0.0;
  double local =
      e.force > 0 ? (k * e.gap * slope + 0.5 * e.gap * e.gap * dk_dx) * slot_.run.speed : 0.0;
  if (e.force > 0) local += e.force * slot_.model->frame_velocity(state.t);
  TermPower p;
  p.external = sum_over_ranks(state.catenary().comm(), local);
  return p;
}

double PenaltyContact::energy(const CoupledState& state) const {
  const Evaluation e = evaluate(state);
  return sum_over_ranks(state.catenary().comm(),
                        e.force > 0 ? 0.5 * e.stiffness * e.gap * e.gap : 0.0);
}

}  // namespace pcsim::assembly
