// Pantograph model files (meshes/pantographs/*.yaml) and the per-scene effects.
//
// A model file states its model with `kind`; the registry maps each kind to the reader
// that reads the file together with the scene's effects and builds the model. Bad input
// gives InputError(file, key, reason). A scene's pantograph entry is
//   {model: <model file, relative to the scene>, effects: {...}}
// Effects (all optional): aerodynamic: bool; DSA-380 only: head_restraint:
// none|rotation|horizontal, friction: {force, kt}, damper: {enabled, one_way, quadratic}.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <string>

#include "pcsim/pantograph/dsa380.hpp"
#include "pcsim/pantograph/lumped.hpp"
#include "pcsim/pantograph/model.hpp"
#include "pcsim/scene/yaml_input.hpp"

namespace pcsim::scene {

// Reads a model file of one kind and the scene's effects (nullptr: none given).
using PantographKindReader = std::function<std::unique_ptr<pantograph::PantographModel>(
    const InputNode& model_file, const InputNode* effects, double speed_m_s)>;

// Model file `kind` -> reader; holds "lumped" and "dsa380".
const std::map<std::string, PantographKindReader>& pantograph_kinds();
// Adds a kind to the registry (or replaces its reader).
void register_pantograph_kind(const std::string& kind, PantographKindReader reader);

// Builds the model of a model file through the registry.
std::unique_ptr<pantograph::PantographModel> load_pantograph_model(const std::string& model_path,
                                                                   const InputNode* effects,
                                                                   double speed_m_s);
// Builds the model of a loaded model file (InputNode::load_referenced).
std::unique_ptr<pantograph::PantographModel> load_pantograph_model(const InputNode& model_file,
                                                                   const InputNode* effects,
                                                                   double speed_m_s);
// Builds the model of a scene's pantograph entry {model, effects}.
std::unique_ptr<pantograph::PantographModel> load_pantograph(const InputNode& entry,
                                                             double speed_m_s);

// Solves the model's static equilibrium at its working height; impossible
// geometry is an InputError naming entry's 'working_height' (the angle, the
// height, the reachable range), with a note when the height is the default.
void check_working_height(const InputNode& entry, pantograph::PantographModel& model,
                          double contact_force, double working_height, bool height_given);

// The readers of the registered kinds, by parts.
pantograph::LumpedParameters load_lumped_parameters(const InputNode& model);
pantograph::Dsa380Parameters load_dsa380_parameters(const InputNode& model);
pantograph::Dsa380Effects load_dsa380_effects(const InputNode& effects);

}  // namespace pcsim::scene
