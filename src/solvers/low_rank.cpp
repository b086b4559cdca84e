#include "pcsim/solvers/low_rank.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <set>
#include <string>
#include <tuple>

#include "block_diagonal.hpp"
#include "capacitance_dots.hpp"
#include "pc_types.hpp"
#include "pcsim/core/error.hpp"
#include "pcsim/core/profiling.hpp"
#include "pcsim/solvers/schur_dd.hpp"
#include "varying_blocks.hpp"

namespace pcsim::solvers {

LowRankStepSolver::LowRankStepSolver(Mat J0, const char* inner_prefix)
    : J0_(J0), varying_(std::make_unique<VaryingBlocks>()) {
  MPI_Comm comm = PetscObjectComm(reinterpret_cast<PetscObject>(J0));
  PetscInt m, n, M, N;
  PCSIM_PETSC(MatGetLocalSize(J0, &m, &n));
  PCSIM_PETSC(MatGetSize(J0, &M, &N));
  PCSIM_PETSC(MatCreateShell(comm, m, n, M, N, this, &op_));
  PCSIM_PETSC(MatShellSetOperation(op_, MATOP_MULT, reinterpret_cast<void (*)(void)>(op_mult)));
  PCSIM_PETSC(KSPCreate(comm, &inner_));
  PCSIM_PETSC(KSPSetOptionsPrefix(inner_, inner_prefix));
}

LowRankStepSolver::~LowRankStepSolver() {
  for (auto& [key, e] : entries_) {
    VecDestroy(&e.u);
    VecDestroy(&e.z);
  }
  for (auto& [g, v] : columns_) VecDestroy(&v);
  for (auto& [u, z] : spare_) {
    VecDestroy(&u);
    VecDestroy(&z);
  }
  VecDestroy(&unit_);
  VecDestroy(&unit_solution_);
  KSPDestroy(&inner_);
  MatDestroy(&op_);
}

namespace {

constexpr const char* kDescription = "pcsim: J0 factored once + Woodbury low-rank terms";

// The PC type pcsimwoodbury: its data is the LowRankStepSolver that install()
// attaches (owned by the dynamic solver, never by the PC).
PetscErrorCode pc_destroy(PC pc) {
  PetscFunctionBeginUser;
  pc->data = nullptr;
  PetscFunctionReturn(0);
}

PetscErrorCode pc_view(PC pc, PetscViewer viewer) {
  PetscBool ascii = PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscCall(
      PetscObjectTypeCompare(reinterpret_cast<PetscObject>(viewer), PETSCVIEWERASCII, &ascii));
  if (ascii) PetscCall(PetscViewerASCIIPrintf(viewer, "  %s\n", kDescription));
  PetscFunctionReturn(0);
}

}  // namespace

PetscErrorCode LowRankStepSolver::pc_create(PC pc) {
  PetscFunctionBeginUser;
  set_pc_type_ops(pc, {pc_setup, pc_apply, pc_destroy, pc_view});
  PetscFunctionReturn(0);
}

void LowRankStepSolver::register_pc() {
  register_pc_type(kPCWoodbury, pc_create);
}

void LowRankStepSolver::install(PC pc) {
  register_pc();
  PCSIM_PETSC(PCSetType(pc, kPCWoodbury));
  pc->data = this;
}

LowRankStepSolver* LowRankStepSolver::attached(PC pc) {
  auto* self = static_cast<LowRankStepSolver*>(pc->data);
  if (!self)
    throw InputError("command line", "-pc_type",
                     std::string(kPCWoodbury) +
                         " is the cheap path's step solver: it needs the run's low-rank terms "
                         "(-pcsim_path auto or cheap, not a KSP of its own)");
  return self;
}

void LowRankStepSolver::invalidate() {
  factored_ = false;
  varying_->invalidate();
  for (auto& [g, v] : columns_) VecDestroy(&v);
  columns_.clear();
  for (auto& [key, e] : entries_) e.z_valid = false;
  capacitance_dirty_ = true;
}

// A term's vectors u and z: a pair a term left if there is one. A new pair's
// first writes fault in fresh pages, as costly as a modal step's products
// (docs/benchmarks.md, "What a modal run's slow steps are"); a kept pair's
// pages are in place.
void LowRankStepSolver::take_vectors(Entry& e) {
  if (spare_.empty()) {
    PCSIM_PETSC(MatCreateVecs(J0_, &e.u, &e.z));
    return;
  }
  std::tie(e.u, e.z) = spare_.back();
  spare_.pop_back();
}

// Spare pairs up to 'count' terms in all, written once so that their pages
// are in place before the first step that needs them.
void LowRankStepSolver::reserve_vectors(std::size_t count) {
  while (entries_.size() + spare_.size() < count) {
    Vec u, z;
    PCSIM_PETSC(MatCreateVecs(J0_, &u, &z));
    PCSIM_PETSC(VecSet(u, 0.0));
    PCSIM_PETSC(VecSet(z, 0.0));
    spare_.emplace_back(u, z);
  }
}

// Every rank knows every index: each writes the entries it owns (no
// communication).
void LowRankStepSolver::build_u(Entry& e) {
  if (!e.u) take_vectors(e);
  PetscInt lo, hi;
  PCSIM_PETSC(VecGetOwnershipRange(e.u, &lo, &hi));
  PetscScalar* u;
  PCSIM_PETSC(VecGetArray(e.u, &u));
  std::fill(u, u + (hi - lo), 0.0);
  const auto& index = e.term.index;
  const auto n = static_cast<PetscInt>(index.size());
  if (e.term.contiguous && n > 0 && index[n - 1] == index[0] + n - 1) {  // [lo, hi) part
    const PetscInt first = std::max(index[0], lo), last = std::min(index[0] + n, hi);
    if (first < last)
      std::copy(e.term.weight.begin() + (first - index[0]),
                e.term.weight.begin() + (last - index[0]), u + (first - lo));
  } else {
    for (PetscInt i = 0; i < n; ++i)
      if (index[i] >= lo && index[i] < hi) u[index[i] - lo] = e.term.weight[i];
  }
  PCSIM_PETSC(VecRestoreArray(e.u, &u));
  // Sparse where u is at most an eighth of the vector (an FE contact's or
  // dropper's few entries; a modal term's are every mode's, not sorted here
  // at every step).
  PetscInt size = 0;
  PCSIM_PETSC(VecGetSize(e.u, &size));
  e.sparse = 8 * n <= size;
  if (!e.sparse) return;
  std::vector<PetscInt> sorted(index.begin(), index.end());
  std::sort(sorted.begin(), sorted.end());
  e.sparse = std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end();
}

CapacitanceDots LowRankStepSolver::active_dots() const {
  CapacitanceDots in;
  const bool sparse =
      std::all_of(active_.begin(), active_.end(), [](auto* e) { return e->sparse; });
  for (const Entry* e : active_) {
    in.us.push_back(e->u);
    in.zs.push_back(e->z);
    if (sparse)
      in.sparse_us.push_back({e->term.index.data(), e->term.weight.data(), e->term.index.size()});
  }
  return in;
}

// J0^-1 e_g, solved once per factorisation and cached. e_g is set in place
// in one kept vector and z duplicated from a kept result-side vector (as
// MatCreateVecs made it before: the same bits; a duplicate of e_g's vector
// gave round-off differences on 2 ranks): no layout set-up and no assembly,
// so no communication beyond the solve's own.
Vec LowRankStepSolver::unit_solution(PetscInt g) {
  auto it = columns_.find(g);
  if (it != columns_.end()) return it->second;
  if (!unit_) PCSIM_PETSC(MatCreateVecs(J0_, &unit_, &unit_solution_));
  Vec z;
  PCSIM_PETSC(VecDuplicate(unit_solution_, &z));
  PCSIM_PETSC(VecSet(unit_, 0.0));
  PetscInt lo, hi;
  PCSIM_PETSC(VecGetOwnershipRange(unit_, &lo, &hi));
  if (g >= lo && g < hi) {
    PetscScalar* e;
    PCSIM_PETSC(VecGetArray(unit_, &e));
    e[g - lo] = 1.0;
    PCSIM_PETSC(VecRestoreArray(unit_, &e));
  }
  solve_fixed(unit_, z);
  columns_[g] = z;
  return z;
}

// z = J0^-1 u with J0 as factored, then the rows of the varying blocks at
// their current values (again at every change of the blocks).
void LowRankStepSolver::update_z(Entry& e) {
  if (!factored_) return;
  if (!e.z_valid) {
    if (e.term.reuse_columns) {
      std::vector<Vec> columns;
      for (PetscInt g : e.term.index) columns.push_back(unit_solution(g));
      PCSIM_PETSC(VecSet(e.z, 0.0));
      PCSIM_PETSC(VecMAXPY(e.z, static_cast<PetscInt>(columns.size()), e.term.weight.data(),
                           columns.data()));
    } else {
      solve_fixed(e.u, e.z);
    }
    e.z_valid = true;
    e.changed = true;
    capacitance_dirty_ = true;
  }
  if (!varying_->empty()) {
    varying_->solve_rows(e.u, e.z);
    e.changed = true;
  }
}

void LowRankStepSolver::evict_unused_columns() {
  std::set<PetscInt> used;
  for (const auto& [key, e] : entries_)
    if (e.term.reuse_columns) used.insert(e.term.index.begin(), e.term.index.end());
  for (auto it = columns_.begin(); it != columns_.end();) {
    if (used.count(it->first)) {
      ++it;
    } else {
      VecDestroy(&it->second);
      it = columns_.erase(it);
    }
  }
}

void LowRankStepSolver::set_terms(const std::vector<assembly::RankOne>& terms,
                                  const std::vector<assembly::BlockChange>& blocks) {
  varying_->set(blocks);
  if (!varying_->empty()) capacitance_dirty_ = true;  // on every rank alike
  if (blocks_ && !skipped_.empty()) {  // a skipped block's rows of J0^-1 are 0: still varying?
    const auto owned = varying_->owned_ranges();
    for (const auto& range : skipped_)
      if (std::find(owned.begin(), owned.end(), range) == owned.end())
        throw SolverError("a varying block of the step matrix left after J0's setup");
  }
  std::set<int> keys;
  for (const auto& term : terms) {
    keys.insert(term.key);
    auto [it, added] = entries_.try_emplace(term.key);
    Entry& e = it->second;
    const bool same_u = !added && e.term.index == term.index && e.term.weight == term.weight;
    if (e.term.coefficient != term.coefficient || !same_u) capacitance_dirty_ = true;
    if (same_u) {  // u kept: its index and weight are not copied again
      e.term.key = term.key;
      e.term.coefficient = term.coefficient;
      e.term.reuse_columns = term.reuse_columns;
      e.term.contiguous = term.contiguous;
    } else {
      e.term = term;
      build_u(e);
      e.z_valid = false;
      e.changed = true;
    }
  }
  for (auto it = entries_.begin(); it != entries_.end();) {
    if (keys.count(it->first)) {
      ++it;
      continue;
    }
    if (it->second.u) spare_.emplace_back(it->second.u, it->second.z);  // u, z: all rewritten
    it = entries_.erase(it);
    capacitance_dirty_ = true;
  }
  if (!factored_) return;
  evict_unused_columns();
  for (auto& [key, e] : entries_) update_z(e);
}

// A J0 whose pattern is block diagonal with small blocks (the modal
// catenary's: its modes and each pantograph's block) is inverted block by
// block (block_diagonal.hpp) instead of factored by the inner KSP, unless the
// options give the inner solver a -cheap_pc_type. A varying block (a
// nonlinear pantograph's) is left out of it whatever its size: solve_j0()
// replaces its rows (the flexible DSA-380's 150 unknowns, which made the
// inner KSP factor the whole J0: docs/benchmarks.md, "The flexible DSA-380's
// block without dense passes").
void LowRankStepSolver::choose_inner(Mat P) {
  inner_chosen_ = true;
  const char* prefix = nullptr;
  PetscBool pc_option = PETSC_FALSE;
  PCSIM_PETSC(KSPGetOptionsPrefix(inner_, &prefix));
  PCSIM_PETSC(PetscOptionsHasName(nullptr, prefix, "-pc_type", &pc_option));
  auto blocks = std::make_unique<BlockDiagonalInverse>();
  skipped_ = varying_->owned_ranges();
  if (!pc_option && blocks->analyse(P, 32, skipped_)) blocks_ = std::move(blocks);
}

// x = J0^-1 r, J0 as factored.
void LowRankStepSolver::solve_fixed(Vec r, Vec x) const {
  if (blocks_)
    blocks_->solve(r, x);
  else
    PCSIM_PETSC(KSPSolve(inner_, r, x));
}

void LowRankStepSolver::solve_j0(Vec r, Vec x) const {
  solve_fixed(r, x);
  if (!varying_->empty()) varying_->solve_rows(r, x);
}

PetscErrorCode LowRankStepSolver::pc_setup(PC pc) {
  PCSIM_CALLBACK_BEGIN
  LowRankStepSolver* self = attached(pc);
  Mat A, P;
  PCSIM_PETSC(PCGetOperators(pc, &A, &P));
  if (!self->inner_chosen_) {
    self->choose_inner(P);
    // The reduced catenary's dense terms (slack droppers) come and go in
    // groups: their vectors are ready (kReservedTerms pairs of m entries).
    if (self->blocks_) self->reserve_vectors(kReservedTerms);
  }
  if (self->blocks_) {
    self->blocks_->factor(P);
  } else {
    PCSIM_PETSC(KSPSetOperators(self->inner_, P, P));
    PCSIM_PETSC(KSPSetUp(self->inner_));
  }
  self->invalidate();
  self->varying_->setup(P);
  self->factored_ = true;
  self->j0_symmetric_ = self->blocks_ && exactly_symmetric(P);  // collective (low_rank.hpp)
  // Every z the way set_terms() computes it (reuse_columns terms from unit
  // solves): z depends only on J0 and u, never on when the PC was set up, so
  // a run restarted from a checkpoint takes the same arithmetic path.
  for (auto& [key, e] : self->entries_) self->update_z(e);
  PCSIM_CALLBACK_END
}

bool LowRankStepSolver::symmetric_capacitance() const {
  return j0_symmetric_ && varying_->empty();
}

std::vector<LowRankStepSolver::Entry*> LowRankStepSolver::active() {
  std::vector<Entry*> list;
  for (auto& [key, e] : entries_)
    if (e.term.coefficient != 0) list.push_back(&e);
  return list;
}

// C^-1 + U^T Z and, in the same reduction, ux = U^T x. With the same active
// terms as before, only the rows and columns of the terms whose u or z
// changed are formed again (a moving contact's, not a window end's
// dashpots): u_i . z_j and z_j . u_i are the same products summed in the same
// order, so either way gives the same bits. With J0 symmetric bit for bit
// (the modal catenary's), each pair's product is formed once, u_a . z_b
// (a before b), for both entries: k products per changed row instead of 2 k,
// k (k + 1) / 2 for a new set instead of k^2 (docs/benchmarks.md, "Each
// pair's capacitance product once").
void LowRankStepSolver::update_capacitance(Vec x, std::vector<PetscScalar>& ux) {
  auto now = active();
  const std::size_t k = now.size();
  const bool same_terms = now == active_ && products_.rows() == static_cast<long>(k);
  active_ = std::move(now);
  CapacitanceDots in = active_dots();
  if (!same_terms) products_.resize(k, k);
  std::vector<std::size_t>& rows = in.rows;
  for (std::size_t i = 0; i < k; ++i)
    if (!same_terms || active_[i]->changed) rows.push_back(i);
  in.symmetric = symmetric_capacitance();  // the same on every rank
  in.transposed = same_terms && !in.symmetric;
  in.x = x;
  std::vector<double> uz, zu;
  capacitance_dots(in, uz, zu, ux);
  if (!same_terms) ++active_set_changes_;
  capacitance_rows_formed_ += static_cast<long>(rows.size());
  const auto is_row = [&](std::size_t j) { return !same_terms || active_[j]->changed; };
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const std::size_t i = rows[r];
    if (in.symmetric) {  // u_a . z_b (a <= b) for both entries of each pair
      for (std::size_t j = 0; j < k; ++j)
        if (j >= i || !is_row(j)) products_(i, j) = products_(j, i) = uz[r * k + j];
      continue;
    }
    for (std::size_t j = 0; j < k; ++j) products_(i, j) = uz[r * k + j];
    if (!same_terms) continue;
    for (std::size_t j = 0; j < k; ++j)
      if (!active_[j]->changed) products_(j, i) = zu[r * k + j];  // a changed row is formed whole
  }
  for (Entry* e : active_) e->changed = false;
  Eigen::MatrixXd capacitance = products_;
  for (std::size_t i = 0; i < k; ++i) capacitance(i, i) += 1.0 / active_[i]->term.coefficient;
  capacitance_lu_.compute(capacitance);  // once per change, not at every apply
  capacitance_dirty_ = false;
}

