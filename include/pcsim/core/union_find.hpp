// Disjoint sets over 0..n-1 as a parent array (each set's root its own
// parent): the root of i, halving the path on the way. The connected parts of
// a stiffness matrix's graph (simulation/modal_basis_groups.cpp) and the
// column blocks of a reduced basis (catenary/reduced_basis.cpp).
#pragma once

#include <vector>

namespace pcsim::core {

template <class Index>
Index find_root(std::vector<Index>& parent, Index i) {
  while (parent[i] != i) {
    parent[i] = parent[parent[i]];
    i = parent[i];
  }
  return i;
}

}  // namespace pcsim::core
