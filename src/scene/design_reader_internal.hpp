// Helpers shared by the design-file readers (design_reader*.cpp).
#pragma once

#include <string>

#include "pcsim/scene/design_reader.hpp"

namespace pcsim::catenary::reader {

// File name without folder and extension (the default design name).
std::string file_stem(const std::string& path);

// 'gravity': a magnitude g >= 0 (vector (0, 0, -g)) or a vector; default g = 9.81.
Eigen::Vector3d read_gravity(const InputNode& root);

// 'damping': {rayleigh_alpha, rayleigh_beta}, both default 0.
RayleighDamping read_damping(const InputNode& root);

// Slack criterion 'key' of n (none, length, force), 'fallback' when absent.
SlackCriterion read_slack(const InputNode& n, const char* fallback);

}  // namespace pcsim::catenary::reader
