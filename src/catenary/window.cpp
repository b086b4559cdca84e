#include "pcsim/catenary/window.hpp"

#include <array>
#include <cmath>
#include <map>

#include "pcsim/catenary/reactions.hpp"
#include "pcsim/core/error.hpp"

namespace pcsim::catenary {

namespace {

// The node of 'wire' nearest to station x.
int wire_node_at(const CatenaryMesh& mesh, const Wire& wire, double x) {
  int best = -1;
  for (int n : wire.nodes)
    if (best < 0 ||
        std::abs(mesh.nodes[n].position.x() - x) < std::abs(mesh.nodes[best].position.x() - x))
      best = n;
  return best;
}

using Key = std::array<long long, 3>;
Key position_key(const Eigen::Vector3d& p) {
  return {std::llround(p.x() * 1e6), std::llround(p.y() * 1e6), std::llround(p.z() * 1e6)};
}

}  // namespace

std::vector<int> release_window_ends(CatenaryMesh& mesh, const std::vector<double>& node_values,
                                     double impedance_factor) {
  if (mesh.support_x.size() < 3)
    throw SolverError("moving window: a mesh of at least two spans is needed");
  std::vector<int> ends;
  std::vector<const Wire*> of_end;
  for (const auto& wire : mesh.wires) {
    if (wire.nodes.size() < 2 ||
        (wire.kind != WireKind::contact && wire.kind != WireKind::messenger))
      continue;
    // Held vertically at an inner support of the line: the line reflects there too.
    const int inner = wire_node_at(mesh, wire, mesh.support_x[1]);
    if (mesh.nodes[inner].fixed[2]) continue;
    for (int end : {wire.nodes.front(), wire.nodes.back()})
      if (mesh.nodes[end].fixed[2]) ends.push_back(end), of_end.push_back(&wire);
  }
  const auto reactions = support_forces(mesh, node_values, ends);
  for (std::size_t i = 0; i < ends.size(); ++i) {
    mesh.nodes[ends[i]].fixed[2] = false;
    mesh.node_forces.push_back(
        {ends[i], Eigen::Vector3d(0.0, 0.0, reactions[i].z()), "window_end"});
    mesh.dashpots.push_back({ends[i], 2, impedance_factor * wave_impedance(*of_end[i])});
    mesh.pins.push_back({ends[i], 2, kPinStiffness, false});
  }
  return ends;
}

std::vector<int> shifted_nodes(const CatenaryMesh& mesh, double shift) {
  // Nodes at the same design position are paired in the order of their indices.
  std::map<Key, std::vector<int>> at;
  for (std::size_t n = 0; n < mesh.nodes.size(); ++n)
    at[position_key(mesh.nodes[n].position)].push_back(static_cast<int>(n));
  std::map<Key, std::size_t> used;
  std::vector<int> partner(mesh.nodes.size(), -1);
  for (std::size_t n = 0; n < mesh.nodes.size(); ++n) {
    const Key self = position_key(mesh.nodes[n].position);
    const std::size_t rank_here = used[self]++;
    const auto it = at.find(position_key(mesh.nodes[n].position + Eigen::Vector3d(shift, 0, 0)));
    if (it != at.end() && rank_here < it->second.size()) partner[n] = it->second[rank_here];
  }
  return partner;
}

}  // namespace pcsim::catenary
