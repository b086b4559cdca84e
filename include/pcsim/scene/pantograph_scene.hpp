// Scenes of `pcsim pantograph` (studies of the pantograph alone, thesis chapter 2):
//   name: ...
//   pantograph: {model: <model file relative to the scene>, effects: {...},
//                base_motion: {...} (lumped models; scene/time_signal.hpp)}
//   speed_kmh: 0                               # for the aerodynamic force only
//   equilibrium: {contact_force: 120, working_height: 1.2}
//   study: {type: time|modes|frf|sweep|calibrate, ...}
// Study keys:
//   time: schemes [rk4|hht], dt, t_end, hht_alpha, record_every, linear, force:
//         {type: constant, value} | {type: harmonic, mean, amplitude, frequency_hz} |
//         {type: file, file: <t, F rows; linear interpolation, held outside>}
//   modes: none
//   frf: f_min_hz, f_max_hz, points (log-spaced)
//   sweep: f_min_hz, f_max_hz, points, amplitudes, dt, settle_s, settle_periods,
//          measure_periods, linear, start_on_linear_steady_state
//   calibrate (DSA-380 only): start {kr, kl, l10, I7}
// Forces are the downward contact force [N].
#pragma once

#include "pcsim/pantograph/study.hpp"
#include "pcsim/scene/yaml_input.hpp"

namespace pcsim::scene {

pantograph::StudyScene load_pantograph_study_scene(const InputNode& scene);

// Downward contact force history of a `force` node (see above).
pantograph::ForceHistory load_force_history(const InputNode& force);

}  // namespace pcsim::scene
