// Criteria sets and a run scene's 'assessment' section (docs/assessment.md).
//
//   assessment:
//     criteria: en50367-ac      # a built-in set (meshes/criteria/<name>.yaml) or a file path
//     electrification: AC       # AC | DC3kV | DC1.5kV (chooses EN 50367's curve)
//     line_speed_kmh: 320       # the line's speed (chooses rows by speed; default: the run's)
//     steady_arm_space_mm: 240  # the space for steady arm uplift (optional)
//
// Without 'criteria' the set is chosen by a written rule: en50318-2002 for
// the EN 50318 reference case (en50318_reference_mismatch), else en50367-dc
// for a DC electrification, else en50367-ac. Every error is an InputError
// naming the file (the scene's or the set's) and the key.
#pragma once

#include <string>
#include <vector>

#include "pcsim/core/criteria.hpp"
#include "pcsim/scene/run_scene.hpp"
#include "pcsim/scene/yaml_input.hpp"

namespace pcsim::scene {

// The built-in sets ("en50318-2002", "en50367-ac", "en50367-dc").
std::vector<std::string> builtin_criteria_sets();

// What a set's rows are chosen by.
struct CriteriaContext {
  double speed_kmh = 0;       // the run's
  double line_speed_kmh = 0;  // the line's ('when: {line_speed_kmh: ...}')
  std::string electrification = "AC";
};

// Reads a criteria set file (its root node); 'ranges' files are read from
// the set file's folder.
CriteriaSet read_criteria_set(const InputNode& root, const CriteriaContext& context);
// The built-in set 'name' (embedded at build time from meshes/criteria/).
CriteriaSet builtin_criteria_set(const std::string& name, const CriteriaContext& context);

// Why the run is not the EN 50318 reference case, "" if it is: one
// pantograph whose model file has the content of
// meshes/pantographs/en50318_two_mass.yaml (but for name and source), no
// pantograph effects, static force 120 N; a design with the content of
// meshes/en50318-reference.yaml but for its name, spans.count and
// element_length; a speed within 0.5 km/h of one with EN 50318 ranges.
std::string en50318_reference_mismatch(const InputNode& scene, const RunScene& run);

// Reads the scene's 'assessment' section (or applies the default rule) into run.assessment.
void read_assessment(const InputNode& scene, RunScene& run);

}  // namespace pcsim::scene
