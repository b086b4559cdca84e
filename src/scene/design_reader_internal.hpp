// Helpers shared by the design-file readers (design_reader*.cpp).
#pragma once

#include <string>

#include "pcsim/scene/design_reader.hpp"

namespace pcsim::scene::reader {

using namespace pcsim::catenary;

// File name without folder and extension (the default design name).
std::string file_stem(const std::string& path);

// 'gravity': a magnitude g >= 0 (vector (0, 0, -g)) or a vector; default g = 9.81.
Eigen::Vector3d read_gravity(const InputNode& root);

// 'damping': {rayleigh_alpha, rayleigh_beta}, both default 0.
RayleighDamping read_damping(const InputNode& root);

// Slack criterion 'key' of n (none, length, force), 'fallback' when absent.
SlackCriterion read_slack(const InputNode& n, const char* fallback);

// Parametric keys of real lines (design_reader_lines.cpp): 'presag' (a
// number or {profile, sag}), 'droppers.spans', 'sections', 'overlap',
// 'tensioning', 'steady_arms', 'messenger_supports', 'support_overrides',
// 'irregularities' (the profile file is read here, relative to the design).
void read_presag(const InputNode& root, ParametricDesign& d);
std::vector<SpanDroppers> read_span_droppers(const InputNode& list);
void read_line(const InputNode& root, ParametricDesign& d);
void read_supports(const InputNode& root, ParametricDesign& d);
void read_irregularities(const InputNode& root, ParametricDesign& d);

}  // namespace pcsim::scene::reader
