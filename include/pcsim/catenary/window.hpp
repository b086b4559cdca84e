// A moving window over a line of identical spans (docs/scaling.md, "Moving
// window"): only W spans are integrated (around the pantograph, or the whole
// train of pantographs); when the (leading) pantograph has run on by one
// period of the line (two spans: the stagger alternates), the dynamic state
// moves back by that period and the new front spans start static.
// Plain functions of the mesh; the run drives them (src/simulation/moving_window.*).
#pragma once

#include <vector>

#include "pcsim/catenary/mesh.hpp"

namespace pcsim::catenary {

// Wave impedance of a tensioned wire, sqrt(T rho_T) = T / c [N s/m]: a
// dashpot of this coefficient at a string's end absorbs every transverse
// wave (reflection coefficient (Z - c_d) / (Z + c_d) = 0).
// Stiffness of a pinned window end [N/m]: the dynamic forces there (~100 N)
// move it by ~0.1 um, and it is ~500 x the step matrix's M / (beta dt^2) at
// dt = 1 ms (an exact LU solves it).
constexpr double kPinStiffness = 1e9;

inline double wave_impedance(const Wire& wire) {
  return wire.tension / wave_speed(wire);
}

// The window's ends as the line continues beyond them: every wire end held
// vertically at the window's end supports but not at the line's inner
// supports (the contact wire at its steady arms; a messenger on fixed
// supports is held there in the line too and stays held) gets its vertical
// position freed, the force the anchor held it with as a NodeForce (so
// 'node_values' stays an equilibrium), and a vertical dashpot of
// impedance_factor x the wire's impedance, and an inactive pin (NodePin,
// kPinStiffness) that holds it where the window's end is the line's anchored
// end. Needs a parametric mesh of at least 3 supports. Returns the released
// nodes.
std::vector<int> release_window_ends(CatenaryMesh& mesh, const std::vector<double>& node_values,
                                     double impedance_factor = 1.0);

// For every node, the node whose design position lies 'shift' further along
// x (the same position to 1e-6 m), or -1 if there is none.
std::vector<int> shifted_nodes(const CatenaryMesh& mesh, double shift);

}  // namespace pcsim::catenary
