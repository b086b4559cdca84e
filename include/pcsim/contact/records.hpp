// What a dynamic run measures at every accepted time step (plain data; the
// coupled system fills it, the output writers store it).
#pragma once

#include <vector>

namespace pcsim::contact {

struct StepRecord {
  double t = 0;
  // Per pantograph: the force on the head (the sum over the contact wires),
  // the contact point's station, the height of the wire it touches (the one
  // pressed hardest, else the lowest one at x).
  std::vector<double> contact_force, contact_x, wire_z;
  std::vector<double> head_z;  // per pantograph: height of the head's contact point [m]
  std::vector<double> wire_y;  // per pantograph: that wire's lateral position at x [m]
  std::vector<std::vector<double>> wire_force;  // per pantograph: force on each contact wire
  std::vector<std::vector<double>> q;           // per pantograph: generalised coordinates
  std::vector<double> support_z;                // contact-wire height at every support
  std::vector<double> dropper_force;            // every dropper (empty if not kept)
};

}  // namespace pcsim::contact
