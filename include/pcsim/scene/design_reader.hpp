// Catenary design files (meshes/*.yaml, docs/design-format.md) -> the plain
// parameter structs of pcsim/catenary/geometry.hpp -> CatenaryMesh.
//
// The reader checks the syntax (unknown keys, types, list shapes, enumerated
// choices); the builders of geometry.hpp check ranges and geometry. Every
// problem throws pcsim::InputError naming the file, the key path and the
// reason.
#pragma once

#include <functional>
#include <string>

#include "pcsim/catenary/geometry.hpp"
#include "pcsim/catenary/mesh.hpp"
#include "pcsim/scene/yaml_input.hpp"

namespace pcsim::scene {

// Called with the size of a design's mesh after the design's checks and before
// the mesh is built; throws (InputError naming size.file and size.key) to refuse it.
using MeshSizeCheck = std::function<void(const catenary::MeshSize&)>;

// Loads and builds the design in 'path'; mesh.source_file = path.
catenary::CatenaryMesh load_catenary_design(const std::string& path, const MeshSizeCheck& check = {});

// Builds a design from an already-parsed YAML root (key 'type' selects the kind).
catenary::CatenaryMesh build_catenary_design(const InputNode& root, const MeshSizeCheck& check = {});

// The parameters of a design root of type parametric / explicit (the key
// 'type' is accepted, not checked); range checks are left to the builders.
catenary::ParametricDesign read_parametric_design(const InputNode& root);
catenary::ExplicitDesign read_explicit_design(const InputNode& root);

}  // namespace pcsim::scene
