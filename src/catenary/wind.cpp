#include "pcsim/catenary/wind.hpp"

#include <algorithm>
#include <cmath>

namespace pcsim::catenary {

namespace {
// The cross-flow drag per length of a cylinder (diameter d, coefficient Cd)
// along `tangent`: 1/2 rho Cd d |V_n| V_n, V_n the wind's normal component.
Eigen::Vector3d cross_flow_drag(double diameter, double drag_coefficient,
                                const Eigen::Vector3d& tangent, const Eigen::Vector3d& velocity,
                                double air_density) {
  const Eigen::Vector3d t = tangent.normalized();
  const Eigen::Vector3d vn = velocity - velocity.dot(t) * t;
  return 0.5 * air_density * drag_coefficient * diameter * vn.norm() * vn;
}
}  // namespace

Eigen::Vector3d wire_drag(const Wire& wire, const Eigen::Vector3d& tangent,
                          const Eigen::Vector3d& velocity, double air_density) {
  return cross_flow_drag(wire_diameter(wire), wire_drag_coefficient(wire), tangent, velocity,
                         air_density);
}

Eigen::Vector3d bar_drag(const BarElement& bar, const Eigen::Vector3d& chord,
                         const Eigen::Vector3d& velocity, double air_density) {
  return cross_flow_drag(bar_diameter(bar), bar_drag_coefficient(bar), chord, velocity,
                         air_density) *
         chord.norm();
}

void set_wind_loads(CatenaryMesh& mesh) {
  const auto& wind = mesh.conditions.wind;
  const Eigen::Vector3d v = wind.velocity();
  for (auto& el : mesh.cables) {
    if (!wind.any()) {
      el.wind_load.setZero();
      continue;
    }
    const Eigen::Vector3d chord =
        mesh.nodes[el.nodes[1]].position - mesh.nodes[el.nodes[0]].position;
    el.wind_load = wire_drag(mesh.wires[el.wire], chord, v, wind.air_density);
  }
  auto& forces = mesh.node_forces;
  forces.erase(std::remove_if(forces.begin(), forces.end(),
                              [](const NodeForce& f) { return f.label == kBarWindLabel; }),
               forces.end());
  if (!wind.any()) return;
  for (const auto& bar : mesh.bars) {
    if (bar_diameter(bar) <= 0) continue;
    const Eigen::Vector3d chord =
        mesh.nodes[bar.nodes[1]].position - mesh.nodes[bar.nodes[0]].position;
    const Eigen::Vector3d half = 0.5 * bar_drag(bar, chord, v, wind.air_density);
    if (half.isZero()) continue;
    for (int node : bar.nodes) forces.push_back({node, half, kBarWindLabel});
  }
}

namespace {

// A wire's nodes as (station, lateral offset from the centre line), in the
// order of their stations.
std::vector<std::pair<double, double>> lateral_profile(const CatenaryMesh& mesh, const Wire& wire,
                                                       const std::vector<double>& values) {
  std::vector<std::pair<double, double>> out;
  for (int n : wire.nodes) {
    const Eigen::Vector2d p(values[6 * n], values[6 * n + 1]);
    const double s = mesh.track.station(p);
    out.emplace_back(s, (p - mesh.track.point(s)).dot(mesh.track.normal(s)));
  }
  std::sort(out.begin(), out.end());
  return out;
}

// Linear interpolation in a profile; false outside it.
bool lateral_at(const std::vector<std::pair<double, double>>& profile, double s, double& y) {
  if (profile.size() < 2 || s < profile.front().first || s > profile.back().first) return false;
  auto hi = std::lower_bound(profile.begin(), profile.end(), std::make_pair(s, -1e300));
  if (hi == profile.begin()) ++hi;
  if (hi == profile.end()) --hi;
  const auto lo = hi - 1;
  const double w = hi->first > lo->first ? (s - lo->first) / (hi->first - lo->first) : 0.0;
  y = (1 - w) * lo->second + w * hi->second;
  return true;
}

// The supports' stations: the design's, or the x of the contact wires'
// nodes held laterally.
std::vector<double> support_stations(const CatenaryMesh& mesh) {
  if (!mesh.support_x.empty()) return mesh.support_x;
  std::vector<double> x;
  for (int w : mesh.contact_wire_list())
    for (int n : mesh.wires[w].nodes)
      if (mesh.nodes[n].fixed[1]) x.push_back(mesh.nodes[n].position.x());
  std::sort(x.begin(), x.end());
  x.erase(std::unique(x.begin(), x.end()), x.end());
  return x;
}

}  // namespace

BlowOff measure_blow_off(const CatenaryMesh& mesh, const std::vector<double>& bare,
                         const std::vector<double>& now) {
  BlowOff b;
  b.permissible_m = mesh.conditions.wind.permissible_m();
  const auto supports = support_stations(mesh);
  std::vector<std::pair<double, int>> stations;  // (x, at support)
  for (std::size_t k = 0; k < supports.size(); ++k) {
    stations.emplace_back(supports[k], 1);
    if (k + 1 < supports.size()) stations.emplace_back(0.5 * (supports[k] + supports[k + 1]), 0);
  }
  const auto wires = mesh.contact_wire_list();
  for (std::size_t i = 0; i < wires.size(); ++i) {
    const auto& wire = mesh.wires[wires[i]];
    const auto p_now = lateral_profile(mesh, wire, now), p_bare = lateral_profile(mesh, wire, bare);
    for (const auto& [s, support] : stations) {
      double y = 0, y0 = 0;
      if (!lateral_at(p_now, s, y) || !lateral_at(p_bare, s, y0)) continue;
      b.x.push_back(s), b.at_support.push_back(support), b.wire.push_back(static_cast<int>(i));
      b.lateral.push_back(y), b.lateral_bare.push_back(y0);
    }
    for (const auto& [s, y] : p_now)  // the largest at any node (between the points too)
      if (std::abs(y) > b.max_excursion_m) b.max_excursion_m = std::abs(y), b.max_excursion_x = s;
  }
  return b;
}

TurbulenceGrid turbulence_grid(const CatenaryMesh& mesh) {
  const auto& s = mesh.conditions.wind.turbulence;
  double lo = 1e300, hi = -1e300;
  for (const auto& el : mesh.cables)
    for (int n : el.nodes)
      lo = std::min(lo, mesh.nodes[n].position.x()), hi = std::max(hi, mesh.nodes[n].position.x());
  if (mesh.cables.empty()) lo = hi = 0;
  const int count = std::max(2, static_cast<int>(std::ceil((hi - lo) / s.grid_spacing)) + 1);
  return {lo, s.grid_spacing, count};
}

std::vector<long> turbulence_row_keys(const CatenaryMesh& mesh) {
  std::vector<long> keys;
  const auto& wind = mesh.conditions.wind;
  if (!wind.any() || !wind.turbulence.on) return keys;
  const TurbulenceGrid grid = turbulence_grid(mesh);
  for (int c = 0; c < 2; ++c)
    for (int i = 0; i < grid.count; ++i) keys.push_back(turbulence_row_key(mesh, grid, c, i));
  return keys;
}

}  // namespace pcsim::catenary
