#include "pcsim/solvers/schur_dd.hpp"

#include <algorithm>
#include <tuple>
#include <utility>
#include <vector>

#include "dd_blocks.hpp"
#include "interface_solve.hpp"
#include "negligible_entries.hpp"
#include "pc_types.hpp"
#include "pcsim/core/error.hpp"
#include "pcsim/core/profiling.hpp"

namespace pcsim::solvers {

namespace {

constexpr const char* kDescription = "pcsim exact domain decomposition (interior LU + Schur)";

class SchurDomainSolver {
 public:
  explicit SchurDomainSolver(MPI_Comm comm) : comm_(comm), interface_system_(comm) {
    MPI_Comm_rank(comm_, &rank_);
    PCSIM_PETSC(KSPCreate(PETSC_COMM_SELF, &interior_ksp_));
    PCSIM_PETSC(KSPSetOptionsPrefix(interior_ksp_, "pcsim_dd_"));
    PCSIM_PETSC(KSPSetType(interior_ksp_, KSPPREONLY));
    PC pc;
    PCSIM_PETSC(KSPGetPC(interior_ksp_, &pc));
    PCSIM_PETSC(PCSetType(pc, PCLU));
    PCSIM_PETSC(PCFactorSetMatSolverType(pc, MATSOLVERPETSC));
    // Measured on the EN 50318 catenary (docs/scaling.md): AMD leaves the
    // least fill (0.86 of nested dissection's) and orders fastest.
#if defined(PETSC_HAVE_SUITESPARSE)
    PCSIM_PETSC(PCFactorSetMatOrderingType(pc, MATORDERINGAMD));
#else
    PCSIM_PETSC(PCFactorSetMatOrderingType(pc, MATORDERINGND));
#endif
    PCSIM_PETSC(KSPSetFromOptions(interior_ksp_));
  }
  ~SchurDomainSolver() {
    release();
    KSPDestroy(&interior_ksp_);
  }

  void set_up(Mat A);
  void apply(Vec r, Vec x);
  DomainDecompositionInfo info() const {
    return info_;
  }

 private:
  void release();
  bool split_unknowns(Mat A, const LocalBlocks& blocks);
  void extract_blocks(Mat diagonal, MatReuse reuse);
  void factor_interior();
  void assemble_schur(const LocalBlocks& blocks);
  std::vector<std::pair<PetscInt, PetscScalar>> couplings(const LocalBlocks& blocks,
                                                          PetscInt row) const;
  void refill_blocks(Mat diagonal);

