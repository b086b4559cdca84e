// Small catenary meshes built in code for solver tests.
#pragma once

#include <cmath>

#include "pcsim/catenary/mesh.hpp"

namespace pcsim::fixtures {

// One straight or parabolic wire along x from 0 to span, n elements, end
// positions fixed (pinned), slopes free. Design shape z = -4 sag x (span - x) / span^2.
inline catenary::CatenaryMesh single_wire(double span, int n, double mass_per_length, double EA,
                                          double EI, double tension, double sag,
                                          double unstressed_ratio) {
  catenary::CatenaryMesh mesh;
  mesh.name = "single-wire";
  catenary::Wire w;
  w.name = "wire";
  w.kind = catenary::WireKind::contact;
  w.mass_per_length = mass_per_length;
  w.EA = EA;
  w.EI = EI;
  w.tension = tension;
  for (int i = 0; i <= n; ++i) {
    const double x = span * i / n;
    catenary::Node node;
    node.position = {x, 0.0, -4 * sag * x * (span - x) / (span * span)};
    const double dzdx = -4 * sag * (span - 2 * x) / (span * span);
    node.slope = Eigen::Vector3d(1.0, 0.0, dzdx).normalized();
    if (i == 0 || i == n) node.fixed[0] = node.fixed[1] = node.fixed[2] = true;
    mesh.nodes.push_back(node);
    w.nodes.push_back(i);
  }
  for (int e = 0; e < n; ++e) {
    catenary::CableElement el;
    el.nodes = {e, e + 1};
    el.wire = 0;
    el.ref_length = (mesh.nodes[e + 1].position - mesh.nodes[e].position).norm();
    el.unstressed_length = el.ref_length * unstressed_ratio;
    mesh.cables.push_back(el);
    w.elements.push_back(e);
  }
  mesh.wires.push_back(w);
  mesh.contact_wire = 0;
  return mesh;
}

}  // namespace pcsim::fixtures
