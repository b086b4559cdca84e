#include "pcsim/scene/yaml_input.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <unordered_map>

#include "pcsim/scene/composition.hpp"

namespace pcsim::scene {

namespace {
std::string short_repr(const YAML::Node& n) {
  if (n.IsScalar()) return "'" + n.Scalar() + "'";
  if (n.IsSequence()) return "a list";
  if (n.IsMap()) return "a map";
  return "nothing";
}
}  // namespace

std::string unreadable_file_reason(const std::string& path) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (status.type() == std::filesystem::file_type::not_found) return "no such file";
  if (status.type() == std::filesystem::file_type::directory) return "is a folder, not a file";
  if (ec || status.type() != std::filesystem::file_type::regular) return "is not a regular file";
  if (!std::ifstream(path)) return "cannot be read (permissions?)";
  return "";
}

const InputOrigin& InputSources::origin_of(const std::string& key_path) const {
  std::string p = key_path;
  for (;;) {
    const auto it = origins.find(p);
    if (it != origins.end()) return it->second;
    if (p.empty()) break;
    const auto cut = p.find_last_of(".[");
    p = cut == std::string::npos ? std::string() : p.substr(0, cut);
  }
  static const InputOrigin unknown{"", "input"};
  return unknown;
}

namespace {

std::string line_of(const YAML::Mark& mark) {
  return mark.is_null() ? std::string() : "line " + std::to_string(mark.line + 1);
}

// Walks a parsed tree once: every map key a plain scalar given once, every
// value present (an empty 'dt:' would otherwise read as "use the default").
// Linear in the size of the tree (one hash set per map).
void check_tree(const YAML::Node& node, const std::string& path, const std::string& file) {
  if (node.IsMap()) {
    std::unordered_map<std::string, YAML::Mark> seen;
    seen.reserve(node.size());
    for (const auto& kv : node) {
      if (!kv.first.IsScalar())
        throw InputError(file, path,
                         "has a key that is not a plain name (" + line_of(kv.first.Mark()) + ")");
      const std::string key = kv.first.Scalar();
      const std::string child = path.empty() ? key : path + "." + key;
      const auto first = seen.emplace(key, kv.first.Mark());
      if (!first.second)
        throw InputError(file, child,
                         "duplicate key (first at " + line_of(first.first->second) + ", again at " +
                             line_of(kv.first.Mark()) + "): give each key once");
      check_tree(kv.second, child, file);
    }
  } else if (node.IsSequence()) {
    for (std::size_t i = 0; i < node.size(); ++i)
      check_tree(node[i], path + "[" + std::to_string(i) + "]", file);
  } else if (node.IsNull() && !path.empty()) {
    throw InputError(file, path,
                     "has no value (an empty value is not the default: give a value or "
                     "remove the key)");
  }
}

}  // namespace

void check_yaml_tree(const YAML::Node& root, const std::string& file, const std::string& key) {
  check_tree(root, key, file);
}

YAML::Node parse_yaml_document(const std::string& text, const std::string& file) {
  std::vector<YAML::Node> documents;
  try {
    documents = YAML::LoadAll(text);
  } catch (const YAML::Exception& e) {
    throw InputError(file, "", std::string("malformed YAML: ") + e.what());
  }
  if (documents.size() > 1) {
    const std::string where = line_of(documents[1].Mark());
    throw InputError(file, "",
                     "holds more than one YAML document (a second one after '---'" +
                         (where.empty() ? std::string() : ", " + where) +
                         "): a file is one document");
  }
  YAML::Node root = documents.empty() ? YAML::Node() : documents.front();
  check_tree(root, "", file);
  return root;
}

InputNode::InputNode(YAML::Node node, std::string file, std::string path)
    : node_(std::move(node)), path_(std::move(path)) {
  auto sources = std::make_shared<InputSources>();
  sources->root_file = file;
  sources->origins[""] = {file, file};
  sources_ = std::move(sources);
}

InputNode InputNode::load_file(const std::string& path) {
  const std::string why = unreadable_file_reason(path);
  if (!why.empty()) throw InputError(path, "", "cannot open file: " + why);
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  YAML::Node root = parse_yaml_document(text.str(), path);
  if (!root.IsMap()) throw InputError(path, "", "top level must be a map of keys");
  return InputNode(root, path, "");
}

