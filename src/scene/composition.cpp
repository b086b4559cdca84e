// Composition of input files: base files, 'set' entries and command-line
// overrides, with the origin of every value (pcsim/scene/composition.hpp).
#include "pcsim/scene/composition.hpp"

#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <unordered_map>

namespace pcsim::scene {

namespace {

bool is_index(const std::string& s) {
  return !s.empty() && s.find_first_not_of("0123456789") == std::string::npos;
}

std::string child_key(const std::string& parent, const std::string& key) {
  return parent.empty() ? key : parent + "." + key;
}

// "a.b[0].c" or "a.b.0.c" -> {a, b, 0, c}; "" if the path is malformed.
std::vector<std::string> split_key(const std::string& key) {
  std::vector<std::string> out;
  std::string part;
  auto flush = [&](bool allow_empty) {
    if (part.empty() && !allow_empty) return false;
    if (!part.empty()) out.push_back(part);
    part.clear();
    return true;
  };
  for (std::size_t i = 0; i < key.size(); ++i) {
    const char c = key[i];
    if (c == '.') {
      if (!flush(i > 0 && key[i - 1] == ']')) return {};
    } else if (c == '[') {
      if (!flush(i > 0 && key[i - 1] == ']')) return {};
      const auto close = key.find(']', i);
      if (close == std::string::npos || !is_index(key.substr(i + 1, close - i - 1))) return {};
      out.push_back(key.substr(i + 1, close - i - 1));
      i = close;
    } else {
      part += c;
    }
  }
  if (!flush(!key.empty() && key.back() == ']')) return {};
  return out;
}

// The folder of 'file' with a trailing '/' ("" for the working directory).
std::string folder_of(const std::string& file) {
  const auto slash = file.find_last_of('/');
  return slash == std::string::npos ? std::string() : file.substr(0, slash + 1);
}

std::string resolve(const std::string& origin_file, const std::string& relative) {
  if (!relative.empty() && relative[0] == '/') return relative;
  return folder_of(origin_file) + relative;
}

// The value at 'path' and everything below it now come from 'origin'.
void set_origin(InputSources& s, const std::string& path, const InputOrigin& origin) {
  for (auto it = s.origins.lower_bound(path); it != s.origins.end();) {
    const std::string& k = it->first;
    if (k.compare(0, path.size(), path) != 0) break;
    const bool below =
        path.empty() || k.size() == path.size() || k[path.size()] == '.' || k[path.size()] == '[';
    it = below ? s.origins.erase(it) : std::next(it);
  }
  s.origins[path] = origin;
}

// 'layer' merged over 'base' at key path 'path' (maps key by key, anything
// else replaced), recording the origin of what 'layer' gave. Linear in the
// number of keys (an index of the base's keys; force_insert appends without
// yaml-cpp's linear search).
YAML::Node merge(const YAML::Node& base, const YAML::Node& layer, const std::string& path,
                 InputSources& s, const InputOrigin& origin) {
  if (!(base.IsMap() && layer.IsMap())) {
    set_origin(s, path, origin);
    return YAML::Clone(layer);
  }
  std::unordered_map<std::string, YAML::Node> merged;  // the layer's keys, merged
  std::unordered_map<std::string, YAML::Node> below;   // the base's keys
  for (const auto& kv : base) below.emplace(kv.first.Scalar(), kv.second);
  for (const auto& kv : layer) {
    const std::string key = kv.first.Scalar();
    const auto it = below.find(key);
    merged[key] = merge(it != below.end() ? it->second : YAML::Node(), kv.second,
                        child_key(path, key), s, origin);
  }
  YAML::Node out(YAML::NodeType::Map);
  for (const auto& kv : base) {
    const auto it = merged.find(kv.first.Scalar());
    out.force_insert(kv.first.Scalar(), it != merged.end() ? it->second : YAML::Clone(kv.second));
  }
  for (const auto& kv : layer)
    if (below.find(kv.first.Scalar()) == below.end())
      out.force_insert(kv.first.Scalar(), merged[kv.first.Scalar()]);
  return out;
}

[[noreturn]] void bad_override(const InputOverride& o, const std::string& reason) {
  throw InputError(o.origin.label, o.key, reason);
}

// The rest of an override's path addresses the file named at 'path'.
void defer(const InputOverride& o, std::size_t next, const YAML::Node& reference,
           const std::string& path, InputSources& s) {
  const std::string named = reference.Scalar();
  const std::string file = resolve(s.origin_of(path).file, named);
  if (!unreadable_file_reason(file).empty())
    bad_override(o, "'" + path + "' is '" + named + "', not a file whose keys can be set");
  InputOverride rest = o;
  rest.origin.label += " (in " + file + ")";
  rest.path.assign(o.path.begin() + static_cast<std::ptrdiff_t>(next), o.path.end());
  s.deferred[path].push_back(rest);
}

// The nodes of a tree by key path, for overrides: a map's children are
// indexed when an override first passes through it, so that thousands of
// overrides of one map cost O(n log n), not yaml-cpp's linear search each.
struct TreeIndex {
  std::map<std::string, YAML::Node> nodes;  // key path -> node
  std::set<std::string> maps;               // key paths of the maps whose keys are indexed
  // Forgets everything below 'path' (its value was replaced).
  void forget_below(const std::string& path) {
    auto below = [&](const std::string& k) {
      return k.compare(0, path.size(), path) == 0 &&
             (path.empty() || k[path.size()] == '.' || k[path.size()] == '[');
    };
    for (auto it = nodes.upper_bound(path);
         it != nodes.end() && it->first.compare(0, path.size(), path) == 0;)
      it = below(it->first) ? nodes.erase(it) : std::next(it);
    maps.erase(path);
    for (auto it = maps.upper_bound(path);
         it != maps.end() && it->compare(0, path.size(), path) == 0;)
      it = below(*it) ? maps.erase(it) : std::next(it);
  }
};

// The child 'part' of the map (or null) 'node' at 'path'; an undefined node if absent.
YAML::Node map_child(YAML::Node& node, const std::string& path, const std::string& part,
                     TreeIndex& index) {
  if (index.maps.insert(path).second && node.IsMap())
    for (auto kv : node) index.nodes[child_key(path, kv.first.Scalar())] = kv.second;
  const auto it = index.nodes.find(child_key(path, part));
  return it == index.nodes.end() ? YAML::Node(YAML::NodeType::Undefined) : it->second;
}

// Sets the value at 'path' (the child 'part' of map 'node'): replaced in place
// if present, else appended.
YAML::Node set_map_child(YAML::Node& node, const std::string& parent, const std::string& part,
                         const YAML::Node& value, TreeIndex& index) {
  const std::string path = child_key(parent, part);
  YAML::Node child = map_child(node, parent, part, index);
  index.forget_below(path);
  if (child.IsDefined()) {
    child = value;
    return child;
  }
  YAML::Node added = value;
  node.force_insert(part, added);
  index.nodes[path] = added;
  return added;
}

void apply_override(YAML::Node& root, const InputOverride& o, InputSources& s, TreeIndex& index) {
  YAML::Node node(root);
  std::string path;
  for (std::size_t i = 0; i < o.path.size(); ++i) {
    const std::string& part = o.path[i];
    const bool last = i + 1 == o.path.size();
    YAML::Node child;
    if (node.IsSequence()) {
      if (!is_index(part))
        bad_override(o, "'" + path + "' is a list: give an entry number, e.g. " + path + "[0]");
      const std::size_t k = std::stoul(part);
      if (k >= node.size())
        bad_override(o, "'" + path + "' has " + std::to_string(node.size()) +
                            (node.size() == 1 ? " entry" : " entries") + " (numbered from 0)");
      path += "[" + part + "]";
      if (last) {
        index.forget_below(path);
        node[k] = YAML::Clone(o.value);
      }
      child.reset(node[k]);
    } else {
      if (!node.IsMap() && !node.IsNull())
        bad_override(o, "'" + path + "' is a value, not a map of keys");
      const std::string parent = path;
      path = child_key(path, part);
      if (last) {
        set_map_child(node, parent, part, YAML::Clone(o.value), index);
        set_origin(s, path, o.origin);
        return;
      }
      child.reset(map_child(node, parent, part, index));
      if (!child.IsMap() && !child.IsSequence() &&
          !child.IsScalar()) {  // missing or empty: a new map
        child.reset(set_map_child(node, parent, part, YAML::Node(YAML::NodeType::Map), index));
        set_origin(s, path, o.origin);
      }
    }
    if (last) {
      set_origin(s, path, o.origin);
      return;
    }
    if (child.IsScalar()) return defer(o, i + 1, child, path, s);
    if (!child.IsMap() && !child.IsSequence()) {  // missing or empty: a new map
      child = YAML::Node(YAML::NodeType::Map);
      set_origin(s, path, o.origin);
    }
    node.reset(child);
  }
}

struct Composed {
  YAML::Node root;
  InputSources sources;
};

YAML::Node parse_root(const std::string& text, const std::string& file) {
  const YAML::Node root = parse_yaml_document(text, file);
  if (!root.IsMap()) throw InputError(file, "", "top level must be a map of keys");
  return root;
}

std::string read_text(const std::string& path) {
  const std::string why = unreadable_file_reason(path);
  if (!why.empty()) throw InputError(path, "", "cannot open file: " + why);
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

Composed compose(const std::string& text, const std::string& file, std::vector<std::string> chain) {
  const YAML::Node root = parse_root(text, file);
  chain.push_back(file);
  Composed out;
  if (root["base"].IsDefined()) {
    const YAML::Node base = root["base"];
    if (!base.IsScalar() || base.Scalar().empty())
      throw InputError(file, "base", "must be the path of the file this one builds on");
    const std::string base_file = resolve(file, base.Scalar());
    for (const auto& f : chain)
      if (f == base_file)
        throw InputError(file, "base", "circular base chain through '" + base_file + "'");
    const std::string why = unreadable_file_reason(base_file);
    if (!why.empty())
      throw InputError(file, "base", "cannot open base file '" + base_file + "': " + why);
    out = compose(read_text(base_file), base_file, chain);
  } else {
    out.root = YAML::Node(YAML::NodeType::Map);
  }
  out.sources.root_file = file;
  out.sources.origins[""] = {file, file};
  YAML::Node layer(YAML::NodeType::Map);
  for (const auto& kv : root) {
    const std::string key = kv.first.as<std::string>();
    if (key != "base" && key != "set") layer.force_insert(key, kv.second);
  }
  out.root = merge(out.root, layer, "", out.sources, {file, file});
  out.sources.origins[""] = {file, file};
  if (root["set"].IsDefined()) {
    const YAML::Node set = root["set"];
    if (!set.IsMap()) throw InputError(file, "set", "must be a map of key paths to values");
    TreeIndex index;
    for (const auto& kv : set) {
      const std::string key = kv.first.as<std::string>();
      InputOverride o = parse_override(key + "=x", {file, file + " (set " + key + ")"});
      o.value.reset(kv.second);  // rebinds (assignment would merge the whole file's node memory)
      apply_override(out.root, o, out.sources, index);
    }
  }
  return out;
}

InputNode finish(Composed c, const std::vector<InputOverride>& overrides) {
  TreeIndex index;
  for (const auto& o : overrides) apply_override(c.root, o, c.sources, index);
  auto sources = std::make_shared<const InputSources>(std::move(c.sources));
  return InputNode(c.root, "", std::move(sources));
}

}  // namespace

InputOverride parse_override(const std::string& assignment, const InputOrigin& origin) {
  InputOverride o;
  o.origin = origin;
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0)
    throw InputError(origin.label, "--set", "expected KEY=VALUE, got '" + assignment + "'");
  o.key = assignment.substr(0, eq);
  o.path = split_key(o.key);
  if (o.path.empty())
    throw InputError(origin.label, "--set",
                     "'" + o.key +
                         "' is not a key path (keys separated by '.', list entries "
                         "as [N], e.g. pantographs[0].start_x)");
  const std::string text = assignment.substr(eq + 1);
  if (text.empty()) throw InputError(origin.label, o.key, "needs a value after '='");
  try {
    o.value = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw InputError(origin.label, o.key, "value is not valid YAML: " + std::string(e.what()));
  }
  check_yaml_tree(o.value, origin.label, o.key);
  if (o.value.IsNull()) throw InputError(origin.label, o.key, "needs a value, got an empty one");
  return o;
}

InputNode load_composed(const std::string& path, const std::vector<InputOverride>& overrides) {
  return finish(compose(read_text(path), path, {}), overrides);
}

InputNode load_composed_text(const std::string& text, const std::string& file,
                             const std::vector<InputOverride>& overrides) {
  return finish(compose(text, file, {}), overrides);
}

std::string to_yaml(const InputNode& node) {
  YAML::Emitter out;
  out << node.raw();
  return std::string(out.c_str()) + "\n";
}

}  // namespace pcsim::scene
