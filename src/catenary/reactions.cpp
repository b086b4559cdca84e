// Support forces, pull-off forces, release of the tensioning devices (see
// reactions.hpp).
#include "pcsim/catenary/reactions.hpp"

#include <cmath>
#include <map>

#include "pcsim/catenary/elements.hpp"

namespace pcsim::catenary {

namespace {

Vec12 cable_dofs(const CatenaryMesh& mesh, const std::vector<double>& values, int e) {
  Vec12 q;
  for (int a = 0; a < 2; ++a)
    for (int c = 0; c < 6; ++c) q[6 * a + c] = values[6 * mesh.cables[e].nodes[a] + c];
  return q;
}

Vec6 bar_dofs(const CatenaryMesh& mesh, const std::vector<double>& values, int b) {
  Vec6 q;
  for (int a = 0; a < 2; ++a)
    for (int c = 0; c < 3; ++c) q[3 * a + c] = values[6 * mesh.bars[b].nodes[a] + c];
  return q;
}

}  // namespace

std::vector<Eigen::Vector3d> support_forces(const CatenaryMesh& mesh,
                                            const std::vector<double>& values,
                                            const std::vector<int>& nodes,
                                            bool without_steady_arms) {
  std::map<int, std::size_t> slot;
  for (std::size_t i = 0; i < nodes.size(); ++i) slot.emplace(nodes[i], i);
  std::vector<Eigen::Vector3d> r(nodes.size(), Eigen::Vector3d::Zero());
  auto add = [&](int node, const Eigen::Vector3d& f) {
    auto it = slot.find(node);
    if (it != slot.end()) r[it->second] += f;
  };
  for (std::size_t e = 0; e < mesh.cables.size(); ++e) {
    const auto& el = mesh.cables[e];
    if (!slot.count(el.nodes[0]) && !slot.count(el.nodes[1])) continue;
    const CableSection section = cable_section(mesh.wires[el.wire], el);
    Vec12 f;
    cable_internal_force(section, el.ref_length, el.unstressed_length,
                         cable_dofs(mesh, values, static_cast<int>(e)), f);
    f -= cable_gravity_force(section, el.ref_length, mesh.gravity);
    f -= cable_line_load(el.ref_length, el.unstressed_length, el.wind_load);
    add(el.nodes[0], f.segment<3>(0));
    add(el.nodes[1], f.segment<3>(6));
  }
  for (std::size_t b = 0; b < mesh.bars.size(); ++b) {
    const auto& bar = mesh.bars[b];
    if (without_steady_arms && bar.kind == BarKind::steady_arm) continue;
    if (!slot.count(bar.nodes[0]) && !slot.count(bar.nodes[1])) continue;
    Vec6 f;
    bar_internal_force(bar_parameters(bar), bar_dofs(mesh, values, static_cast<int>(b)), f);
    f -= bar_gravity_force(bar.mass, mesh.gravity);
    add(bar.nodes[0], f.head<3>());
    add(bar.nodes[1], f.tail<3>());
  }
  for (const auto& pm : mesh.point_masses) add(pm.node, -pm.mass * mesh.gravity);
  for (const auto& nf : mesh.node_forces) add(nf.node, -nf.force);
  return r;
}

std::vector<double> registration_forces(const CatenaryMesh& mesh,
                                        const std::vector<double>& values) {
  std::vector<int> nodes;
  for (const auto& reg : mesh.registrations) nodes.push_back(reg.node);
  const auto forces = support_forces(mesh, values, nodes, true);
  std::vector<double> lateral;
  for (std::size_t i = 0; i < nodes.size(); ++i)
    lateral.push_back(forces[i].dot(mesh.registrations[i].lateral));
  return lateral;
}

void release_tensioning_devices(CatenaryMesh& mesh, const std::vector<double>& values) {
  std::vector<int> nodes;
  for (const auto& dev : mesh.tensioning_devices) nodes.push_back(dev.node);
  const auto forces = support_forces(mesh, values, nodes);
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    auto& dev = mesh.tensioning_devices[i];
    if (dev.released) continue;
    const Eigen::Vector3d& d = dev.direction;
    const bool along_x = std::abs(d.y()) < 1e-12;
    Node& node = mesh.nodes[dev.node];
    node.fixed[0] = false;
    Eigen::Vector3d pull(forces[i].x(), 0.0, 0.0);
    if (!along_x) {
      node.fixed[1] = false;
      pull.y() = forces[i].y();
      mesh.springs.push_back({dev.node, 0, kGuideStiffness, Eigen::Vector3d(-d.y(), d.x(), 0.0)});
    }
    mesh.node_forces.push_back({dev.node, pull, "tensioning_device"});
    if (dev.kind == TensioningKind::weight && dev.mass > 0)
      mesh.point_masses.push_back({dev.node, dev.mass, "balance_weight"});
    if (dev.kind == TensioningKind::spring) {
      if (along_x)
        mesh.springs.push_back({dev.node, 0, dev.stiffness, Eigen::Vector3d::Zero()});
      else
        mesh.springs.push_back({dev.node, 0, dev.stiffness, d});
    }
    dev.pull = forces[i].dot(d);
    dev.released = true;
  }
}

}  // namespace pcsim::catenary