InputNode InputNode::load_string(const std::string& text, const std::string& file) {
  return InputNode(parse_yaml_document(text, file), file, "");
}

std::string InputNode::directory() const {
  const std::string& file = origin().file;
  auto slash = file.find_last_of('/');
  return slash == std::string::npos ? std::string("./") : file.substr(0, slash + 1);
}

std::string InputNode::resolve_path(const std::string& relative) const {
  if (!relative.empty() && relative[0] == '/') return relative;
  return directory() + relative;
}

std::string InputNode::get_file_path(const std::string& key) const {
  const std::string path = path_value(key);
  const std::string why = unreadable_file_reason(path);
  if (!why.empty()) fail_key(key, "cannot open '" + path + "': " + why);
  return path;
}

std::string InputNode::path_value(const std::string& key) const {
  return (*this)[key].resolve_path(get_string(key));
}

InputNode InputNode::load_referenced(const std::string& key) const {
  const std::string file = get_file_path(key);
  const auto it = sources_->deferred.find(child_path(key));
  if (it != sources_->deferred.end()) return load_composed(file, it->second);
  const auto cached = sources_->referenced.find(file);
  if (cached != sources_->referenced.end())
    return InputNode(cached->second.first, "", cached->second.second);
  const InputNode loaded = load_composed(file);
  sources_->referenced[file] = {loaded.raw(), loaded.sources_};
  return loaded;
}

std::string InputNode::child_path(const std::string& key) const {
  return path_.empty() ? key : path_ + "." + key;
}

bool InputNode::has(const std::string& key) const {
  return node_.IsMap() && node_[key].IsDefined() && !node_[key].IsNull();
}

InputNode InputNode::operator[](const std::string& key) const {
  if (!node_.IsMap()) fail("must be a map with key '" + key + "'");
  if (!has(key)) fail_key(key, "required key is missing");
  return InputNode(node_[key], child_path(key), sources_);
}

InputNode InputNode::at(std::size_t index) const {
  if (!node_.IsSequence()) fail("must be a list");
  if (index >= node_.size()) fail("list has no entry " + std::to_string(index));
  return InputNode(node_[index], path_ + "[" + std::to_string(index) + "]", sources_);
}

std::vector<std::string> InputNode::keys() const {
  std::vector<std::string> out;
  if (!node_.IsMap()) return out;
  for (const auto& kv : node_) out.push_back(kv.first.as<std::string>());
  return out;
}

namespace {
AllowedKeys& allowed_key_registry() {
  static AllowedKeys registry;
  return registry;
}
}  // namespace

const AllowedKeys& allowed_keys_seen() {
  return allowed_key_registry();
}

