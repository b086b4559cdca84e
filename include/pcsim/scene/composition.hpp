// Composition of YAML input files (docs/scene-format.md, "Composition"):
//
//   base: ../en50318-300.yaml      # a file this one builds on (relative to this file)
//   name: en50318-250
//   simulation: {speed_kmh: 250}   # maps merge key by key; this file's keys win
//   set:                           # keys by path, applied after the merge
//     pantographs[0].static_force: 100
//     catenary.design.spans.count: 20   # through a file reference: a key of the design
//
// then the command line's `--set KEY=VALUE` overrides, in order. Maps merge
// recursively; lists and scalars are replaced whole. A key path that passes
// through a value naming a file (catenary.design, pantographs[N].model, ...)
// continues inside that file: the override is applied when the reader loads
// it (InputNode::load_referenced). Every value keeps its origin, so that
// errors name the file or the override that gave it.
#pragma once

#include <string>
#include <vector>

#include "pcsim/scene/yaml_input.hpp"

namespace pcsim::scene {

// "KEY=VALUE": KEY a key path (list entries as [N] or .N), VALUE YAML (a
// number, true/false, a string, [a, b], {k: v}). InputError(origin.label,
// "--set", reason) on bad syntax.
InputOverride parse_override(const std::string& assignment, const InputOrigin& origin);

// Loads 'path' with its base files and 'set' entries, then applies the
// overrides in order. InputError on a missing file, a circular base chain, a
// key path that does not fit the tree, or malformed YAML.
InputNode load_composed(const std::string& path, const std::vector<InputOverride>& overrides = {});
// The same for YAML text that stands for the file 'file' (tests, docs).
InputNode load_composed_text(const std::string& text, const std::string& file,
                             const std::vector<InputOverride>& overrides = {});

// The composed tree as YAML text (provenance).
std::string to_yaml(const InputNode& node);

}  // namespace pcsim::scene
