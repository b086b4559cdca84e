// The products G = V^T M S V of a moving window's shift over the modal
// data's vectors (modal_basis_internal.hpp, ShiftProducts).
#include <malloc.h>

#include <Eigen/Core>
#include <algorithm>

#include "modal_basis_internal.hpp"
#include "pcsim/core/dense_gemm.hpp"
#include "pcsim/core/error.hpp"
#include "pcsim/core/profiling.hpp"

namespace pcsim::simulation::modal_detail {

namespace {

// v's local part from a column (local rows).
void set_vector(Vec v, const double* column) {
  PetscInt n;
  PetscScalar* a;
  PCSIM_PETSC(VecGetLocalSize(v, &n));
  PCSIM_PETSC(VecGetArray(v, &a));
  std::copy(column, column + n, a);
  PCSIM_PETSC(VecRestoreArray(v, &a));
}

// y = A x, or y = A^T x, into column j of W (local rows).
void product_column(Mat A, Vec x, Vec y, bool transpose, Eigen::MatrixXd& W, long j) {
  PCSIM_PETSC(transpose ? MatMultTranspose(A, x, y) : MatMult(A, x, y));
  const PetscScalar* r;
  PCSIM_PETSC(VecGetArrayRead(y, &r));
  std::copy(r, r + W.rows(), W.col(j).data());
  PCSIM_PETSC(VecRestoreArrayRead(y, &r));
}

}  // namespace

void product_tn(long m, long n, long k, const double* A, const double* B, double* C, long ldc) {
  product_tn_rows(m, n, {{0, k}}, A, k, B, k, C, ldc);
}

std::vector<RowRange> nonzero_row_ranges(const Eigen::MatrixXd& W, long first_column,
                                         long end_column) {
  std::vector<char> nonzero(static_cast<std::size_t>(W.rows()), 0);
  for (long j = first_column; j < end_column; ++j)  // column by column: W is column-major
    for (long i = 0; i < W.rows(); ++i) nonzero[i] |= W(i, j) != 0.0;
  std::vector<RowRange> ranges;
  for (long i = 0; i < W.rows(); ++i) {
    if (!nonzero[i]) continue;
    if (!ranges.empty() && ranges.back().end == i)
      ++ranges.back().end;
    else
      ranges.push_back({i, i + 1});
  }
  return ranges;
}

void product_tn_rows(long m, long n, const std::vector<RowRange>& rows, const double* A, long lda,
                     const double* B, long ldb, double* C, long ldc) {
  if (m == 0 || n == 0) return;
  bool written = false;
  for (const RowRange& r : rows) {
    if (r.end == r.begin) continue;
    dense_gemm(true, false, m, n, r.end - r.begin, 1.0, A + r.begin, lda, B + r.begin, ldb,
               written ? 1.0 : 0.0, C, ldc);
    written = true;
  }
  if (!written)  // no rows: C = 0
    for (long j = 0; j < n; ++j) std::fill(C + j * ldc, C + j * ldc + m, 0.0);
}

ShiftProducts::ShiftProducts(Mat M, Mat S, std::string spill_dir)
    : M_(M), S_(S), spill_dir_(std::move(spill_dir)) {}

ShiftProducts::~ShiftProducts() = default;

long ShiftProducts::spilled_blocks() const {
  long n = 0;
  for (std::size_t b = 0; store_ && b < store_->blocks(); ++b) n += store_->spilled(b) ? 1 : 0;
  return n;
}

void ShiftProducts::append(Vec v) {
  PCSIM_PETSC(VecGetLocalSize(v, &local_));
  if (!store_) store_ = std::make_unique<VectorStore>(local_, spill_dir_);
  const PetscScalar* a;
  PCSIM_PETSC(VecGetArrayRead(v, &a));
  store_->append(a);
  PCSIM_PETSC(VecRestoreArrayRead(v, &a));
  ++count_;
}

// G(:, j) = V^T (M S v_j) for the new columns j, by blocks of columns (dense
// products: the local gemms are the cost, ~2 n' c^2 flops at the first call,
// n' the rows of M S V that are not zero; blocks on file are read back once
// per block of new columns).
void ShiftProducts::new_columns(Vec like) {
  constexpr long kBlock = VectorStore::kBlock;
  Vec column, shifted, w;
  PCSIM_PETSC(VecDuplicate(like, &column));
  PCSIM_PETSC(VecDuplicate(like, &shifted));
  PCSIM_PETSC(VecDuplicate(like, &w));
  Eigen::MatrixXd W(local_, kBlock), scratch;
  for (std::size_t J = static_cast<std::size_t>(computed_ / kBlock); J < store_->blocks(); ++J) {
    const long first = static_cast<long>(J) * kBlock, width = store_->width(J);
    const long j0 = std::max(computed_ - first, 0L);  // the block's first new column
    const Eigen::MatrixXd& VJ = store_->block(J, scratch);
    for (long j = j0; j < width; ++j) {
      set_vector(column, VJ.col(j).data());
      PCSIM_PETSC(MatMult(S_, column, shifted));
      product_column(M_, shifted, w, false, W, j);
    }
    // G (row-major) block (I, new columns) as the column-major W^T V_I,
    // over W's rows that are not zero: M S v is zero where the window's
    // front spans would take their field from beyond it (2 of its spans).
    const ScopedEvent timed(log_events().shift_gemm);
    const auto rows = nonzero_row_ranges(W, j0, width);  // W's columns beyond width: unset
    for (std::size_t I = 0; I < store_->blocks(); ++I)
      product_tn_rows(width - j0, store_->width(I), rows, W.col(j0).data(), local_,
                      store_->block(I, scratch).data(), local_,
                      g_.data() + static_cast<long>(I) * kBlock * count_ + first + j0, count_);
  }
  for (Vec* v : {&column, &shifted, &w}) PCSIM_PETSC(VecDestroy(v));
}

// G(i, j) = (S^T M v_i)^T v_j for the new rows i and the old columns j.
void ShiftProducts::new_rows_of_old_columns(Vec like) {
  constexpr long kBlock = VectorStore::kBlock;
  const long fresh = count_ - computed_;
  if (computed_ == 0 || fresh == 0) return;
  Vec column, mass, z;
  PCSIM_PETSC(VecDuplicate(like, &column));
  PCSIM_PETSC(VecDuplicate(like, &mass));
  PCSIM_PETSC(VecDuplicate(like, &z));
  Eigen::MatrixXd Z(local_, fresh), scratch;
  for (std::size_t I = static_cast<std::size_t>(computed_ / kBlock); I < store_->blocks(); ++I) {
    const Eigen::MatrixXd& VI = store_->block(I, scratch);
    const long first = static_cast<long>(I) * kBlock;
    for (long i = std::max(computed_, first); i < first + store_->width(I); ++i) {
      set_vector(column, VI.col(i - first).data());
      PCSIM_PETSC(MatMult(M_, column, mass));
      product_column(S_, mass, z, true, Z, i - computed_);
    }
  }
  const ScopedEvent timed(log_events().shift_gemm);
  const auto rows = nonzero_row_ranges(Z, 0, fresh);  // S^T M v: zero on the window's rear 2 spans
  for (std::size_t I = 0; static_cast<long>(I) * kBlock < computed_; ++I) {
    const long first = static_cast<long>(I) * kBlock;
    const long cols = std::min(store_->width(I), computed_ - first);  // old columns of block I
    // G (row-major) block (new rows, old columns of I) as the column-major V_I^T Z.
    product_tn_rows(cols, fresh, rows, store_->block(I, scratch).data(), local_, Z.data(), local_,
                    g_.data() + computed_ * count_ + first, count_);
  }
  for (Vec* v : {&column, &mass, &z}) PCSIM_PETSC(VecDestroy(v));
}

Eigen::Map<const ShiftProducts::RowMatrix> ShiftProducts::compute(Vec like, bool keep_vectors) {
  if (taken_) throw SolverError("shift products: computed after they were taken");
  const long c = count_, old = computed_;
  if (c == old) return {g_.data(), c, c};
  const ScopedEvent timed(log_events().shift_products);
  {  // G grows; its computed part stays
    std::vector<double> grown(static_cast<std::size_t>(c * c));
    for (long i = 0; i < old; ++i)
      std::copy(g_.begin() + i * old, g_.begin() + (i + 1) * old, grown.begin() + i * c);
    g_.swap(grown);
  }
  malloc_trim(0);  // the smaller G freed: given back (modal_basis_internal.hpp)
  auto G = Eigen::Map<RowMatrix>(g_.data(), c, c);
  new_columns(like);
  new_rows_of_old_columns(like);
  if (!keep_vectors) store_->clear();
  const MPI_Comm comm = PetscObjectComm(reinterpret_cast<PetscObject>(like));
  if (old == 0) {
    MPI_Allreduce(MPI_IN_PLACE, g_.data(), static_cast<int>(g_.size()), MPI_DOUBLE, MPI_SUM, comm);
  } else {  // the new parts: the new columns of every row, the old columns of the new rows
    std::vector<double> sums;
    sums.reserve(static_cast<std::size_t>(c * (c - old) + (c - old) * old));
    for (long i = 0; i < c; ++i)
      for (long j = old; j < c; ++j) sums.push_back(G(i, j));
    for (long i = old; i < c; ++i)
      for (long j = 0; j < old; ++j) sums.push_back(G(i, j));
    MPI_Allreduce(MPI_IN_PLACE, sums.data(), static_cast<int>(sums.size()), MPI_DOUBLE, MPI_SUM,
                  comm);
    auto s = sums.begin();
    for (long i = 0; i < c; ++i)
      for (long j = old; j < c; ++j) G(i, j) = *s++;
    for (long i = old; i < c; ++i)
      for (long j = 0; j < old; ++j) G(i, j) = *s++;
  }
  malloc_trim(0);  // the sums' buffer and the products' blocks freed: given back
  computed_ = c;
  return {g_.data(), c, c};
}

std::vector<double> ShiftProducts::take() {
  if (computed_ != count_) throw SolverError("shift products: taken before they were computed");
  taken_ = true;
  return std::move(g_);
}

void ShiftProducts::give_back(std::vector<double>&& g) {
  if (!taken_ || g.size() != static_cast<std::size_t>(computed_ * computed_))
    throw SolverError("shift products: given back what was not taken");
  g_ = std::move(g);
  taken_ = false;
}

}  // namespace pcsim::simulation::modal_detail
