// Prescribed time histories read from scenes: a file of "t, value" rows (the pantograph
// studies' force, a vehicle's roof motion) and the base motion of a pantograph (issue 25):
//   base_motion: {type: harmonic, amplitude: A, frequency_hz: f}   z_b = A sin(2π f t)
//   base_motion: {type: file, file: <t, z_b rows>}                 piecewise linear
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

// The base motion of a `base_motion` node (see above); the file's z_b is continuous and
// piecewise linear, its velocity v_b the slope (constant between samples, 0 outside), and
// it has no acceleration (empty); harmonic and psd give the exact a_b.
pantograph::BaseMotion load_base_motion(const InputNode& node);

// If the pantograph entry has the key `base_motion`, gives it to the model; fails naming
// the key for a model that takes none, and `type` for a file given to a moving-frame model
// (DSA-380: needs a_b).
void apply_base_motion(const InputNode& entry, pantograph::PantographModel& model);

}  // namespace pcsim::scene
