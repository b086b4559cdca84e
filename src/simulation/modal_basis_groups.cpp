// K's connected components, grouped for the reduced basis's eigensolves
// (see modal_basis_internal.hpp).
#include <algorithm>
#include <numeric>

#include "modal_basis_internal.hpp"
#include "pcsim/core/error.hpp"
#include "pcsim/core/union_find.hpp"

namespace pcsim::simulation::modal_detail {

namespace {

// Each DOF's component as the smallest DOF in it, from K's pattern (every
// rank holds the whole pattern: a line's, some ten entries a row).
std::vector<PetscInt> component_of_each_dof(Mat K) {
  PetscInt n;
  PCSIM_PETSC(MatGetSize(K, &n, nullptr));
  Mat* whole = whole_on_every_rank(K);
  PetscInt rows;
  const PetscInt *ia, *ja;
  PetscBool done;
  PCSIM_PETSC(MatGetRowIJ(whole[0], 0, PETSC_FALSE, PETSC_FALSE, &rows, &ia, &ja, &done));
  if (!done) throw SolverError("reduced basis: the stiffness matrix's pattern is not available");
  std::vector<PetscInt> parent(static_cast<std::size_t>(n));
  std::iota(parent.begin(), parent.end(), PetscInt{0});
  for (PetscInt i = 0; i < rows; ++i)
    for (PetscInt k = ia[i]; k < ia[i + 1]; ++k) {
      const PetscInt a = core::find_root(parent, i), b = core::find_root(parent, ja[k]);
      if (a != b) parent[std::max(a, b)] = std::min(a, b);  // the smaller DOF is the root
    }
  PCSIM_PETSC(MatRestoreRowIJ(whole[0], 0, PETSC_FALSE, PETSC_FALSE, &rows, &ia, &ja, &done));
  PCSIM_PETSC(MatDestroySubMatrices(1, &whole));
  for (PetscInt i = 0; i < n; ++i) parent[i] = core::find_root(parent, i);
  return parent;
}

}  // namespace

Mat* whole_on_every_rank(Mat A) {
  PetscInt n;
  PCSIM_PETSC(MatGetSize(A, &n, nullptr));
  IS all;
  PCSIM_PETSC(ISCreateStride(PETSC_COMM_SELF, n, 0, 1, &all));
  Mat* copy;
  PCSIM_PETSC(MatCreateSubMatrices(A, 1, &all, &all, MAT_INITIAL_MATRIX, &copy));
  PCSIM_PETSC(ISDestroy(&all));
  return copy;
}

std::vector<std::vector<PetscInt>> component_groups(Mat K, long min_group_dofs) {
  const std::vector<PetscInt> root = component_of_each_dof(K);
  const auto n = static_cast<PetscInt>(root.size());
  std::vector<PetscInt> size(root.size(), 0);
  for (PetscInt i = 0; i < n; ++i) ++size[root[i]];
  // Group of each root: its own for a large component, else the pool's
  // (numbered where its first DOF falls), in the order of the first DOFs.
  std::vector<long> group(root.size(), -1);
  long groups = 0, pool = -1;
  for (PetscInt i = 0; i < n; ++i) {
    if (root[i] != i) continue;
    if (size[i] >= min_group_dofs) {
      group[i] = groups++;
    } else {
      if (pool < 0) pool = groups++;
      group[i] = pool;
    }
  }
  std::vector<std::vector<PetscInt>> owned(static_cast<std::size_t>(groups));
  PetscInt lo, hi;
  PCSIM_PETSC(MatGetOwnershipRange(K, &lo, &hi));
  for (PetscInt i = lo; i < hi; ++i) owned[group[root[i]]].push_back(i);
  return owned;
}

}  // namespace pcsim::simulation::modal_detail