// x = (J0 + U C U^T)^-1 r = y - Z (C^-1 + U^T Z)^-1 U^T y,  y = J0^-1 r.
PetscErrorCode LowRankStepSolver::pc_apply(PC pc, Vec r, Vec x) {
  PCSIM_CALLBACK_BEGIN
  LowRankStepSolver* self = attached(pc);
  self->solve_j0(r, x);
  const ScopedEvent timed(log_events().woodbury);
  std::vector<PetscScalar> w;
  if (self->capacitance_dirty_) self->update_capacitance(x, w);  // U^T y in its reduction
  const std::size_t k = self->active_.size();
  if (k == 0) return 0;
  CapacitanceDots in = self->active_dots();  // no rows: x . u_j alone
  if (w.size() != k) {  // U^T y by the capacitance's kernel: the same bits either way
    in.x = x;
    std::vector<double> uz, zu;  // both empty
    capacitance_dots(in, uz, zu, w);
  }
  Eigen::VectorXd s =
      self->capacitance_lu_.solve(Eigen::Map<Eigen::VectorXd>(w.data(), static_cast<long>(k)));
  s = -s;
  PCSIM_PETSC(VecMAXPY(x, static_cast<PetscInt>(k), s.data(), in.zs.data()));
  LastApply& last = self->last_apply_;
  last.x = x;
  PCSIM_PETSC(PetscObjectStateGet(reinterpret_cast<PetscObject>(x), &last.state));
  last.uy = Eigen::Map<Eigen::VectorXd>(w.data(), static_cast<long>(k));
  last.s = s;
  PCSIM_CALLBACK_END
}

long LowRankStepSolver::sparse_block_factorisations() const {
  return varying_->sparse_factorisations();
}

long LowRankStepSolver::kept_order_factorisations() const {
  return varying_->kept_order_factorisations();
}

bool LowRankStepSolver::solves_exactly() const {
  return blocks_ || preonly_with(inner_, {PCLU, PCCHOLESKY, kPCSchur});
}

}  // namespace pcsim::solvers
