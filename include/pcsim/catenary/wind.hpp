// Wind on the wires (docs/conditions.md, issue 25): the mean wind's drag on
// every cable element, and the contact wires' lateral position under it
// (the static blow-off check).
#pragma once

#include <vector>

#include "pcsim/catenary/mesh.hpp"
#include "pcsim/catenary/results.hpp"

namespace pcsim::catenary {

// Drag per length of a wire in a wind of velocity V (horizontal) on an
// element of unit design tangent t: the component of V normal to the wire,
// V_n = V - (V.t) t, gives q = rho Cd d |V_n| V_n / 2 (the cross-flow
// principle) [N/m].
Eigen::Vector3d wire_drag(const Wire& wire, const Eigen::Vector3d& tangent,
                          const Eigen::Vector3d& velocity, double air_density);

// The drag on a bar of design chord c (from its first node to its second)
// in a wind of velocity V: q L with q as wire_drag's (the bar's diameter and
// drag coefficient, bar_diameter, bar_drag_coefficient) and L = |c| [N].
Eigen::Vector3d bar_drag(const BarElement& bar, const Eigen::Vector3d& chord,
                         const Eigen::Vector3d& velocity, double air_density);

// Sets every cable element's wind_load from mesh.conditions.wind (zero
// without wind); the element's tangent is its design chord. Every bar with
// a diameter (droppers, stitch bars by default) carries its drag (bar_drag)
// as two node forces labelled kBarWindLabel, half on each end; the call
// replaces those of an earlier one.
inline constexpr const char* kBarWindLabel = "bar_wind";
void set_wind_loads(CatenaryMesh& mesh);

// The contact wires' lateral position relative to the track's centre line
// at every support and mid-span (mesh.support_x; a design without supports:
// the contact wires' laterally held nodes), under 'now' and 'bare' node
// values; permissible from mesh.conditions.wind.
BlowOff measure_blow_off(const CatenaryMesh& mesh, const std::vector<double>& bare,
                         const std::vector<double>& now);

// The turbulence field's stations (docs/conditions.md, "Turbulence"): x0 +
// i grid_spacing, i < count, over the design x of the cable nodes.
struct TurbulenceGrid {
  double x0 = 0, spacing = 1;
  int count = 0;
};
TurbulenceGrid turbulence_grid(const CatenaryMesh& mesh);

// The modal level's turbulence rows (assembly/modal_wind.hpp): the
// generalised forces of a unit u' (component 0) or w' (component 1) at one
// station, kept as rows of the basis under keys beyond every node's
// (basis_row_key of a node index >= mesh.nodes.size()). Empty without
// turbulence.
std::vector<long> turbulence_row_keys(const CatenaryMesh& mesh);
inline long turbulence_row_key(const CatenaryMesh& mesh, const TurbulenceGrid& grid, int component,
                               int station) {
  return 6L * static_cast<long>(mesh.nodes.size()) + component * grid.count + station;
}
inline bool is_turbulence_row_key(const CatenaryMesh& mesh, long key) {
  return key >= 6L * static_cast<long>(mesh.nodes.size());
}

}  // namespace pcsim::catenary