void InputNode::allow_only(std::initializer_list<const char*> allowed) const {
  static const std::regex index("\\[[0-9]+\\]");
  auto& seen = allowed_key_registry()[sources_->root_file][std::regex_replace(path_, index, "[]")];
  for (const char* a : allowed) seen.insert(a);
  if (!node_.IsMap()) fail("must be a map of keys");
  for (const auto& kv : node_) {
    const std::string key = kv.first.as<std::string>();
    bool known = false;
    for (const char* a : allowed) known = known || key == a;
    if (!known) {
      std::string list;
      for (const char* a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
      fail_key(key, "unknown key (allowed here: " + list + ")");
    }
  }
}

double InputNode::as_double() const {
  if (!node_.IsScalar()) fail("must be a number, got " + short_repr(node_));
  try {
    double v = node_.as<double>();
    if (!std::isfinite(v)) fail("must be a finite number, got " + short_repr(node_));
    return v;
  } catch (const YAML::Exception&) {
    fail("must be a number, got " + short_repr(node_));
  }
}

long InputNode::as_int() const {
  if (!node_.IsScalar()) fail("must be an integer, got " + short_repr(node_));
  try {
    return node_.as<long>();
  } catch (const YAML::Exception&) {
    fail("must be an integer, got " + short_repr(node_));
  }
}

bool InputNode::as_bool() const {
  if (!node_.IsScalar()) fail("must be true or false, got " + short_repr(node_));
  try {
    return node_.as<bool>();
  } catch (const YAML::Exception&) {
    fail("must be true or false, got " + short_repr(node_));
  }
}

std::string InputNode::as_string() const {
  if (!node_.IsScalar()) fail("must be a string, got " + short_repr(node_));
  return node_.Scalar();
}

std::vector<double> InputNode::as_doubles() const {
  if (!node_.IsSequence()) fail("must be a list of numbers, got " + short_repr(node_));
  std::vector<double> out;
  for (std::size_t i = 0; i < node_.size(); ++i) out.push_back(at(i).as_double());
  return out;
}

std::array<double, 3> InputNode::as_vec3() const {
  auto v = as_doubles();
  if (v.size() != 3) fail("must be a list of 3 numbers [x, y, z]");
  return {v[0], v[1], v[2]};
}

double InputNode::get_double(const std::string& key, double fallback) const {
  return has(key) ? (*this)[key].as_double() : fallback;
}
long InputNode::get_int(const std::string& key, long fallback) const {
  return has(key) ? (*this)[key].as_int() : fallback;
}
bool InputNode::get_bool(const std::string& key, bool fallback) const {
  return has(key) ? (*this)[key].as_bool() : fallback;
}
std::string InputNode::get_string(const std::string& key, const std::string& fallback) const {
  return has(key) ? (*this)[key].as_string() : fallback;
}

static std::string num(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

double InputNode::get_positive(const std::string& key) const {
  double v = get_double(key);
  if (!(v > 0)) fail_key(key, "must be positive (got " + num(v) + ")");
  return v;
}
double InputNode::get_positive(const std::string& key, double fallback) const {
  return has(key) ? get_positive(key) : fallback;
}
double InputNode::get_nonnegative(const std::string& key) const {
  double v = get_double(key);
  if (!(v >= 0)) fail_key(key, "must not be negative (got " + num(v) + ")");
  return v;
}
double InputNode::get_nonnegative(const std::string& key, double fallback) const {
  return has(key) ? get_nonnegative(key) : fallback;
}

double InputNode::get_positive(const std::string& key, const Limit& limit) const {
  const double v = get_positive(key);
  const std::string why = limit_violation(v, limit);
  if (!why.empty()) fail_key(key, why);
  return v;
}
double InputNode::get_positive(const std::string& key, const Limit& limit, double fallback) const {
  return has(key) ? get_positive(key, limit) : fallback;
}
double InputNode::get_nonnegative(const std::string& key, const Limit& limit) const {
  const double v = get_nonnegative(key);
  const std::string why = limit_violation(v, limit);
  if (!why.empty()) fail_key(key, why);
  return v;
}
double InputNode::get_nonnegative(const std::string& key, const Limit& limit,
                                  double fallback) const {
  return has(key) ? get_nonnegative(key, limit) : fallback;
}
double InputNode::get_real(const std::string& key, const Limit& limit) const {
  const double v = get_double(key);
  const std::string why = limit_violation(v, limit);
  if (!why.empty()) fail_key(key, why);
  return v;
}
double InputNode::get_real(const std::string& key, const Limit& limit, double fallback) const {
  return has(key) ? get_real(key, limit) : fallback;
}

std::string InputNode::get_choice(const std::string& key,
                                  std::initializer_list<const char*> choices,
                                  const std::string& fallback) const {
  if (!has(key)) return fallback;
  std::string v = get_string(key);
  std::string list;
  for (const char* c : choices) {
    if (v == c) return v;
    list += (list.empty() ? "" : ", ") + std::string(c);
  }
  fail_key(key, "must be one of " + list + " (got '" + v + "')");
}

void InputNode::fail(const std::string& reason) const {
  throw InputError(origin().label, path_, reason);
}
void InputNode::fail_key(const std::string& key, const std::string& reason) const {
  const std::string path = child_path(key);
  throw InputError(sources_->origin_of(path).label, path, reason);
}
void InputNode::rethrow_with_origin(const InputError& error) const {
  const InputOrigin& origin = sources_->origin_of(error.key());
  if (error.file() == sources_->root_file && origin.label != error.file())
    throw InputError(origin.label, error.key(), error.reason());
  throw error;
}

}  // namespace pcsim::scene