  MPI_Comm comm_;
  int rank_ = 0;
  KSP interior_ksp_ = nullptr;
  std::vector<PetscInt> interior_, interface_;  // local row numbers
  std::vector<PetscInt> interface_global_;      // global G numbers of all ranks, ascending
  std::vector<int> counts_, offsets_;           // |G_r| and their offsets in G
  Mat A_II_ = nullptr, A_IG_ = nullptr, A_GI_ = nullptr, X_ = nullptr, F_ = nullptr;
  Vec r_I_ = nullptr, y_I_ = nullptr, t_I_ = nullptr, g_r_ = nullptr, x_G_r_ = nullptr;
  InterfaceSystem interface_system_;  // S, gathered and factored on every rank
  std::vector<PetscScalar> x_G_;      // the interface solution, all ranks'
  DomainDecompositionInfo info_;
  Mat source_ = nullptr;             // the diagonal block the blocks were taken from
  PetscInt diagonal_nonzeros_ = -1;  // and its number of stored values
  // Where each stored value of A_II, A_IG, A_GI sits in the diagonal block's
  // values (empty: no map, MatCreateSubMatrix refills the block).
  std::vector<PetscInt> at_II_, at_IG_, at_GI_;
};

void SchurDomainSolver::release() {
  for (Mat* m : {&A_II_, &A_IG_, &A_GI_, &X_, &source_}) MatDestroy(m);
  for (Vec* v : {&r_I_, &y_I_, &t_I_, &g_r_, &x_G_r_}) VecDestroy(v);
  F_ = nullptr;  // owned by the interior KSP's PC
  for (auto* at : {&at_II_, &at_IG_, &at_GI_}) at->clear();
  // A new split may change the interior's size: the KSP forgets the old one.
  if (interior_ksp_) KSPReset(interior_ksp_);
}

// Interface: owned rows with a coupling to another rank's unknowns, and owned
// unknowns another rank's rows couple to (the pattern need not be symmetric).
// A coupling is a nonzero value: the step matrices store zeros where a term
// may couple later (every pantograph with the whole contact wire, for the
// full path's moving contact), which would put every contact-wire unknown
// in the interface. Returns whether the split differs from the last one.
bool SchurDomainSolver::split_unknowns(Mat A, const LocalBlocks& blocks) {
  PetscInt lo, hi;
  PCSIM_PETSC(MatGetOwnershipRange(A, &lo, &hi));
  std::vector<char> coupled(static_cast<std::size_t>(hi - lo), 0);
  std::vector<char> ghost_used(static_cast<std::size_t>(blocks.n_off_columns), 0);
  if (blocks.off_diagonal) {
    PetscInt n;
    const PetscInt *ia, *ja;
    PetscBool done;
    const PetscScalar* va;
    PCSIM_PETSC(MatGetRowIJ(blocks.off_diagonal, 0, PETSC_FALSE, PETSC_FALSE, &n, &ia, &ja, &done));
    PCSIM_PETSC(MatSeqAIJGetArrayRead(blocks.off_diagonal, &va));
    for (PetscInt i = 0; i < n; ++i)
      for (PetscInt k = ia[i]; k < ia[i + 1]; ++k)
        if (va[k] != 0.0) coupled[i] = ghost_used[ja[k]] = 1;
    PCSIM_PETSC(MatSeqAIJRestoreArrayRead(blocks.off_diagonal, &va));
    PCSIM_PETSC(
        MatRestoreRowIJ(blocks.off_diagonal, 0, PETSC_FALSE, PETSC_FALSE, &n, &ia, &ja, &done));
  }
  std::vector<PetscInt> used;  // the other ranks' unknowns this rank's rows couple to
  for (PetscInt k = 0; k < blocks.n_off_columns; ++k)
    if (ghost_used[k]) used.push_back(blocks.off_columns[k]);
  const auto ghost_counts = all_counts(comm_, static_cast<int>(used.size()));
  const auto ghost_offsets = offsets_of(ghost_counts);
  std::vector<PetscInt> ghosts(static_cast<std::size_t>(ghost_offsets.back()));
  MPI_Allgatherv(used.data(), static_cast<int>(used.size()), MPIU_INT, ghosts.data(),
                 ghost_counts.data(), ghost_offsets.data(), MPIU_INT, comm_);
  for (PetscInt g : ghosts)
    if (g >= lo && g < hi) coupled[g - lo] = 1;
  std::vector<PetscInt> interior, interface;
  for (PetscInt i = 0; i < hi - lo; ++i) (coupled[i] ? interface : interior).push_back(i);
  int changed = interior != interior_ || interface != interface_ || !A_II_;
  MPI_Allreduce(MPI_IN_PLACE, &changed, 1, MPI_INT, MPI_MAX, comm_);
  if (!changed) return false;
  interior_ = std::move(interior);
  interface_ = std::move(interface);
  counts_ = all_counts(comm_, static_cast<int>(interface_.size()));
  offsets_ = offsets_of(counts_);
  std::vector<PetscInt> mine(interface_.size());
  for (std::size_t j = 0; j < mine.size(); ++j) mine[j] = lo + interface_[j];
  interface_global_.resize(static_cast<std::size_t>(offsets_.back()));
  MPI_Allgatherv(mine.data(), static_cast<int>(mine.size()), MPIU_INT, interface_global_.data(),
                 counts_.data(), offsets_.data(), MPIU_INT, comm_);
  return true;
}

void sub_matrix(Mat A, const std::vector<PetscInt>& rows, const std::vector<PetscInt>& cols,
                MatReuse reuse, Mat* sub) {
  IS is_rows, is_cols;
  PCSIM_PETSC(ISCreateGeneral(PETSC_COMM_SELF, static_cast<PetscInt>(rows.size()), rows.data(),
                              PETSC_USE_POINTER, &is_rows));
  PCSIM_PETSC(ISCreateGeneral(PETSC_COMM_SELF, static_cast<PetscInt>(cols.size()), cols.data(),
                              PETSC_USE_POINTER, &is_cols));
  PCSIM_PETSC(MatCreateSubMatrix(A, is_rows, is_cols, reuse, sub));
  PCSIM_PETSC(ISDestroy(&is_rows));
  PCSIM_PETSC(ISDestroy(&is_cols));
}

PetscInt stored_values(Mat seq) {
  PetscInt n;
  const PetscInt *ia, *ja;
  PetscBool done;
  PCSIM_PETSC(MatGetRowIJ(seq, 0, PETSC_FALSE, PETSC_FALSE, &n, &ia, &ja, &done));
  const PetscInt count = ia[n];
  PCSIM_PETSC(MatRestoreRowIJ(seq, 0, PETSC_FALSE, PETSC_FALSE, &n, &ia, &ja, &done));
  return count;
}

// Position in the diagonal block's values of each stored value of sub =
// diagonal(rows, cols) (ascending local numbers; both patterns sorted by
// column), or an empty list if sub stores a value the block does not.
std::vector<PetscInt> value_positions(Mat diagonal, Mat sub, const std::vector<PetscInt>& rows,
                                      const std::vector<PetscInt>& cols) {
  PetscInt n, n_sub;
  const PetscInt *ia, *ja, *sia, *sja;
  PetscBool done;
  PCSIM_PETSC(MatGetRowIJ(diagonal, 0, PETSC_FALSE, PETSC_FALSE, &n, &ia, &ja, &done));
  PCSIM_PETSC(MatGetRowIJ(sub, 0, PETSC_FALSE, PETSC_FALSE, &n_sub, &sia, &sja, &done));
  std::vector<PetscInt> at(static_cast<std::size_t>(sia[n_sub]));
  bool found = true;
  for (PetscInt i = 0; i < n_sub && found; ++i) {
    const PetscInt r = rows[static_cast<std::size_t>(i)];
    PetscInt k = ia[r];
    for (PetscInt s = sia[i]; s < sia[i + 1] && found; ++s) {
      const PetscInt c = cols[static_cast<std::size_t>(sja[s])];
      while (k < ia[r + 1] && ja[k] < c) ++k;
      found = k < ia[r + 1] && ja[k] == c;
      at[static_cast<std::size_t>(s)] = k;
    }
  }
  PCSIM_PETSC(MatRestoreRowIJ(sub, 0, PETSC_FALSE, PETSC_FALSE, &n_sub, &sia, &sja, &done));
  PCSIM_PETSC(MatRestoreRowIJ(diagonal, 0, PETSC_FALSE, PETSC_FALSE, &n, &ia, &ja, &done));
  if (!found) at.clear();
  return at;
}

// sub's values from the diagonal block's, one pass over sub's values
// (MatCreateSubMatrix with MAT_REUSE_MATRIX searches every row: on one rank
// it was a third of the full path's factorisation time).
void copy_values(Mat diagonal, Mat sub, const std::vector<PetscInt>& at) {
  const PetscScalar* from;
  PetscScalar* to;
  PCSIM_PETSC(MatSeqAIJGetArrayRead(diagonal, &from));
  PCSIM_PETSC(MatSeqAIJGetArray(sub, &to));
  for (std::size_t s = 0; s < at.size(); ++s) to[s] = from[at[s]];
  PCSIM_PETSC(MatSeqAIJRestoreArray(sub, &to));
  PCSIM_PETSC(MatSeqAIJRestoreArrayRead(diagonal, &from));
}

// A_II, A_IG, A_GI from the diagonal block: new matrices after a new split,
// else the same ones with new values (the interior LU then keeps its
// ordering and symbolic factorisation: only the numeric one is redone). A
// rank without interface factors the diagonal block itself (no copy).
void SchurDomainSolver::extract_blocks(Mat diagonal, MatReuse reuse) {
  if (reuse == MAT_REUSE_MATRIX) return refill_blocks(diagonal);
  if (interface_.empty()) {
    PCSIM_PETSC(PetscObjectReference(reinterpret_cast<PetscObject>(diagonal)));
    A_II_ = diagonal;
  } else {
    sub_matrix(diagonal, interior_, interior_, reuse, &A_II_);
    sub_matrix(diagonal, interior_, interface_, reuse, &A_IG_);
    sub_matrix(diagonal, interface_, interior_, reuse, &A_GI_);
    at_II_ = value_positions(diagonal, A_II_, interior_, interior_);
    at_IG_ = value_positions(diagonal, A_IG_, interior_, interface_);
    at_GI_ = value_positions(diagonal, A_GI_, interface_, interior_);
  }
  PCSIM_PETSC(VecCreateSeq(PETSC_COMM_SELF, static_cast<PetscInt>(interior_.size()), &r_I_));
  for (Vec* v : {&y_I_, &t_I_}) PCSIM_PETSC(VecDuplicate(r_I_, v));
  PCSIM_PETSC(VecCreateSeq(PETSC_COMM_SELF, static_cast<PetscInt>(interface_.size()), &g_r_));
  PCSIM_PETSC(VecDuplicate(g_r_, &x_G_r_));
}

void SchurDomainSolver::refill_blocks(Mat diagonal) {
  if (interface_.empty()) return;  // A_II_ is the diagonal block
  const std::pair<Mat*, std::vector<PetscInt>*> blocks[] = {
      {&A_II_, &at_II_}, {&A_IG_, &at_IG_}, {&A_GI_, &at_GI_}};
  const std::vector<PetscInt>* rows[] = {&interior_, &interior_, &interface_};
  const std::vector<PetscInt>* cols[] = {&interior_, &interface_, &interior_};
  for (int b = 0; b < 3; ++b) {
    if (!blocks[b].second->empty() || stored_values(*blocks[b].first) == 0)
      copy_values(diagonal, *blocks[b].first, *blocks[b].second);
    else
      sub_matrix(diagonal, *rows[b], *cols[b], MAT_REUSE_MATRIX, blocks[b].first);
  }
}

// A_II = L U (sequential), X = A_II^-1 A_IG (dense, |I_r| x |G_r|, made
// sparse after S: negligible_entries.hpp), solved column by column in place
// of A_IG's dense copy (no second dense block).
void SchurDomainSolver::factor_interior() {
  const PetscInt n_I = static_cast<PetscInt>(interior_.size());
  const PetscInt m = static_cast<PetscInt>(interface_.size());
  PCSIM_PETSC(MatDestroy(&X_));
  if (m > 0) PCSIM_PETSC(MatConvert(A_IG_, MATSEQDENSE, MAT_INITIAL_MATRIX, &X_));
  if (n_I == 0) return;
  PCSIM_PETSC(KSPSetOperators(interior_ksp_, A_II_, A_II_));
  PCSIM_PETSC(KSPSetUp(interior_ksp_));
  PC pc;
  PCSIM_PETSC(KSPGetPC(interior_ksp_, &pc));
  PCSIM_PETSC(PCFactorGetMatrix(pc, &F_));
  for (PetscInt j = 0; j < m; ++j) {
    Vec column;
    PCSIM_PETSC(MatDenseGetColumnVec(X_, j, &column));
    PCSIM_PETSC(VecCopy(column, t_I_));
    PCSIM_PETSC(MatSolve(F_, t_I_, column));
    PCSIM_PETSC(MatDenseRestoreColumnVec(X_, j, &column));
  }
  MatInfo mi;
  PCSIM_PETSC(MatGetInfo(F_, MAT_LOCAL, &mi));
  info_.factor_nonzeros = mi.nz_used;
}

// Interface row i's couplings to other ranks' interface (A_GG's off-diagonal
// block): (G number, value), ascending; stored zeros are not couplings.
std::vector<std::pair<PetscInt, PetscScalar>> SchurDomainSolver::couplings(
    const LocalBlocks& blocks, PetscInt i) const {
  std::vector<std::pair<PetscInt, PetscScalar>> found;
  if (!blocks.off_diagonal) return found;
  PetscInt n;
  const PetscInt* cols;
  const PetscScalar* vals;
  PCSIM_PETSC(MatGetRow(blocks.off_diagonal, interface_[i], &n, &cols, &vals));
  for (PetscInt k = 0; k < n; ++k) {
    if (vals[k] == 0.0) continue;  // not a coupling (split_unknowns)
    const PetscInt g = blocks.off_columns[cols[k]];
    const auto at = std::lower_bound(interface_global_.begin(), interface_global_.end(), g);
    found.emplace_back(static_cast<PetscInt>(at - interface_global_.begin()), vals[k]);
  }
  PCSIM_PETSC(MatRestoreRow(blocks.off_diagonal, interface_[i], &n, &cols, &vals));
  return found;
}

// S: every rank writes its rows (A_GG - A_GI X within the rank, A_GG
// couplings to other ranks' interface), their nonzeros and diagonal only;
// the interface system gathers and factors them.
void SchurDomainSolver::assemble_schur(const LocalBlocks& blocks) {
  const PetscInt first = offsets_[rank_], m = static_cast<PetscInt>(interface_.size());
  Mat A_GG = nullptr, C = nullptr;
  sub_matrix(blocks.diagonal, interface_, interface_, MAT_INITIAL_MATRIX, &A_GG);
  const PetscScalar* c = nullptr;
  PetscInt ldc = 0;
  if (!interior_.empty() && m > 0) {
    PCSIM_PETSC(MatMatMult(A_GI_, X_, MAT_INITIAL_MATRIX, PETSC_DEFAULT, &C));
    PCSIM_PETSC(MatDenseGetArrayRead(C, &c));
    PCSIM_PETSC(MatDenseGetLDA(C, &ldc));
  }
  InterfaceRows rows;
  std::vector<PetscScalar> own(static_cast<std::size_t>(m));
  const auto put = [&rows](PetscInt col, PetscScalar v) {
    rows.columns.push_back(col);
    rows.values.push_back(v);
  };
  for (PetscInt i = 0; i < m; ++i) {
    std::fill(own.begin(), own.end(), 0.0);
    PetscInt n;
    const PetscInt* cols;
    const PetscScalar* vals;
    PCSIM_PETSC(MatGetRow(A_GG, i, &n, &cols, &vals));
    for (PetscInt k = 0; k < n; ++k) own[cols[k]] += vals[k];
    PCSIM_PETSC(MatRestoreRow(A_GG, i, &n, &cols, &vals));
    if (c)
      for (PetscInt j = 0; j < m; ++j) own[j] -= c[i + j * ldc];
    const auto off = couplings(blocks, i);  // ascending: before and after this rank's G
    auto k = off.begin();
    for (; k != off.end() && k->first < first; ++k) put(k->first, k->second);
    for (PetscInt j = 0; j < m; ++j)
      if (own[j] != 0.0 || j == i) put(first + j, own[j]);
    for (; k != off.end(); ++k) put(k->first, k->second);
    rows.starts.push_back(static_cast<PetscInt>(rows.columns.size()));
  }
  if (c) PCSIM_PETSC(MatDenseRestoreArrayRead(C, &c));
  PCSIM_PETSC(MatDestroy(&C));
  PCSIM_PETSC(MatDestroy(&A_GG));
  interface_system_.factor(rows, counts_);
  info_.interface_size = offsets_.back();
  info_.interface_bandwidth = interface_system_.lu().bandwidth();
  info_.interface_nonzeros = interface_system_.lu().nonzeros();
}

void SchurDomainSolver::set_up(Mat A) {
  const ScopedEvent timed(log_events().dd_setup);
  const LocalBlocks blocks = local_blocks(A);
  bool new_split = split_unknowns(A, blocks);
  const PetscInt nonzeros = stored_values(blocks.diagonal);
  // Another matrix (its pattern may differ) or a pattern grown since: new blocks.
  int new_pattern = blocks.diagonal != source_ || nonzeros != diagonal_nonzeros_;
  MPI_Allreduce(MPI_IN_PLACE, &new_pattern, 1, MPI_INT, MPI_MAX, comm_);
  new_split = new_split || new_pattern;
  if (new_split) {
    release();
    PCSIM_PETSC(PetscObjectReference(reinterpret_cast<PetscObject>(blocks.diagonal)));
    source_ = blocks.diagonal;
    diagonal_nonzeros_ = nonzeros;
  }
  info_ = {};
  extract_blocks(blocks.diagonal, new_split ? MAT_INITIAL_MATRIX : MAT_REUSE_MATRIX);
  factor_interior();
  assemble_schur(blocks);
  if (X_) drop_negligible(&X_, &info_.correction_entries, &info_.correction_stored);
  double sums[] = {info_.factor_nonzeros, info_.correction_entries, info_.correction_stored};
  MPI_Allreduce(MPI_IN_PLACE, sums, 3, MPI_DOUBLE, MPI_SUM, comm_);
  std::tie(info_.factor_nonzeros, info_.correction_entries, info_.correction_stored) =
      std::tie(sums[0], sums[1], sums[2]);
}

void SchurDomainSolver::apply(Vec r, Vec x) {
  const ScopedEvent timed(log_events().dd_apply);
  const PetscScalar* rr;
  PetscScalar *ri, *gr;
  PCSIM_PETSC(VecGetArrayRead(r, &rr));
  PCSIM_PETSC(VecGetArray(r_I_, &ri));
  for (std::size_t k = 0; k < interior_.size(); ++k) ri[k] = rr[interior_[k]];
  PCSIM_PETSC(VecRestoreArray(r_I_, &ri));
  if (F_) PCSIM_PETSC(MatSolve(F_, r_I_, y_I_));  // y = A_II^-1 r_I
  if (!interface_.empty()) {
    if (F_)
      PCSIM_PETSC(MatMult(A_GI_, y_I_, g_r_));
    else
      PCSIM_PETSC(VecSet(g_r_, 0.0));
    PCSIM_PETSC(VecGetArray(g_r_, &gr));  // g = r_G - A_GI y
    for (std::size_t j = 0; j < interface_.size(); ++j) gr[j] = rr[interface_[j]] - gr[j];
  } else {
    PCSIM_PETSC(VecGetArray(g_r_, &gr));
  }
  PCSIM_PETSC(VecRestoreArrayRead(r, &rr));
  interface_system_.solve(gr, x_G_);
  PCSIM_PETSC(VecRestoreArray(g_r_, &gr));
  const PetscScalar* x_G = x_G_.data() + offsets_[rank_];  // this rank's
  PetscScalar* xs;
  PCSIM_PETSC(VecGetArray(x_G_r_, &xs));
  std::copy(x_G, x_G + interface_.size(), xs);
  PCSIM_PETSC(VecRestoreArray(x_G_r_, &xs));
  if (F_ && !interface_.empty()) {  // x_I = y - X x_G
    PCSIM_PETSC(MatMult(X_, x_G_r_, t_I_));
    PCSIM_PETSC(VecAXPY(y_I_, -1.0, t_I_));
  }
  PetscScalar* xx;
  const PetscScalar* yi;
  PCSIM_PETSC(VecGetArray(x, &xx));
  PCSIM_PETSC(VecGetArrayRead(y_I_, &yi));
  for (std::size_t k = 0; k < interior_.size(); ++k) xx[interior_[k]] = F_ ? yi[k] : 0.0;
  for (std::size_t j = 0; j < interface_.size(); ++j) xx[interface_[j]] = x_G[j];
  PCSIM_PETSC(VecRestoreArrayRead(y_I_, &yi));
  PCSIM_PETSC(VecRestoreArray(x, &xx));
}

// The PC type pcsimschur: its data is the solver, made at the first set-up
// (the interior KSP reads its options then) and freed with the PC.
SchurDomainSolver* data_of(PC pc) {
  return static_cast<SchurDomainSolver*>(pc->data);
}

PetscErrorCode pc_setup(PC pc) {
  PCSIM_CALLBACK_BEGIN
  if (!pc->data)
    pc->data = new SchurDomainSolver(PetscObjectComm(reinterpret_cast<PetscObject>(pc)));
  data_of(pc)->set_up(pc->pmat);
  PCSIM_CALLBACK_END
}

PetscErrorCode pc_apply(PC pc, Vec r, Vec x) {
  PCSIM_CALLBACK_BEGIN
  data_of(pc)->apply(r, x);
  PCSIM_CALLBACK_END
}

PetscErrorCode pc_destroy(PC pc) {
  PCSIM_CALLBACK_BEGIN
  delete data_of(pc);
  pc->data = nullptr;
  PCSIM_CALLBACK_END
}

PetscErrorCode pc_view(PC pc, PetscViewer viewer) {
  PetscBool ascii = PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscCall(
      PetscObjectTypeCompare(reinterpret_cast<PetscObject>(viewer), PETSCVIEWERASCII, &ascii));
  if (ascii) {
    const DomainDecompositionInfo info = pc->data ? data_of(pc)->info() : DomainDecompositionInfo{};
    PetscCall(PetscViewerASCIIPrintf(viewer,
                                     "  %s: interface of %" PetscInt_FMT " unknowns, %" PetscInt_FMT
                                     " entries, bandwidth %" PetscInt_FMT "\n",
                                     kDescription, info.interface_size, info.interface_nonzeros,
                                     info.interface_bandwidth));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode pc_create(PC pc) {
  PetscFunctionBeginUser;
  set_pc_type_ops(pc, {pc_setup, pc_apply, pc_destroy, pc_view});
  PetscFunctionReturn(0);
}

SchurDomainSolver* solver_of(KSP ksp) {
  PC pc;
  PCSIM_PETSC(KSPGetPC(ksp, &pc));
  PetscBool schur = PETSC_FALSE;
  PCSIM_PETSC(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(pc), kPCSchur, &schur));
  return schur ? data_of(pc) : nullptr;
}

}  // namespace

void register_schur_pc() {
  register_pc_type(kPCSchur, pc_create);
}

void use_schur_domain_decomposition(KSP ksp) {
  register_schur_pc();
  PCSIM_PETSC(KSPSetType(ksp, KSPPREONLY));
  PC pc;
  PCSIM_PETSC(KSPGetPC(ksp, &pc));
  PCSIM_PETSC(PCSetType(pc, kPCSchur));
}

DomainDecompositionInfo domain_decomposition_info(KSP ksp) {
  const SchurDomainSolver* self = solver_of(ksp);
  return self ? self->info() : DomainDecompositionInfo{};
}

}  // namespace pcsim::solvers
