// Catenary designs given by their parameters (no design file), for the tests
// of the geometry builders and of what is built on them.
#pragma once

#include "pcsim/catenary/geometry.hpp"

namespace pcsim::design_fixtures {

// The parameters of meshes/en50318-reference.yaml on 'spans' spans of 60 m.
inline catenary::ParametricDesign reference_design(long spans) {
  catenary::ParametricDesign d;
  d.file = "reference-parameters";
  d.name = "en50318-reference";
  d.gravity = {0.0, 0.0, -9.81};
  d.damping = {0.0125, 1.0e-4};
  d.span_count = spans;
  d.span_length = 60.0;
  d.system_height = 1.2;
  d.contact_wire_height = 5.3;
  d.presag = 0.0;
  d.stagger = 0.2;
  d.element_length = 0.5;
  d.contact = {1.35, 1.44e7, 195.0, 20000.0};
  d.messenger = {1.07, 1.0e7, 131.7, 16000.0};
  d.droppers.positions = {5.0, 10.5, 17.0, 23.5, 30.0, 36.5, 43.0, 49.5, 55.0};
  d.droppers.stiffness = 1.0e5;
  d.droppers.slack = catenary::SlackCriterion::force;
  d.droppers.mass_per_length = 0.117;
  d.droppers.clamp_mass_messenger = 0.195;
  d.droppers.clamp_mass_contact = 0.165;
  d.steady_arms.mass = 1.0;
  return d;
}

// The parameters of meshes/taut-string.yaml: a 20 m string of 40 elements
// between two pinned nodes, no gravity, taut at 20 kN.
inline catenary::ExplicitDesign taut_string_design() {
  catenary::ExplicitDesign d;
  d.file = "taut-string-parameters";
  d.name = "taut-string";
  d.gravity = {0.0, 0.0, 0.0};
  d.nodes = {{0.0, 0.0, 0.0}, {20.0, 0.0, 0.0}};
  catenary::ExplicitWire w;
  w.name = "string";
  w.run = catenary::WireRun{catenary::NodeRef::at(0), catenary::NodeRef::at(1), 40};
  w.mass_per_length = 1.35;
  w.EA = 1.44e7;
  w.EI = 195.0;
  w.tension = 20000.0;
  d.wires.push_back(w);
  d.supports = {{catenary::NodeRef::at(0), {0, 1, 2}}, {catenary::NodeRef::at(1), {0, 1, 2}}};
  return d;
}

}  // namespace pcsim::design_fixtures
