// A run scene's 'assessment' section and the default choice of criteria set
// (pcsim/scene/criteria_reader.hpp, docs/assessment.md).
#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "pcsim/core/format.hpp"
#include "pcsim/scene/criteria_reader.hpp"

namespace pcsim::scene {

const std::map<std::string, std::string>& builtin_input_files();

namespace {

const char* const kReferenceDesign = "meshes/en50318-reference.yaml";
const char* const kReferenceModel = "meshes/pantographs/en50318_two_mass.yaml";
constexpr Limit kUpliftSpace{1e4, "mm"};  // the space for steady arm uplift

bool scalars_equal(const YAML::Node& a, const YAML::Node& b) {
  const std::string x = a.Scalar(), y = b.Scalar();
  if (x == y) return true;
  try {  // 1.0e5 and 100000 are the same number
    std::size_t nx = 0, ny = 0;
    const double dx = std::stod(x, &nx), dy = std::stod(y, &ny);
    return nx == x.size() && ny == y.size() && dx == dy;
  } catch (const std::exception&) {
    return false;
  }
}

// Whether two trees hold the same values, but for the key paths in 'ignored'.
bool same_tree(const YAML::Node& a, const YAML::Node& b, const std::string& path,
               const std::set<std::string>& ignored) {
  if (a.Type() != b.Type()) return false;
  if (a.IsScalar()) return scalars_equal(a, b);
  if (a.IsSequence()) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i)
      if (!same_tree(a[i], b[i], path + "[]", ignored)) return false;
    return true;
  }
  if (!a.IsMap()) return true;
  std::set<std::string> keys;
  for (const auto& kv : a) keys.insert(kv.first.Scalar());
  for (const auto& kv : b) keys.insert(kv.first.Scalar());
  for (const auto& key : keys) {
    const std::string child = path.empty() ? key : path + "." + key;
    if (ignored.count(child)) continue;
    if (!a[key] || !b[key] || !same_tree(a[key], b[key], child, ignored)) return false;
  }
  return true;
}

YAML::Node builtin_tree(const char* file) {
  return YAML::Load(builtin_input_files().at(file));
}

std::string choose_default(const InputNode& scene, const RunScene& run,
                           const std::string& electrification, std::string& choice) {
  if (electrification != "AC") {
    choice = "default: a " + electrification + " line";
    return "en50367-dc";
  }
  const std::string mismatch = en50318_reference_mismatch(scene, run);
  if (mismatch.empty()) {
    choice = "default: the EN 50318 reference case";
    return "en50318-2002";
  }
  choice = "default: not the EN 50318 reference case (" + mismatch + ")";
  return "en50367-ac";
}

// The set named by assessment.criteria: a built-in name or a file path.
CriteriaSet named_set(const InputNode& a, const CriteriaContext& context) {
  const std::string value = a.get_string("criteria");
  const auto names = builtin_criteria_sets();
  for (const auto& n : names)
    if (n == value) return builtin_criteria_set(n, context);
  const bool path = value.find('/') != std::string::npos ||
                    value.find(".yaml") != std::string::npos ||
                    value.find(".json") != std::string::npos;
  if (!path) {
    std::string list;
    for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
    a.fail_key("criteria", "no built-in criteria set '" + value + "' (built in: " + list +
                               "; or give a file path)");
  }
  return read_criteria_set(InputNode::load_file(a.get_file_path("criteria")), context);
}

}  // namespace

std::string en50318_reference_mismatch(const InputNode& scene, const RunScene& run) {
  if (run.pantographs.size() != 1)
    return std::to_string(run.pantographs.size()) + " pantographs; the reference case has one";
  const InputNode p = scene["pantographs"].at(0);
  if (!same_tree(p.load_referenced("model").raw(), builtin_tree(kReferenceModel), "",
                 {"name", "source"}))
    return "the pantograph model is not the reference two-mass model";
  if (p.has("effects")) return "the pantograph has effects";
  if (std::abs(run.pantographs[0].static_force - 120.0) > 1e-9)
    return "static force " + format_number(run.pantographs[0].static_force) + " N, not 120 N";
  if (!same_tree(scene["catenary"].load_referenced("design").raw(), builtin_tree(kReferenceDesign),
                 "", {"name", "spans.count", "element_length"}))
    return "the design is not the reference catenary";
  if (run.catenary.mesh.conditions.any()) return "the line is under conditions (conditions)";
  const CriteriaContext context{run.speed * 3.6, run.speed * 3.6, "AC"};
  const CriteriaSet en50318 = builtin_criteria_set("en50318-2002", context);
  for (const auto& k : en50318.criteria)
    if (k.upper.kind != CriterionBound::Kind::none) return "";
  return "EN 50318 gives no ranges at " + format_number(run.speed * 3.6) + " km/h";
}

void read_assessment(const InputNode& scene, RunScene& run) {
  Assessment& a = run.assessment;
  a.line_speed_kmh = run.speed * 3.6;
  a.electrification = "AC";
  const bool given = scene.has("assessment");
  const InputNode section = given ? scene["assessment"] : scene;
  if (given) {
    section.allow_only({"criteria", "electrification", "line_speed_kmh", "steady_arm_space_mm"});
    a.electrification = section.get_choice("electrification", {"AC", "DC3kV", "DC1.5kV"}, "AC");
    a.line_speed_kmh = section.get_positive("line_speed_kmh", limits::speed_kmh, a.line_speed_kmh);
    a.steady_arm_space_mm = section.get_positive("steady_arm_space_mm", kUpliftSpace, 0.0);
  }
  const CriteriaContext context{run.speed * 3.6, a.line_speed_kmh, a.electrification};
  if (given && section.has("criteria")) {
    a.set = named_set(section, context);
    a.choice = "scene";
  } else {
    a.set = builtin_criteria_set(choose_default(scene, run, a.electrification, a.choice), context);
  }
  // A set written for some systems only (en50367-dc: DC3kV, DC1.5kV).
  const auto& systems = a.set.electrification;
  if (!systems.empty() &&
      std::find(systems.begin(), systems.end(), a.electrification) == systems.end()) {
    std::string list;
    for (const auto& e : systems) list += (list.empty() ? "" : " or ") + e;
    throw InputError(given ? section.file() : scene.file(), "assessment.electrification",
                     "criteria set '" + a.set.name + "' is for " + list +
                         " lines, the scene's is " + a.electrification +
                         (given && section.has("electrification") ? "" : " (the default)"));
  }
}

}  // namespace pcsim::scene
