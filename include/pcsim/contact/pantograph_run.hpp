// How a pantograph travels along the line and starts, and which effects of the
// interaction a run switches on (the scene's `pantographs:` and `effects:`).
// Plain data: the scene readers fill it, the coupled system uses it.
#pragma once

#include <algorithm>
#include <string>

namespace pcsim::contact {

struct InteractionEffects {
  // (The catenary's fidelity is the scene's catenary.model, held by the model.)
  bool dropper_slack = true;     // the bars' slack criteria; else linear bars
  bool rayleigh_damping = true;  // C = alpha M + beta K_static (thesis eq. 3.1)
};

struct PantographRun {
  std::string name;
  double start_x = 0;         // contact point x at t = 0 [m]
  double speed = 0;           // [m/s]
  double static_force = 0;    // F0: static contact force [N]
  bool static_start = false;  // start in static equilibrium in contact
  double ramp_distance = 0;   // ramp-up: head force weighted 0 -> 1 over this distance [m]
  // > 0: start at rest this far below the wire with the full uplift, no contact
  // force (not an equilibrium: the head rises and lands on the wire) [m].
  double start_gap = 0;
  // Height of the contact point above the pantograph's base at the start [m];
  // <= 0: the model takes absolute heights (lumped models).
  double working_height = 0;
  // The mean cross-wind's force on the pantograph (scene 'cross_wind',
  // docs/conditions.md "Wind on the pantograph"): F_y = rho CdA V_y |V_y| / 2
  // from the wind's component across the track, and the head's quasi-static
  // lateral deflection F_y / k_y [N, m]. The models have no lateral motion:
  // it moves the head under the wire, not the contact force.
  bool cross_wind = false;
  double cross_wind_force = 0, head_lateral_offset = 0;

  double contact_x(double t) const { return start_x + speed * t; }
  // Weight of the pantograph's own uplift during the ramp (thesis 3.3.1); 1 after it.
  double ramp_factor(double t) const {
    if (!ramps()) return 1.0;
    return std::clamp(speed * t / ramp_distance, 0.0, 1.0);
  }
  // d ramp_factor / dt [1/s] (0 where it is constant: no ramp, or after it).
  double ramp_rate(double t) const {
    return ramps() && speed * t < ramp_distance ? speed / ramp_distance : 0.0;
  }
  // A ramp start (not static, no gap, a ramp distance).
  bool ramps() const { return !static_start && start_gap <= 0 && ramp_distance > 0; }
};

}  // namespace pcsim::contact
