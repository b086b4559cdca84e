// The node-values type shared by every part: the state of a catenary as 6
// values per node, position r and slope r' = dr/dchi (thesis eq. 3.2), node
// by node (node-major), SI units.
#pragma once

#include <vector>

namespace pcsim {

constexpr int kNodeDofs = 6;

using NodeValues = std::vector<double>;  // kNodeDofs per node

// Positions (3 per node) from node values.
inline std::vector<double> positions_from_node_values(const NodeValues& node_values) {
  std::vector<double> positions(node_values.size() / kNodeDofs * 3);
  for (std::size_t n = 0; n < node_values.size() / kNodeDofs; ++n)
    for (int c = 0; c < 3; ++c) positions[3 * n + c] = node_values[kNodeDofs * n + c];
  return positions;
}

}  // namespace pcsim
