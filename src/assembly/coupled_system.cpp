#include "pcsim/assembly/coupled_system.hpp"

#include <mpi.h>
#include <petsc/private/petscimpl.h>  // PetscObjectStateGet

#include <algorithm>
#include <cmath>
#include <vector>

#include "pcsim/assembly/interaction_terms.hpp"
#include "pcsim/core/error.hpp"
#include "pcsim/core/profiling.hpp"

namespace pcsim::assembly {

CoupledSystem::CoupledSystem(std::unique_ptr<CatenaryModel> catenary,
                             std::vector<PantographSlot> pantographs,
                             const contact::InteractionEffects& effects, double contact_stiffness)
    : catenary_(std::move(catenary)),
      pantographs_(std::move(pantographs)),
      state_(*catenary_, pantographs_),
      contact_stiffness_(contact_stiffness) {
  PetscInt offset = 0;
  std::vector<bool> wire_coupled;
  for (auto& slot : pantographs_) {
    slot.first_dof = catenary_->extra_global(offset);
    slot.state_first = offset;
    for (int i = 0; i < slot.dof_count(); ++i)
      wire_coupled.push_back(i == slot.model->contact_dof());
    offset += slot.dof_count();
  }
  wire_coupled_ = wire_coupled;
  for (std::size_t p = 0; p < pantographs_.size(); ++p) {
    terms_.push_back(std::make_unique<PantographTerm>(p, pantographs_[p]));
    contacts_.emplace_back();
    for (int w = 0; w < catenary_->contact_wire_count(); ++w) {
      auto contact = std::make_unique<PenaltyContact>(p, pantographs_[p], contact_stiffness, w);
      contacts_.back().push_back(contact.get());
      terms_.push_back(std::move(contact));
    }
  }
  Mat pattern = build_pattern(catenary_->has_reference_pattern());
  auto catenary_terms = catenary_->make_terms(effects, pattern);
  // Not kept: all zeros and as large as a Jacobian (1000 spans: ~0.25 GB per
  // rank, docs/scaling.md); create_matrix() builds each copy afresh.
  PCSIM_PETSC(MatDestroy(&pattern));
  terms_.insert(terms_.begin(), std::make_move_iterator(catenary_terms.begin()),
                std::make_move_iterator(catenary_terms.end()));
  // Merge the linear parts that share a matrix.
  for (const auto& term : terms_)
    for (const auto& part : term->linear_parts()) {
      auto it = std::find_if(parts_.begin(), parts_.end(),
                             [&](const MergedPart& m) { return m.matrix == part.matrix; });
      if (it == parts_.end())
        parts_.push_back({part.matrix, part.cu, part.cv, part.ca, part.structure});
      else
        it->cu += part.cu, it->cv += part.cv, it->ca += part.ca;
    }
  part_axpy_.resize(parts_.size());
  for (std::size_t k = 0; k < parts_.size(); ++k)
    part_arguments_.push_back(catenary_->create_vector());
  reference_ = catenary_->create_vector();
  catenary_->reference_state(reference_);
  work_ = catenary_->create_vector();
}

CoupledSystem::~CoupledSystem() {
  terms_.clear();
  VecDestroy(&reference_);
  VecDestroy(&work_);
  VecDestroy(&rest_);
  VecDestroy(&rest_next_);
  MatDestroy(&reference_rest_);
  for (Vec& w : part_arguments_) VecDestroy(&w);
}

PetscInt CoupledSystem::global_size() const {
  PetscInt n = catenary_->catenary_dofs();
  for (const auto& slot : pantographs_) n += slot.dof_count();
  return n;
}

Term& CoupledSystem::add_load_term(std::unique_ptr<Term> term) {
  if (!term->linear_parts().empty() || term->tangent_kind() != TangentKind::constant)
    throw SolverError("coupled system: '" + term->name() +
                      "' is not a load term (it has linear parts or a tangent)");
  terms_.push_back(std::move(term));
  return *terms_.back();
}

bool CoupledSystem::cheap_path_possible() const {
  return std::none_of(terms_.begin(), terms_.end(), [](const auto& term) {
    return term->tangent_kind() == TangentKind::varying;
  });
}

// The catenary model's pattern plus the interaction terms' (the pantographs'
// blocks), assembled.
Mat CoupledSystem::build_pattern(bool reference) const {
  Mat J = reference ? catenary_->create_reference_matrix(wire_coupled_)
                    : catenary_->create_matrix(wire_coupled_);
  for (const auto& term : terms_) term->insert_pattern(J);
  PCSIM_PETSC(MatAssemblyBegin(J, MAT_FINAL_ASSEMBLY));
  PCSIM_PETSC(MatAssemblyEnd(J, MAT_FINAL_ASSEMBLY));
  return J;
}

Mat CoupledSystem::create_matrix() const {
  return build_pattern(false);
}

Mat CoupledSystem::create_reference_matrix() const {
  return build_pattern(catenary_->has_reference_pattern());
}

// Skipped when the same vectors, unchanged (PETSc object states), were loaded
// last at the same time: a step's Jacobian at its last residual's state needs
// no second ghost exchange and pantographs' broadcast.
void CoupledSystem::load(double t, Vec U, Vec V, Vec A) {
  LoadStamp now;
  now.t = t;
  const Vec vecs[3] = {U, V, A};
  for (int k = 0; k < 3; ++k) {
    if (!vecs[k]) continue;
    const auto object = reinterpret_cast<PetscObject>(vecs[k]);
    PCSIM_PETSC(PetscObjectGetId(object, &now.ids[k]));  // unique: never a freed Vec's
    PCSIM_PETSC(PetscObjectStateGet(object, &now.states[k]));
  }
  if (loaded_.valid && now.t == loaded_.t && now.ids == loaded_.ids && now.states == loaded_.states)
    return;
  now.valid = true;
  const ScopedEvent timed(log_events().state_load);
  state_.load(t, U, V, A);
  loaded_ = now;
}

namespace {

// A new matrix holding J's nonzero values alone (its own, smaller pattern).
Mat copy_nonzeros(Mat J) {
  PetscInt lo, hi, col_lo, col_hi, m, n, M, N;
  PCSIM_PETSC(MatGetOwnershipRange(J, &lo, &hi));
  PCSIM_PETSC(MatGetOwnershipRangeColumn(J, &col_lo, &col_hi));
  PCSIM_PETSC(MatGetLocalSize(J, &m, &n));
  PCSIM_PETSC(MatGetSize(J, &M, &N));
  std::vector<PetscInt> diagonal(m, 0), off(m, 0), columns;
  std::vector<PetscScalar> values;
  std::vector<PetscInt> row_start(1, 0);
  for (PetscInt i = lo; i < hi; ++i) {
    PetscInt count;
    const PetscInt* cols;
    const PetscScalar* vals;
    PCSIM_PETSC(MatGetRow(J, i, &count, &cols, &vals));
    for (PetscInt k = 0; k < count; ++k) {
      if (vals[k] == 0.0) continue;
      columns.push_back(cols[k]);
      values.push_back(vals[k]);
      ++(cols[k] >= col_lo && cols[k] < col_hi ? diagonal : off)[i - lo];
    }
    PCSIM_PETSC(MatRestoreRow(J, i, &count, &cols, &vals));
    row_start.push_back(static_cast<PetscInt>(columns.size()));
  }
  Mat T;
  PCSIM_PETSC(MatCreateAIJ(PetscObjectComm(reinterpret_cast<PetscObject>(J)), m, n, M, N, 0,
                           diagonal.data(), 0, off.data(), &T));
  PCSIM_PETSC(MatSetOption(T, MAT_NO_OFF_PROC_ENTRIES, PETSC_TRUE));
  for (PetscInt i = lo; i < hi; ++i) {
    const PetscInt first = row_start[i - lo], count = row_start[i - lo + 1] - first;
    if (count > 0)
      PCSIM_PETSC(MatSetValues(T, 1, &i, count, columns.data() + first, values.data() + first,
                               INSERT_VALUES));
  }
  PCSIM_PETSC(MatAssemblyBegin(T, MAT_FINAL_ASSEMBLY));
  PCSIM_PETSC(MatAssemblyEnd(T, MAT_FINAL_ASSEMBLY));
  return T;
}

// Whether a part has an argument at this state (V, A may be absent).
bool part_active(double cu, double cv, double ca, Vec V, Vec A) {
  return cu != 0 || (cv != 0 && V) || (ca != 0 && A);
}

}  // namespace

// Each part's argument w_k = cu (U - U_ref) + cv V + ca A, all in one pass
// over the state (each entry takes the operations, in order, of the VecWAXPY,
// VecScale and VecAXPY that formed it before: the same bits).
void CoupledSystem::form_part_arguments(Vec U, Vec V, Vec A) {
  PetscInt n = 0;
  const PetscScalar *u = nullptr, *r = nullptr, *v = nullptr, *a = nullptr;
  PCSIM_PETSC(VecGetLocalSize(reference_, &n));
  PCSIM_PETSC(VecGetArrayRead(U, &u));
  PCSIM_PETSC(VecGetArrayRead(reference_, &r));
  if (V) PCSIM_PETSC(VecGetArrayRead(V, &v));
  if (A) PCSIM_PETSC(VecGetArrayRead(A, &a));
  for (std::size_t k = 0; k < parts_.size(); ++k) {
    const MergedPart& part = parts_[k];
    if (!part_active(part.cu, part.cv, part.ca, V, A)) continue;
    const double cu = part.cu, cv = v ? part.cv : 0.0, ca = a ? part.ca : 0.0;
    PetscScalar* w = nullptr;
    PCSIM_PETSC(VecGetArrayWrite(part_arguments_[k], &w));
    for (PetscInt i = 0; i < n; ++i) {
      double x = 0;
      if (cu != 0) x = cu == 1 ? u[i] - r[i] : (u[i] - r[i]) * cu;
      if (cv != 0) x = cu != 0 ? x + cv * v[i] : cv * v[i];
      if (ca != 0) x = cu != 0 || cv != 0 ? x + ca * a[i] : ca * a[i];
      w[i] = x;
    }
    PCSIM_PETSC(VecRestoreArrayWrite(part_arguments_[k], &w));
  }
  if (A) PCSIM_PETSC(VecRestoreArrayRead(A, &a));
  if (V) PCSIM_PETSC(VecRestoreArrayRead(V, &v));
  PCSIM_PETSC(VecRestoreArrayRead(reference_, &r));
  PCSIM_PETSC(VecRestoreArrayRead(U, &u));
}

// F = sum over constant matrices A_k w_k (the first product sets F: no pass
// to zero it), or F = 0 without linear parts.
void CoupledSystem::set_linear_parts(Vec U, Vec V, Vec A, Vec F) {
  const ScopedEvent timed(log_events().linear_parts);
  form_part_arguments(U, V, A);
  bool first = true;
  for (std::size_t k = 0; k < parts_.size(); ++k) {
    const MergedPart& part = parts_[k];
    if (!part_active(part.cu, part.cv, part.ca, V, A)) continue;
    if (first)
      PCSIM_PETSC(MatMult(part.matrix, part_arguments_[k], F));
    else
      PCSIM_PETSC(MatMultAdd(part.matrix, part_arguments_[k], F, F));
    first = false;
  }
  if (first) PCSIM_PETSC(VecSet(F, 0.0));
}

void CoupledSystem::add_term_residuals(Vec F) {
  for (const auto& term : terms_)
    if (!term->adds_by_set_values()) term->add_residual(state_, F);
  for (const auto& term : terms_)
    if (term->adds_by_set_values()) term->add_residual(state_, F);
  PCSIM_PETSC(VecAssemblyBegin(F));
  PCSIM_PETSC(VecAssemblyEnd(F));
}

void CoupledSystem::residual(double t, Vec U, Vec V, Vec A, Vec F) {
  const ScopedEvent timed(log_events().residual);
  load(t, U, V, A);
  if (!keep_rest_) {
    set_linear_parts(U, V, A, F);
    add_term_residuals(F);
    return;
  }
  PCSIM_PETSC(VecSet(rest_, 0.0));
  add_term_residuals(rest_);
  set_linear_parts(U, V, A, F);
  PCSIM_PETSC(VecAXPY(F, 1.0, rest_));
  rest_valid_ = true;
}

bool CoupledSystem::enable_residual_update() {
  if (parts_.empty()) return false;
  if (!rest_) {
    rest_ = catenary_->create_vector();
    rest_next_ = catenary_->create_vector();
  }
  keep_rest_ = true;
  return true;
}

bool CoupledSystem::residual_update(double t, Vec U, Vec V, Vec A, Vec Y, Vec F) {
  if (!keep_rest_ || !rest_valid_ || !reference_rest_) return false;
  const ScopedEvent timed(log_events().residual_update);
  load(t, U, V, A);
  PCSIM_PETSC(VecSet(rest_next_, 0.0));
  add_term_residuals(rest_next_);
  PCSIM_PETSC(VecWAXPY(F, -1.0, rest_, rest_next_));
  PCSIM_PETSC(MatMultAdd(reference_rest_, Y, F, F));
  std::swap(rest_, rest_next_);
  return true;
}

// The linear parts' ca A products and the terms' inertia at (t, U, V), in the
// residual's order (vector operations first, VecSetValues last, one assembly).
// A configuration-dependent mass reads the state: loaded here (at the step's
// last residual's state, as the integrator calls it, the load is skipped).
void CoupledSystem::inertia_product(double t, Vec U, Vec V, Vec A, Vec MA) {
  const bool varying = std::any_of(terms_.begin(), terms_.end(), [](const auto& term) {
    return term->acceleration_use() == AccelerationUse::varying;
  });
  if (varying) load(t, U, V, A);
  bool first = true;
  for (const auto& part : parts_) {
    if (part.ca == 0) continue;
    Vec x = A;  // ca A, or A itself for ca = 1 (the same bits: no copy)
    if (part.ca != 1) {
      PCSIM_PETSC(VecAXPBY(work_, part.ca, 0.0, A));
      x = work_;
    }
    if (first)
      PCSIM_PETSC(MatMult(part.matrix, x, MA));
    else
      PCSIM_PETSC(MatMultAdd(part.matrix, x, MA, MA));
    first = false;
  }
  if (first) PCSIM_PETSC(VecSet(MA, 0.0));
  for (bool by_set_values : {false, true})
    for (const auto& term : terms_)
      if (term->adds_by_set_values() == by_set_values &&
          term->acceleration_use() != AccelerationUse::none)
        term->add_inertia(state_, A, MA);
  // Terms add inertia on owned entries only (term.hpp): an assembly without
  // communication (no reduction to find who sends what).
  PCSIM_PETSC(VecSetOption(MA, VEC_IGNORE_OFF_PROC_ENTRIES, PETSC_TRUE));
  PCSIM_PETSC(VecAssemblyBegin(MA));
  PCSIM_PETSC(VecAssemblyEnd(MA));
  PCSIM_PETSC(VecSetOption(MA, VEC_IGNORE_OFF_PROC_ENTRIES, PETSC_FALSE));
}

void CoupledSystem::assemble_tangent(Shifts shifts, Mat J, bool reference) {
  PCSIM_PETSC(MatZeroEntries(J));
  for (const auto& term : terms_) {
    if (reference)
      term->add_reference_tangent(state_, shifts, J);
    else
      term->add_tangent(state_, shifts, J);
  }
  PCSIM_PETSC(MatAssemblyBegin(J, MAT_FINAL_ASSEMBLY));
  PCSIM_PETSC(MatAssemblyEnd(J, MAT_FINAL_ASSEMBLY));
  if (reference && keep_rest_) {  // T: the terms' reference tangents alone
    PCSIM_PETSC(MatDestroy(&reference_rest_));
    reference_rest_ = copy_nonzeros(J);
  }
  for (std::size_t k = 0; k < parts_.size(); ++k) {
    const auto& part = parts_[k];
    const double c = part.cu + shifts.v * part.cv + shifts.a * part.ca;
    if (part.structure == SUBSET_NONZERO_PATTERN)
      part_axpy_[k].apply(J, c, part.matrix);
    else
      PCSIM_PETSC(MatAXPY(J, c, part.matrix, part.structure));
  }
  if (reference && keep_rest_) {  // -info: T's size against J0's
    MatInfo j0, rest;
    PCSIM_PETSC(MatGetInfo(J, MAT_GLOBAL_SUM, &j0));
    PCSIM_PETSC(MatGetInfo(reference_rest_, MAT_GLOBAL_SUM, &rest));
    PCSIM_PETSC(PetscInfo(J,
                          "residual update: the terms' reference tangents keep %.0f of J0's %.0f "
                          "entries\n",
                          rest.nz_used, j0.nz_used));
  }
}

void CoupledSystem::jacobian(double t, Vec U, Vec V, Vec A, Shifts shifts, Mat J) {
  load(t, U, V, A);
  assemble_tangent(shifts, J, false);
}

void CoupledSystem::reference_jacobian(double t, Vec U, Vec V, Vec A, Shifts shifts, Mat J0) {
  load(t, U, V, A);
  assemble_tangent(shifts, J0, true);
}

// Every term's values to sum over the ranks, in one reduction.
void CoupledSystem::sum_low_rank_values() {
  std::vector<double> sums;
  std::vector<std::size_t> first;
  for (const auto& term : terms_) {
    first.push_back(sums.size());
    term->append_low_rank_sums(state_, sums);
  }
  first.push_back(sums.size());
  if (sums.empty()) return;
  if (state_.size() > 1)
    MPI_Allreduce(MPI_IN_PLACE, sums.data(), static_cast<int>(sums.size()), MPI_DOUBLE, MPI_SUM,
                  comm());
  for (std::size_t k = 0; k < terms_.size(); ++k)
    if (first[k + 1] > first[k]) terms_[k]->take_low_rank_sums(&sums[first[k]]);
}

bool CoupledSystem::low_rank_change(double t, Vec U, Vec V, Vec A, std::vector<RankOne>& terms,
                                    Shifts shifts, std::vector<BlockChange>* blocks) {
  const ScopedEvent timed(log_events().low_rank_change);
  load(t, U, V, A);
  terms.clear();
  if (blocks) blocks->clear();
  sum_low_rank_values();
  bool reference_ok = true;
  for (std::size_t k = 0; k < terms_.size(); ++k) {
    const std::size_t first = terms.size();
    reference_ok = terms_[k]->low_rank_change(state_, terms) && reference_ok;
    // Keys unique over the system: term number in the high bits.
    const int high = static_cast<int>(k << 20);
    for (std::size_t i = first; i < terms.size(); ++i) terms[i].key += high;
    if (!blocks || terms_[k]->tangent_kind() != TangentKind::block) continue;
    const std::size_t first_block = blocks->size();
    terms_[k]->block_change(state_, shifts, *blocks);
    for (std::size_t i = first_block; i < blocks->size(); ++i) (*blocks)[i].key += high;
  }
  return reference_ok;
}

std::vector<std::vector<double>> CoupledSystem::checkpoint_terms() const {
  std::vector<std::vector<double>> states;
  for (const auto& term : terms_) states.push_back(term->checkpoint());
  return states;
}

void CoupledSystem::restore_terms(const std::vector<std::vector<double>>& states) {
  if (states.size() != terms_.size())
    throw SolverError("restore: " + std::to_string(states.size()) + " term states for " +
                      std::to_string(terms_.size()) + " terms");
  for (std::size_t k = 0; k < terms_.size(); ++k) terms_[k]->restore(states[k]);
}

double CoupledSystem::energy(double t, Vec U, Vec V) {
  load(t, U, V, nullptr);
  double e = 0;
  for (const auto& term : terms_) e += term->energy(state_);
  return e;
}

TermPower CoupledSystem::power(double t, Vec U, Vec V) {
  load(t, U, V, nullptr);
  TermPower total;
  for (const auto& term : terms_) {
    const TermPower p = term->power(state_);
    total.dissipative += p.dissipative;
    total.external += p.external;
  }
  return total;
}

}  // namespace pcsim::assembly
