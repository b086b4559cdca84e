#include "pcsim/catenary/reduced_basis.hpp"

#include <algorithm>

#include "pcsim/catenary/wind.hpp"

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

}  // namespace pcsim::catenary
