// What a dynamic run measures at every accepted time step (plain data; the
// coupled system fills it, the output writers store it).
#pragma once

#include <vector>

namespace pcsim::contact {

struct StepRecord {
  double t = 0;
  std::vector<double> contact_force, contact_x, wire_z;  // per pantograph
  std::vector<std::vector<double>> q;                    // per pantograph: generalised coordinates
  std::vector<double> support_z;                         // contact-wire height at every support
  std::vector<double> dropper_force;                     // every dropper (empty if not kept)
};

}  // namespace pcsim::contact
