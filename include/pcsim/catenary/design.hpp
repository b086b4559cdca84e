// Catenary designs: YAML files under meshes/ that describe a catenary, and
// the generator that turns one into a CatenaryMesh (mesh.hpp).
//
// Two kinds of design (docs/design-format.md lists every key):
//  - type: parametric — a straight-track simple catenary (spans, wires,
//    droppers, stagger, pre-sag, steady arms, optional stitch wires);
//  - type: explicit — arbitrary nodes, cable wires, bars, supports, masses,
//    springs and form-finding targets, for small verification structures.
//
// Every input problem throws pcsim::InputError naming the file, the key path
// and the reason.
#pragma once

#include <string>

#include "pcsim/catenary/mesh.hpp"
#include "pcsim/scene/yaml_input.hpp"

namespace pcsim::catenary {

// Loads and builds the design in 'path'; mesh.source_file = path.
CatenaryMesh load_catenary_design(const std::string& path);

// Builds a design from an already-parsed YAML root (key 'type' selects the kind).
CatenaryMesh build_catenary_design(const pcsim::InputNode& root);

// Internal consistency of a mesh (indices in range, element lengths positive,
// targets pointing at form-finding bars, ...). Returns an empty string when
// the mesh is consistent, otherwise a description of the first problem.
// Used by the tests and as a guard by code that builds meshes by hand.
std::string mesh_consistency_error(const CatenaryMesh& mesh);

}  // namespace pcsim::catenary
