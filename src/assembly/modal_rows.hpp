// Helpers of the modal catenary's terms (modal_terms.cpp, modal_exact_droppers.cpp).
#pragma once

#include <petscmat.h>

#include <Eigen/Core>
#include <vector>

#include "pcsim/assembly/modal_catenary.hpp"
#include "pcsim/assembly/term.hpp"
#include "pcsim/core/error.hpp"

namespace pcsim::assembly::modal_rows {

using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// The indices 0 .. m-1 of the modal coordinates, shared by a term's rank-one terms.
inline SharedEntries<PetscInt> all_modes(const ModalCatenary& catenary) {
  std::vector<PetscInt> modes(catenary.catenary_dofs());
  for (std::size_t k = 0; k < modes.size(); ++k) modes[k] = static_cast<PetscInt>(k);
  return modes;
}

// Adds a dense modal block (m x m) to J on the owner.
inline void add_modal_block(const ModalCatenary& catenary, const RowMatrix& block, Mat J) {
  if (!catenary.on_owner()) return;
  const PetscInt m = catenary.catenary_dofs();
  const auto modes = all_modes(catenary);
  PCSIM_PETSC(MatSetValues(J, m, modes.data(), m, modes.data(), block.data(), ADD_VALUES));
}

}  // namespace pcsim::assembly::modal_rows
