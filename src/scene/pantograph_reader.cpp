// The registry of pantograph model kinds and the lumped-mass reader.
#include "pcsim/scene/pantograph_reader.hpp"

#include <sstream>

#include "pcsim/core/format.hpp"
#include "pcsim/scene/composition.hpp"
#include "pcsim/scene/flexible_dsa380_reader.hpp"
#include "pcsim/scene/time_signal.hpp"

namespace pcsim::scene {

namespace {

std::unique_ptr<pantograph::PantographModel> read_lumped(const InputNode& model,
                                                         const InputNode* effects,
                                                         double speed_m_s) {
  bool aerodynamic = false;
  if (effects) {
    effects->allow_only({"aerodynamic"});
    aerodynamic = effects->get_bool("aerodynamic", false);
  }
  return std::make_unique<pantograph::LumpedPantograph>(load_lumped_parameters(model), aerodynamic,
                                                        speed_m_s);
}

std::unique_ptr<pantograph::PantographModel> read_dsa380(const InputNode& model,
                                                         const InputNode* effects,
                                                         double speed_m_s) {
  const pantograph::Dsa380Effects e =
      effects ? load_dsa380_effects(*effects) : pantograph::Dsa380Effects{};
  return std::make_unique<pantograph::Dsa380Pantograph>(load_dsa380_parameters(model), e,
                                                        speed_m_s);
}

// The flexible-bar DSA-380 (thesis 2.2): the rigid model's effects apply.
std::unique_ptr<pantograph::PantographModel> read_dsa380_flexible(const InputNode& model,
                                                                  const InputNode* effects,
                                                                  double speed_m_s) {
  const pantograph::Dsa380Effects e =
      effects ? load_dsa380_effects(*effects) : pantograph::Dsa380Effects{};
  return std::make_unique<pantograph::FlexibleDsa380Pantograph>(read_flexible_dsa380(model), e,
                                                                speed_m_s);
}

std::map<std::string, PantographKindReader>& registry() {
  static std::map<std::string, PantographKindReader> kinds = {
      {"lumped", read_lumped}, {"dsa380", read_dsa380}, {"dsa380_flexible", read_dsa380_flexible}};
  return kinds;
}

}  // namespace

const std::map<std::string, PantographKindReader>& pantograph_kinds() {
  return registry();
}

void register_pantograph_kind(const std::string& kind, PantographKindReader reader) {
  registry()[kind] = std::move(reader);
}

std::unique_ptr<pantograph::PantographModel> load_pantograph_model(const std::string& model_path,
                                                                   const InputNode* effects,
                                                                   double speed_m_s) {
  return load_pantograph_model(load_composed(model_path), effects, speed_m_s);
}

std::unique_ptr<pantograph::PantographModel> load_pantograph_model(const InputNode& model,
                                                                   const InputNode* effects,
                                                                   double speed_m_s) {
  const std::string kind = model.get_string("kind");
  const auto& kinds = pantograph_kinds();
  const auto reader = kinds.find(kind);
  if (reader == kinds.end()) {
    std::string list;
    for (const auto& k : kinds) list += (list.empty() ? "" : ", ") + k.first;
    model.fail_key("kind", "must be one of " + list + " (got '" + kind + "')");
  }
  try {
    return reader->second(model, effects, speed_m_s);
  } catch (const InputError& e) {
    model.rethrow_with_origin(e);
  }
}

std::unique_ptr<pantograph::PantographModel> load_pantograph(const InputNode& entry,
                                                             double speed_m_s) {
  entry.allow_only({"model", "effects", "base_motion"});
  const auto model = entry.load_referenced("model");
  std::unique_ptr<pantograph::PantographModel> loaded;
  if (entry.has("effects")) {
    const auto effects = entry["effects"];
    loaded = load_pantograph_model(model, &effects, speed_m_s);
  } else {
    loaded = load_pantograph_model(model, nullptr, speed_m_s);
  }
  apply_base_motion(entry, *loaded);
  return loaded;
}

pantograph::LumpedParameters load_lumped_parameters(const InputNode& model) {
  model.allow_only({"kind", "name", "source", "stages", "uplift", "gravity", "aerodynamic"});
  pantograph::LumpedParameters p;
  p.name = model.get_string("name", "lumped");
  const auto stages = model["stages"];
  if (!stages.is_sequence() || stages.size() == 0) stages.fail("must be a non-empty list");
  for (std::size_t i = 0; i < stages.size(); ++i) {
    const auto s = stages.at(i);
    s.allow_only({"name", "mass", "stiffness", "damping"});
    pantograph::LumpedStage st;
    st.name = s.get_string("name", "stage" + std::to_string(i));
    st.mass = s.get_positive("mass", limits::mass);
    st.stiffness = s.get_nonnegative("stiffness", limits::stiffness);
    st.damping = s.get_nonnegative("damping", limits::damping, 0.0);
    p.stages.push_back(st);
  }
  if (model.has("uplift")) {
    const auto u = model["uplift"];
    u.allow_only({"force", "stage"});
    p.uplift_force = u.get_real("force", limits::force);
    const std::string stage = u.get_string("stage", p.stages.back().name);
    p.uplift_stage = -1;
    for (std::size_t i = 0; i < p.stages.size(); ++i)
      if (p.stages[i].name == stage) p.uplift_stage = static_cast<int>(i);
    if (p.uplift_stage < 0) u.fail_key("stage", "no stage named '" + stage + "'");
  }
  p.gravity = model.get_bool("gravity", false);
  if (model.has("aerodynamic")) {
    const auto a = model["aerodynamic"];
    a.allow_only({"a", "b", "c"});
    p.aero_a = a.get_real("a", limits::coefficient, 0.0);
    p.aero_b = a.get_real("b", limits::coefficient, 0.0);
    p.aero_c = a.get_real("c", limits::coefficient, 0.0);
  }
  return p;
}

void check_working_height(const InputNode& entry, pantograph::PantographModel& model,
                          double contact_force, double working_height, bool height_given) {
  const std::string note = height_given ? ""
                                        : " (working_height not given: the model's default " +
                                              format_number(working_height) + " m)";
  try {
    model.static_equilibrium(contact_force, working_height);
  } catch (const InputError& e) {
    if (!e.file().empty()) throw;
    entry.fail_key("working_height", e.reason() + note);
  } catch (const SolverError& e) {
    entry.fail_key("working_height", "the pantograph has no static equilibrium at working height " +
                                         format_number(working_height) + " m under " +
                                         format_number(contact_force) + " N: " + e.what() + note);
  }
}

}  // namespace pcsim::scene
