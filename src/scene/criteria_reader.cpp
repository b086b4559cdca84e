// Criteria set files (meshes/criteria/*.yaml or a user's file): each value
// read through InputNode, so that an error names the set's file and key.
#include "pcsim/scene/criteria_reader.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>

#include "pcsim/core/format.hpp"

namespace pcsim::scene {

// The embedded input files (generated at configure time from meshes/): path
// relative to the source tree -> text.
const std::map<std::string, std::string>& builtin_input_files();

namespace {

const char* const kBuiltinPrefix = "meshes/criteria/";
const char* const kBuiltinLabel = " (built in)";

std::string join(const std::vector<std::string>& items, const std::string& sep) {
  std::string s;
  for (std::size_t k = 0; k < items.size(); ++k) s += (k ? sep : "") + items[k];
  return s;
}

bool is_figure(const std::string& name) {
  const auto& f = criteria_figures();
  return std::find(f.begin(), f.end(), name) != f.end();
}

std::vector<std::string> strings_of(const InputNode& n) {
  std::vector<std::string> out;
  if (n.is_sequence())
    for (std::size_t i = 0; i < n.size(); ++i) out.push_back(n.at(i).as_string());
  else
    out.push_back(n.as_string());
  return out;
}

void check_electrification(const InputNode& n) {
  for (const auto& e : strings_of(n))
    if (e != "AC" && e != "DC3kV" && e != "DC1.5kV")
      n.fail("must be AC, DC3kV or DC1.5kV (or a list of them), got '" + e + "'");
}

// bound: {constant: X} | {speed_curve: [a, b]} | {factor: X, of: FIGURE}, and 'strict'.
CriterionBound read_bound(const InputNode& b) {
  b.allow_only({"constant", "speed_curve", "factor", "of", "strict"});
  CriterionBound bound;
  const int given = int(b.has("constant")) + int(b.has("speed_curve")) + int(b.has("factor"));
  if (given != 1) b.fail("give exactly one of constant, speed_curve or factor");
  if (b.has("constant")) {
    bound.kind = CriterionBound::Kind::constant;
    bound.a = b.get_double("constant");
  } else if (b.has("speed_curve")) {
    const auto c = b["speed_curve"].as_doubles();
    if (c.size() != 2) b.fail_key("speed_curve", "must be [a, b]: a v^2 + b, v in km/h");
    bound.kind = CriterionBound::Kind::speed_curve;
    bound.a = c[0];
    bound.b = c[1];
  } else {
    bound.kind = CriterionBound::Kind::factor;
    bound.a = b.get_double("factor");
    bound.of = b.get_string("of");
    if (!is_figure(bound.of) && bound.of != "steady_arm_space_mm")
      b.fail_key("of", "must be a figure (" + join(criteria_figures(), ", ") +
                           ") or steady_arm_space_mm, got '" + bound.of + "'");
  }
  if (b.has("factor") == false && b.has("of")) b.fail_key("of", "goes with factor only");
  bound.strict = b.get_bool("strict", false);
  return bound;
}

// Whether a criterion's 'when' holds for this run.
bool applies(const InputNode& c, const CriteriaContext& context) {
  if (!c.has("when")) return true;
  const InputNode w = c["when"];
  w.allow_only({"line_speed_kmh", "electrification"});
  bool ok = true;
  if (w.has("line_speed_kmh")) {
    const InputNode s = w["line_speed_kmh"];
    s.allow_only({"above", "at_most"});
    const double inf = std::numeric_limits<double>::infinity();
    ok = ok && context.line_speed_kmh > s.get_double("above", -inf) &&
         context.line_speed_kmh <= s.get_double("at_most", inf);
  }
  if (w.has("electrification")) {
    check_electrification(w["electrification"]);
    const auto list = strings_of(w["electrification"]);
    ok = ok && std::count(list.begin(), list.end(), context.electrification) > 0;
  }
  return ok;
}

Criterion read_criterion(const InputNode& c) {
  c.allow_only({"key", "figure", "label", "unit", "lower", "upper", "when", "clause", "source",
                "sourced", "note"});
  Criterion k;
  k.key = c.get_string("key");
  k.figure = c.get_string("figure");
  if (!is_figure(k.figure))
    c.fail_key("figure",
               "must be one of " + join(criteria_figures(), ", ") + ", got '" + k.figure + "'");
  k.label = c.get_string("label", k.figure);
  k.unit = c.get_string("unit", "");
  if (c.has("lower")) k.lower = read_bound(c["lower"]);
  if (c.has("upper")) k.upper = read_bound(c["upper"]);
  k.clause = c.get_string("clause");
  k.source = c.get_string("source");
  if (!c.has("sourced"))
    c.fail("needs 'sourced: true' (the value was checked against its source) or false");
  k.sourced = c.get_bool("sourced", false);
  k.note = c.get_string("note", "");
  return k;
}

// The ranges file of an EN 50318-style set: {edition, about, figures, ranges_by_speed_kmh}.
InputNode ranges_file(const InputNode& root, bool builtin) {
  if (!builtin) return InputNode::load_file(root.get_file_path("ranges"));
  const std::string path = root.get_string("ranges");
  if (path.rfind("../", 0) != 0) root.fail_key("ranges", "a built-in set names ../FILE");
  const std::string file = "meshes/" + path.substr(3);
  const auto it = builtin_input_files().find(file);
  if (it == builtin_input_files().end()) root.fail_key("ranges", "no built-in file " + file);
  return InputNode::load_string(it->second, file + kBuiltinLabel);
}

// An EN 50318-style set: one criterion per figure, bounded by the range at the run's speed.
void read_ranges(const InputNode& root, bool builtin, const CriteriaContext& context,
                 CriteriaSet& set) {
  const InputNode r = ranges_file(root, builtin);
  r.allow_only({"edition", "about", "figures", "ranges_by_speed_kmh"});
  const InputNode figures = r["figures"];
  const InputNode by_speed = r["ranges_by_speed_kmh"];
  std::optional<InputNode> at_speed;  // the ranges at the run's speed (within 0.5 km/h)
  for (const auto& speed : by_speed.keys()) {
    double v = 0;
    try {
      v = std::stod(speed);
    } catch (const std::exception&) {
      by_speed.fail_key(speed, "must be a speed in km/h");
    }
    if (std::abs(v - context.speed_kmh) < 0.5) at_speed = by_speed[speed];
  }
  for (std::size_t i = 0; i < figures.size(); ++i) {
    const InputNode f = figures.at(i);
    f.allow_only({"key", "label", "unit", "from", "scale"});
    Criterion k;
    k.key = k.figure = f.get_string("key");
    if (!is_figure(k.figure)) f.fail_key("key", "is not a figure pcsim computes");
    k.label = f.get_string("label");
    k.unit = f.get_string("unit");
    k.clause = root.get_string("clause");
    k.source = root.get_string("source");
    k.sourced = root.get_bool("sourced", false);
    if (at_speed && at_speed->has(k.figure)) {
      const auto range = (*at_speed)[k.figure].as_doubles();
      if (range.size() != 2 || range[0] > range[1])
        at_speed->fail_key(k.figure, "must be [low, high]");
      k.lower = {CriterionBound::Kind::constant, range[0], 0, "", false};
      k.upper = {CriterionBound::Kind::constant, range[1], 0, "", false};
    }
    set.criteria.push_back(k);
  }
}

CriteriaSet read_set(const InputNode& root, const CriteriaContext& context, bool builtin) {
  root.allow_only({"name", "title", "scope", "electrification", "criteria", "ranges", "clause",
                   "source", "sourced"});
  CriteriaSet set;
  set.name = root.get_string("name");
  set.title = root.get_string("title", set.name);
  set.scope = root.get_string("scope", "");
  set.file = root.file();
  if (root.has("electrification")) {
    check_electrification(root["electrification"]);
    set.electrification = strings_of(root["electrification"]);
  }
  if (root.has("ranges") == root.has("criteria"))
    root.fail("give either 'criteria' (a list) or 'ranges' (an EN 50318-style ranges file)");
  if (root.has("ranges")) {
    read_ranges(root, builtin, context, set);
    return set;
  }
  const InputNode list = root["criteria"];
  if (!list.is_sequence() || list.size() == 0) list.fail("must be a non-empty list of criteria");
  for (std::size_t i = 0; i < list.size(); ++i) {
    const Criterion k = read_criterion(list.at(i));
    if (applies(list.at(i), context)) set.criteria.push_back(k);
  }
  return set;
}

}  // namespace

std::vector<std::string> builtin_criteria_sets() {
  std::vector<std::string> names;
  for (const auto& [path, text] : builtin_input_files())
    if (path.rfind(kBuiltinPrefix, 0) == 0)
      names.push_back(path.substr(std::string(kBuiltinPrefix).size(),
                                  path.size() - std::string(kBuiltinPrefix).size() - 5));
  return names;
}

CriteriaSet read_criteria_set(const InputNode& root, const CriteriaContext& context) {
  return read_set(root, context, false);
}

CriteriaSet builtin_criteria_set(const std::string& name, const CriteriaContext& context) {
  const std::string file = kBuiltinPrefix + name + ".yaml";
  const auto it = builtin_input_files().find(file);
  if (it == builtin_input_files().end())
    throw InputError("", "assessment.criteria", "no built-in criteria set '" + name + "'");
  return read_set(InputNode::load_string(it->second, file + kBuiltinLabel), context, true);
}

}  // namespace pcsim::scene
