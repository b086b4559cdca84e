// Prescribed time histories read from scenes: a file of "t, value" rows (the pantograph
// studies' force, a vehicle's roof motion) and the base motion of a pantograph (issue 25):
//   base_motion: {type: harmonic, amplitude: A, frequency_hz: f}   z_b = A sin(2π f t)
//   base_motion: {type: file, file: <t, z_b rows>, interpolation: linear | cubic}
//                linear (lumped models' default) or a natural cubic spline (the
//                DSA-380 models' default and only choice: their moving frame needs a_b)
//   base_motion: {type: psd, frequency_hz: [..], psd: [.. m^2/Hz], seed: 1, components: 1024}
//                a seeded random motion with that one-sided PSD (sum of cosines)
#pragma once

#include <vector>

#include "pcsim/pantograph/model.hpp"
#include "pcsim/scene/yaml_input.hpp"

namespace pcsim::scene {

// Samples (t_k, y_k), t increasing, interpolated linearly and held constant outside.
struct Samples {
  std::vector<double> t, y;
  double value(double time) const;
  // Derivative of value(): y's slope on the interval holding `time`, 0 outside.
  double slope(double time) const;
};

// The rows "t, <what>" of the file named by `node`'s key "file" (commas or blanks, '#'
// comments); fails naming the key on a bad line, times that do not increase, no samples.
Samples load_samples(const InputNode& node, const std::string& what);

// The base motion of a `base_motion` node (see above). A file read linearly gives a
// continuous, piecewise-linear z_b, its velocity v_b the slope (constant between samples,
// 0 outside) and no acceleration (empty); read by the cubic spline, z_b, v_b and a_b of
// the spline (held at the end values with v_b = a_b = 0 outside the samples). Harmonic and
// psd give the exact a_b. `moving_frame`: for a model that needs a_b (DSA-380): a file's
// interpolation is then cubic by default, and linear fails naming the key.
pantograph::BaseMotion load_base_motion(const InputNode& node, bool moving_frame = false);

// If the pantograph entry has the key `base_motion`, gives it to the model; fails naming
// the key for a model that takes none.
void apply_base_motion(const InputNode& entry, pantograph::PantographModel& model);

}  // namespace pcsim::scene
