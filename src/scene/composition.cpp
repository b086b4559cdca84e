// Composition of input files: base files, 'set' entries and command-line
// overrides, with the origin of every value (pcsim/scene/composition.hpp).
#include "pcsim/scene/composition.hpp"

#include <fstream>
#include <sstream>

namespace pcsim {

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
// else replaced), recording the origin of what 'layer' gave.
YAML::Node merge(const YAML::Node& base, const YAML::Node& layer, const std::string& path,
                 InputSources& s, const InputOrigin& origin) {
  if (!(base.IsMap() && layer.IsMap())) {
    set_origin(s, path, origin);
    return YAML::Clone(layer);
  }
  YAML::Node out = YAML::Clone(base);
  for (const auto& kv : layer) {
    const std::string key = kv.first.as<std::string>();
    const YAML::Node below = base[key];
    out[key] =
        merge(below.IsDefined() ? below : YAML::Node(), kv.second, child_key(path, key), s, origin);
  }
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

void apply_override(YAML::Node& root, const InputOverride& o, InputSources& s) {
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
      if (last) node[k] = YAML::Clone(o.value);
      child.reset(node[k]);
    } else {
      if (!node.IsMap() && !node.IsNull())
        bad_override(o, "'" + path + "' is a value, not a map of keys");
      path = child_key(path, part);
      if (last) node[part] = YAML::Clone(o.value);
      child.reset(node[part]);
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
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw InputError(file, "", std::string("malformed YAML: ") + e.what());
  }
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
    if (key != "base" && key != "set") layer[key] = kv.second;
  }
  out.root = merge(out.root, layer, "", out.sources, {file, file});
  out.sources.origins[""] = {file, file};
  if (root["set"].IsDefined()) {
    const YAML::Node set = root["set"];
    if (!set.IsMap()) throw InputError(file, "set", "must be a map of key paths to values");
    for (const auto& kv : set) {
      const std::string key = kv.first.as<std::string>();
      InputOverride o = parse_override(key + "=x", {file, file + " (set " + key + ")"});
      o.value = kv.second;
      apply_override(out.root, o, out.sources);
    }
  }
  return out;
}

InputNode finish(Composed c, const std::vector<InputOverride>& overrides) {
  for (const auto& o : overrides) apply_override(c.root, o, c.sources);
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

}  // namespace pcsim
