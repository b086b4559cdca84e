// The products G = V^T M S V of a moving window's shift over the modal
// data's vectors (modal_basis_internal.hpp, ShiftProducts).
#include <Eigen/Core>
#include <algorithm>

#include "modal_basis_internal.hpp"
#include "pcsim/core/error.hpp"

namespace pcsim::simulation::modal_detail {

ShiftProducts::ShiftProducts(Mat M, Mat S) : M_(M), S_(S) {}

void ShiftProducts::append(Vec v) {
  PCSIM_PETSC(VecGetLocalSize(v, &local_));
  if (count_ % kBlock == 0) blocks_.emplace_back(local_, kBlock);
  const PetscScalar* a;
  PCSIM_PETSC(VecGetArrayRead(v, &a));
  std::copy(a, a + local_, blocks_.back().col(count_ % kBlock).data());
  PCSIM_PETSC(VecRestoreArrayRead(v, &a));
  ++count_;
}

// W = M S V by blocks of columns, G(I, J) = V_I^T W_J on every rank (dense
// products: the local gemms are the cost, ~2 n c^2 flops), then summed over
// the ranks.
std::vector<double> ShiftProducts::compute(Vec like) {
  const long c = count_;
  if (c == 0) return {};
  Vec column, shifted, w;
  PCSIM_PETSC(VecDuplicate(like, &column));
  PCSIM_PETSC(VecDuplicate(like, &shifted));
  PCSIM_PETSC(VecDuplicate(like, &w));
  const auto width = [&](std::size_t b) {
    return std::min<long>(kBlock, c - static_cast<long>(b) * kBlock);
  };
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> G(c, c);
  Eigen::MatrixXd W(local_, kBlock);
  for (std::size_t J = 0; J < blocks_.size(); ++J) {
    for (long j = 0; j < width(J); ++j) {
      PetscScalar* a;
      PCSIM_PETSC(VecGetArray(column, &a));
      std::copy(blocks_[J].col(j).data(), blocks_[J].col(j).data() + local_, a);
      PCSIM_PETSC(VecRestoreArray(column, &a));
      PCSIM_PETSC(MatMult(S_, column, shifted));
      PCSIM_PETSC(MatMult(M_, shifted, w));
      const PetscScalar* r;
      PCSIM_PETSC(VecGetArrayRead(w, &r));
      std::copy(r, r + local_, W.col(j).data());
      PCSIM_PETSC(VecRestoreArrayRead(w, &r));
    }
    for (std::size_t I = 0; I < blocks_.size(); ++I)
      G.block(static_cast<long>(I) * kBlock, static_cast<long>(J) * kBlock, width(I), width(J))
          .noalias() = blocks_[I].leftCols(width(I)).transpose() * W.leftCols(width(J));
  }
  for (Vec* v : {&column, &shifted, &w}) PCSIM_PETSC(VecDestroy(v));
  blocks_.clear();
  MPI_Allreduce(MPI_IN_PLACE, G.data(), static_cast<int>(G.size()), MPI_DOUBLE, MPI_SUM,
                PetscObjectComm(reinterpret_cast<PetscObject>(like)));
  return std::vector<double>(G.data(), G.data() + G.size());
}

}  // namespace pcsim::simulation::modal_detail
