// Pieces of the reduced-basis computation (modal_basis.cpp drives them):
// the catenary's operators at the static configuration, the kept rows of a
// global vector, the eigenpairs of an interval streamed one by one.
//
// Memory given back: a library PETSc loads (SuperLU_DIST's constructor)
// turns off the C library's mmap for large blocks (mallopt(M_MMAP_MAX, 0)),
// so every block freed stays in the heap, resident, until malloc_trim. The
// computation gives back what it frees in large parts (a raise's superseded
// basis, the columns copied, the smaller shift products G, the summing
// buffer; the assembly the data's rows): the 1000-span window's first run
// peaks at 765 MB instead of 966 (docs/benchmarks.md, "The 1000-span
// window's first-run peak").
#pragma once

#include <petscksp.h>

#include <Eigen/Core>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "pcsim/assembly/catenary_system.hpp"
#include "pcsim/catenary/reduced_basis.hpp"
#include "vector_store.hpp"

namespace pcsim::simulation::modal_detail {

// K_T (every term) and M of the catenary at x; symmetric.
struct Operators {
  Mat K = nullptr, M = nullptr;
  Operators(assembly::CatenarySystem& system, Vec x);
  Operators(Mat K_, Mat M_);  // takes a reference to each (tests)
  ~Operators();
  Operators(const Operators&) = delete;
  Operators& operator=(const Operators&) = delete;
};

// The kept rows (catenary::basis_row_key) of global vectors, on every rank;
// a turbulence row (catenary::turbulence_row_keys) is the product with its
// column of 'loads' (assembly::turbulence_load_matrix), a generalised force.
class RowGather {
 public:
  RowGather(const assembly::CatenarySystem& system, const std::vector<long>& keys,
            Mat loads = nullptr);
  ~RowGather();
  RowGather(const RowGather&) = delete;
  RowGather& operator=(const RowGather&) = delete;
  // out[keys.size()]: the values of the rows (0 for constrained DOFs).
  void gather(Vec v, double* out) const;
  std::size_t size() const { return size_; }

 private:
  VecScatter scatter_ = nullptr;
  Vec local_ = nullptr;
  std::vector<std::size_t> slot_;  // row of each scattered value
  std::size_t size_ = 0;
  // Turbulence rows: L^T v (column layout), gathered to every rank, into
  // the rows from load_slot_ on.
  Mat loads_ = nullptr;
  Vec forces_ = nullptr, forces_all_ = nullptr;
  VecScatter to_all_ = nullptr;
  std::size_t load_slot_ = 0;
};

// Called with each eigenpair (lambda, phi), phi M-normalised with its largest
// component positive, in ascending order of lambda.
using ModeSink = std::function<void(double lambda, Vec phi)>;

// The DOFs of K's connected components (two DOFs in one when an element
// couples them, directly or through others: a line's tension sections,
// which share no element, are one each), in groups whose spectra can be
// computed apart: each component of at least min_group_dofs DOFs alone, the
// smaller ones together. Each group's global indices owned by this rank,
// ascending; the groups in the order of their first DOF. One group when K
// is connected. Collective.
constexpr long kMinGroupDofs = 2000;
std::vector<std::vector<PetscInt>> component_groups(Mat K, long min_group_dofs = kMinGroupDofs);
// The whole of a distributed matrix on every rank (a sequential AIJ matrix,
// destroyed with MatDestroySubMatrices(1, &copy)).
Mat* whole_on_every_rank(Mat A);

// Every eigenpair of K phi = lambda M phi with lambda in [0, lambda_max],
// computed in chunks of the interval (options prefix -modal_), each group
// of component_groups on its own DOFs (-pcsim_debug_modes_whole: the whole
// structure at once, as before 2026-12-03; tests); returns the
// largest relative residual ||K phi - lambda M phi|| / (lambda ||M phi||).
// progress(done, total, parts) after each chunk (may be empty); parts: the
// groups computed apart.
// lambda_above > 0: only those above it (a raised cut-off's).
// chunk_modes: about the modes of a chunk (of the largest group's);
// min_group_dofs: component_groups's (tests).
constexpr double kChunkModes = 800;
double stream_modes(const Operators& op, double lambda_above, double lambda_max,
                    const ModeSink& sink, const std::function<void(long, long, int)>& progress,
                    double chunk_modes = kChunkModes, long min_group_dofs = kMinGroupDofs);

// G = V^T M S V (row-major, c x c, every rank) over the vectors V appended
// (c of them, their local parts kept: n x c doubles in all, in a
// VectorStore: on a file in spill_dir but for the block being filled): a
// moving window's shift in the computed vectors (ModalData::shift_products),
// in the order appended. compute() after more appends computes only the rows
// and columns of the new vectors (a raised cut-off's modes): with G(i, j) of
// a new row i and an old column j as (S^T M v_i)^T v_j.
class ShiftProducts {
 public:
  ShiftProducts(Mat M, Mat S, std::string spill_dir);
  ~ShiftProducts();
  void append(Vec v);
  using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  // Collective; 'like' a vector of the layout. keep_vectors false: frees
  // the columns (no later compute()). A view of G, valid until the next
  // compute() or take().
  Eigen::Map<const RowMatrix> compute(Vec like, bool keep_vectors);
  // G's storage (row-major, c x c) moved out: no copy of G beside it (the
  // 1000-span window's G at 136 Hz is 224 MB); no later compute() until it
  // is given back (the same values, in the order appended).
  std::vector<double> take();
  void give_back(std::vector<double>&& g);
  long count() const { return count_; }
  long spilled_blocks() const;  // blocks of the vectors on file (tests)

 private:
  void new_columns(Vec like);
  void new_rows_of_old_columns(Vec like);
  Mat M_, S_;
  std::string spill_dir_;
  PetscInt local_ = 0;
  long count_ = 0, computed_ = 0;  // vectors appended, and in G
  std::unique_ptr<VectorStore> store_;
  std::vector<double> g_;  // G, row-major, computed_ x computed_ (c x c while computed)
  bool taken_ = false;
};

// C = A^T B (column-major; A: k x m, B: k x n, C: m x n with leading
// dimension ldc) by the system's BLAS (Debian's libblas.so.3: BLIS with
// scripts/setup-deps.sh, ~3 x Eigen's kernels at pcsim's portable flags;
// runs/bench_blas.sh): the local part of products over distributed vectors.
void product_tn(long m, long n, long k, const double* A, const double* B, double* C, long ldc);

// Rows [begin, end) of a column-major block.
struct RowRange {
  long begin, end;
};
// The runs of rows of W where a column in [first_column, end_column) is not zero.
std::vector<RowRange> nonzero_row_ranges(const Eigen::MatrixXd& W, long first_column,
                                         long end_column);
// C = sum over the row ranges of A(rows, :)^T B(rows, :) (column-major, A: m
// columns with leading dimension lda, B: n columns with ldb, C: m x n with
// ldc): product_tn where the other rows of A or B are zero.
void product_tn_rows(long m, long n, const std::vector<RowRange>& rows, const double* A, long lda,
                     const double* B, long ldb, double* C, long ldc);

// Every eigenpair of a small structure by a dense solve on every rank.
double stream_all_modes_dense(const Operators& op, const ModeSink& sink);

}  // namespace pcsim::simulation::modal_detail
