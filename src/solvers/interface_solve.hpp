// The interface problem of the domain-decomposition step solver
// (pcsim/solvers/schur_dd.hpp): the Schur complement S on the interface
// unknowns G of all ranks, stored sparse. S couples the unknowns of one
// rank's cuts with each other and, across each cut, with the neighbouring
// rank's: along the track a chain of cuts, block-tridiagonal. METIS's part
// numbers need not follow the track, so S is ordered by reverse
// Cuthill-McKee (banded: each cut next to its neighbours along the chain)
// and LU-factored by PETSc (MATSEQAIJ, no pivoting, as the interior blocks).
// Every rank holds the whole factor: each rank writes its own rows, one
// MPI_Allgatherv gathers S's nonzeros (not n_G^2 values), and a solve
// gathers g and costs 2 nnz(L+U) flops (at most ~4 b n_G for bandwidth b;
// measured ~60 n_G on the catenary, docs/scaling.md "The interface solve").
#pragma once

#include <petscmat.h>

#include <vector>

namespace pcsim::solvers {

// offsets[r] = counts[0] + .. + counts[r - 1], r = 0 .. size.
std::vector<int> offsets_of(const std::vector<int>& counts);

// Some rows of S in CSR form.
struct InterfaceRows {
  std::vector<PetscInt> starts{0};  // row k's entries: [starts[k], starts[k + 1])
  std::vector<PetscInt> columns;    // G numbers, ascending in each row
  std::vector<PetscScalar> values;
  PetscInt rows() const { return static_cast<PetscInt>(starts.size()) - 1; }
};

// Sparse LU of a whole (sequential) S.
class InterfaceFactor {
 public:
  InterfaceFactor() = default;
  ~InterfaceFactor();
  InterfaceFactor(const InterfaceFactor&) = delete;
  InterfaceFactor& operator=(const InterfaceFactor&) = delete;

  // Factors S (every row, each with its diagonal). same_pattern: S has the
  // last one's pattern, whose ordering and symbolic factorisation are kept.
  void factor(const InterfaceRows& S, bool same_pattern);
  // x = S^-1 b (n values each; b and x distinct).
  void solve(const PetscScalar* b, PetscScalar* x) const;
  PetscInt size() const { return size_; }
  // max |p(i) - p(j)| over S's entries (i, j), p the ordering.
  PetscInt bandwidth() const { return bandwidth_; }
  PetscInt nonzeros() const {  // S's stored entries
    return nonzeros_;
  }
  double factor_nonzeros() const;  // stored in L and U

 private:
  void release();
  void order_and_analyse(const InterfaceRows& S);

  Mat S_ = nullptr, F_ = nullptr;
  Vec b_ = nullptr, x_ = nullptr;  // arrays placed at each solve
  PetscInt size_ = 0, bandwidth_ = 0, nonzeros_ = 0;
};

// S distributed by rows (rank r writes the rows of its interface unknowns,
// G numbers offsets[r] ..), gathered and factored on every rank.
class InterfaceSystem {
 public:
  explicit InterfaceSystem(MPI_Comm comm) : comm_(comm) {}
  // Collective: mine = this rank's rows, counts[r] = rank r's number of rows.
  // S's pattern is gathered again only when a rank's changed.
  void factor(const InterfaceRows& mine, const std::vector<int>& counts);
  // Collective: x = S^-1 g (all n_G values) from this rank's rows of g.
  void solve(const PetscScalar* g_mine, std::vector<PetscScalar>& x);
  const InterfaceFactor& lu() const { return lu_; }

 private:
  bool gather_pattern(const InterfaceRows& mine, const std::vector<int>& counts);

  MPI_Comm comm_;
  InterfaceRows mine_;                 // this rank's last rows (pattern)
  std::vector<int> counts_, offsets_;  // rows per rank
  std::vector<int> value_counts_, value_offsets_;
  InterfaceRows all_;  // S
  InterfaceFactor lu_;
  std::vector<PetscScalar> g_;
};

}  // namespace pcsim::solvers
