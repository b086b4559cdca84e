#include "pcsim/catenary/reduced_basis.hpp"

#include <algorithm>
#include <numeric>

#include "pcsim/catenary/wind.hpp"
#include "pcsim/core/union_find.hpp"

namespace pcsim::catenary {

const char* fidelity_name(CatenaryFidelity f) {
  switch (f) {
    case CatenaryFidelity::nonlinear:
      return "nonlinear";
    case CatenaryFidelity::linear:
      return "linear";
    case CatenaryFidelity::modal:
      return "modal";
  }
  return "?";
}

const char* modal_method_name(ModalSettings::Method m) {
  switch (m) {
    case ModalSettings::Method::automatic:
      return "auto";
    case ModalSettings::Method::whole:
      return "whole";
    case ModalSettings::Method::window:
      return "window";
  }
  return "?";
}

std::vector<int> contact_wire_nodes(const CatenaryMesh& mesh) {
  std::vector<int> nodes;
  for (int w : mesh.contact_wire_list())
    nodes.insert(nodes.end(), mesh.wires[w].nodes.begin(), mesh.wires[w].nodes.end());
  return nodes;
}

std::vector<long> reduced_basis_rows(const CatenaryMesh& mesh, bool full_shapes) {
  std::vector<long> keys;
  const bool lateral = mesh.conditions.wind.any();  // the contact point's lateral motion
  for (int n : contact_wire_nodes(mesh)) {
    keys.push_back(basis_row_key(n, 2));
    keys.push_back(basis_row_key(n, 5));
    if (lateral) keys.push_back(basis_row_key(n, 1)), keys.push_back(basis_row_key(n, 4));
  }
  for (const auto& bar : mesh.bars)
    for (int n : bar.nodes)
      for (int c = 0; c < 3; ++c) keys.push_back(basis_row_key(n, c));
  for (int n : mesh.support_nodes) keys.push_back(basis_row_key(n, 2));
  for (const auto& d : mesh.dashpots) keys.push_back(basis_row_key(d.node, d.dof));
  for (const auto& p : mesh.pins) keys.push_back(basis_row_key(p.node, p.dof));
  if (full_shapes)
    for (std::size_t n = 0; n < mesh.nodes.size(); ++n)
      for (int c = 0; c < 3; ++c) keys.push_back(basis_row_key(static_cast<int>(n), c));
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  const auto turbulence = turbulence_row_keys(mesh);  // beyond every node's: still ascending
  keys.insert(keys.end(), turbulence.begin(), turbulence.end());
  return keys;
}

void order_columns_by_block(ReducedBasis& b) {
  const long m = static_cast<long>(b.size());
  const long rows = static_cast<long>(b.row_keys.size());
  b.column_blocks = {0, m};
  if (m == 0 || !b.shift.empty()) return;
  // Columns joined by every kept row's nonzeros (union-find, smaller root).
  std::vector<long> parent(static_cast<std::size_t>(m));
  std::iota(parent.begin(), parent.end(), 0L);
  for (long r = 0; r < rows; ++r) {
    const double* row = b.rows.data() + r * m;
    long first = -1;
    for (long k = 0; k < m; ++k) {
      if (row[k] == 0) continue;
      if (first < 0) {
        first = core::find_root(parent, k);
        continue;
      }
      const long root = core::find_root(parent, k);
      if (root == first) continue;
      parent[std::max(root, first)] = std::min(root, first);
      first = std::min(root, first);
    }
  }
  // Blocks in the order of their first columns (a root is its block's smallest column).
  std::vector<long> block(static_cast<std::size_t>(m), -1), count;
  for (long k = 0; k < m; ++k) {
    const long root = core::find_root(parent, k);
    if (block[root] < 0) {
      block[root] = static_cast<long>(count.size());
      count.push_back(0);
    }
    block[k] = block[root];
    ++count[block[k]];
  }
  if (count.size() == 1) return;
  std::vector<long> start(count.size() + 1, 0);
  for (std::size_t i = 0; i < count.size(); ++i) start[i + 1] = start[i] + count[i];
  std::vector<long> source(static_cast<std::size_t>(m));  // new column -> old
  {
    std::vector<long> next(start.begin(), start.end() - 1);
    for (long k = 0; k < m; ++k) source[next[block[k]]++] = k;
  }
  const auto permute = [&](std::vector<double>& v, long offset, std::vector<double>& tmp) {
    for (long j = 0; j < m; ++j) tmp[j] = v[offset + source[j]];
    std::copy(tmp.begin(), tmp.end(), v.begin() + offset);
  };
  std::vector<double> tmp(static_cast<std::size_t>(m));
  permute(b.omega2, 0, tmp);
  if (static_cast<long>(b.wind_damping.size()) == m) permute(b.wind_damping, 0, tmp);
  for (long r = 0; r < rows; ++r) permute(b.rows, r * m, tmp);
  b.column_blocks = start;
}

}  // namespace pcsim::catenary
