// Forces at the supports of a static configuration, and what is derived from
// them: the pull-off forces of the steady arms and the release of the
// tensioning devices (mesh.hpp). Plain functions of the mesh and its node
// values (6 per node), the same on every rank.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "pcsim/catenary/mesh.hpp"

namespace pcsim::catenary {

// Stiffness of the horizontal guide that keeps a released tensioning device
// on its line of pull on curved track (a penalty: 1e9 N/m against a few kN
// gives micrometres) [N/m].
constexpr double kGuideStiffness = 1e9;

// Force the supports exert on each of 'nodes' (at its position DOFs) for the
// configuration to be in equilibrium there: the residual, internal minus
// external forces, of the cable elements, bars, point masses and node forces
// attached to the node. Springs are supports and not included, nor, when
// without_steady_arms, bars of kind steady_arm.
std::vector<Eigen::Vector3d> support_forces(const CatenaryMesh& mesh,
                                            const std::vector<double>& node_values,
                                            const std::vector<int>& nodes,
                                            bool without_steady_arms = false);

// Lateral force of every registration on its wire (mesh.registrations), along
// its 'lateral' direction [N]: the pull-off force of the steady arm.
std::vector<double> registration_forces(const CatenaryMesh& mesh,
                                        const std::vector<double>& node_values);

// Frees the wire end of every tensioning device not yet released along its
// horizontal line of pull (x on straight track; x and y with a guide spring
// across the line on curved track) and applies the force the anchor held it
// with as a NodeForce, plus the weight's mass or the device's spring. The
// configuration 'node_values' stays an equilibrium.
void release_tensioning_devices(CatenaryMesh& mesh, const std::vector<double>& node_values);

}  // namespace pcsim::catenary
