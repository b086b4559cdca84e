// The dot products a Woodbury capacitance needs, in one pass over memory
// (low_rank.cpp): for the terms whose u or z changed, u_r . z_j and
// z_r . u_j over every term j, and x . u_j, where VecMDot made one pass over
// every column per changed row (five passes a step with two moving contacts).
#pragma once

#include <petscvec.h>

#include <vector>

namespace pcsim::solvers {

// A u by its entries (global indices, none twice; the weights of the rank's
// own rows are read, the others skipped): a product with it reads only those
// entries of the other vector.
struct SparseU {
  const PetscInt* index = nullptr;
  const double* weight = nullptr;
  std::size_t size = 0;
};

struct CapacitanceDots {
  std::vector<Vec> us, zs;  // the k active terms' u and J0^-1 u (one layout)
  // Every u by its entries instead of the dense passes over us (empty: the
  // dense kernel): the FE catenary's terms, a contact's or a dropper's few
  // entries in vectors of tens of thousands. Each product sums its entries in
  // their order, then over the ranks: other bits than the dense kernel's
  // lanes, and the same symmetric and transposed bits as those.
  std::vector<SparseU> sparse_us;
  std::vector<std::size_t> rows;  // the changed terms, indices into us/zs
  bool transposed = false;        // z_r . u_j too (zu)
  // z_j = A^-1 u_j with A symmetric, so that u_i . z_j = u_j . z_i: each
  // pair's product formed once, as u_a . z_b (a <= b), in uz only (not with
  // transposed): row r (term i) holds j >= i, and j < i for j not in rows
  // (those rows' own); the other entries are 0.
  bool symmetric = false;
  Vec x = nullptr;  // x . u_j too (ux), when given
};

// uz[r k + j] = u_rows[r] . z_j, zu[r k + j] = u_j . z_rows[r] (if
// transposed), ux[j] = x . u_j (if x), over the local entries in blocks of
// 256 that every stream of a block reads from L1, then over the ranks (one
// reduction). Each product sums in 4 lanes (entry e into lane e mod 4; the
// lanes (l0 + l2) + (l1 + l3)), u first: u_i . z_j has the same bits in uz
// and zu, and u_j . z_i of a symmetric row (formed with z_i's loads shared)
// has the bits of row j's. The vector kernel (AVX2 and FMA, where the
// processor has them) shares each load of a u among four products;
// vector_kernel false takes the portable one (tests). With sparse_us (one
// per term) every product is summed from the u's entries instead.
void capacitance_dots(const CapacitanceDots& in, std::vector<double>& uz, std::vector<double>& zu,
                      std::vector<double>& ux, bool vector_kernel = true);

}  // namespace pcsim::solvers
