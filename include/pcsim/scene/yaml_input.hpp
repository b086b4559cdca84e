// Strict, self-describing access to YAML input files.
//
// Every value read through an InputNode knows where it came from and its key
// path, so that errors read "meshes/x.yaml: key 'wires.contact.tension': must
// be positive (got -5)". Unknown keys are rejected with
// InputNode::allow_only(), so that a typo never goes unnoticed.
//
// A tree may be composed (pcsim/scene/composition.hpp): a base file, 'set'
// entries and command-line overrides. Each value then keeps its own origin:
// the file it was written in (for relative paths and messages) or the
// override that set it ("command line --set simulation.speed_kmh=320").
#pragma once

#include <yaml-cpp/yaml.h>

#include <array>
#include <initializer_list>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "pcsim/core/error.hpp"
#include "pcsim/core/limits.hpp"

namespace pcsim::scene {

// Why 'path' cannot be read as an input file ("" if it can): missing, a
// folder, not a regular file, or unreadable.
std::string unreadable_file_reason(const std::string& path);

// Parses the YAML text of one input file: InputError(file, ...) if it is
// malformed, holds more than one document ('---'), or its tree breaks
// check_yaml_tree. A file with no document gives a null node.
YAML::Node parse_yaml_document(const std::string& text, const std::string& file);
// Checks a parsed tree whose root is at key path 'key': no key given twice
// in a map, no key that is not a plain name, no empty value ('dt:' with
// nothing); InputError(file, key path, reason) on the first breach.
void check_yaml_tree(const YAML::Node& root, const std::string& file, const std::string& key);

// Where a value came from.
struct InputOrigin {
  std::string file;   // relative paths are resolved from its folder ("": working directory)
  std::string label;  // what messages name: the file, or the override
};

// A value set by key path (`--set KEY=VALUE`, or an entry of a file's 'set' map).
struct InputOverride {
  std::string key;                // the key path as written ("pantographs[0].start_x")
  std::vector<std::string> path;  // its components ("pantographs", "0", "start_x")
  YAML::Node value;
  InputOrigin origin;
};

// What the nodes of one tree share: the origins of its values and the
// overrides that address files named by its values.
struct InputSources {
  std::string root_file;
  std::map<std::string, InputOrigin> origins;  // key path -> origin (the longest prefix applies)
  std::map<std::string, std::vector<InputOverride>> deferred;  // reference key -> overrides
  // Files named by values of this tree, loaded once (load_referenced without
  // overrides): path -> composed root and its sources. 5000 pantographs of one
  // model parse the model file once.
  mutable std::map<std::string, std::pair<YAML::Node, std::shared_ptr<const InputSources>>>
      referenced;
  const InputOrigin& origin_of(const std::string& key_path) const;
};

class InputNode {
 public:
  // Loads a YAML file as it is (no composition); throws InputError if it is
  // missing or malformed.
  static InputNode load_file(const std::string& path);
  // Parses YAML text (for tests); 'file' names it in messages.
  static InputNode load_string(const std::string& text, const std::string& file);

  InputNode(YAML::Node node, std::string file, std::string path);
  InputNode(YAML::Node node, std::string path, std::shared_ptr<const InputSources> sources)
      : node_(std::move(node)), path_(std::move(path)), sources_(std::move(sources)) {}

  // What messages name for this node: its file, or the override that set it.
  const std::string& file() const { return origin().label; }
  const std::string& path() const { return path_; }
  // The file the whole tree was loaded from.
  const std::string& root_file() const { return sources_->root_file; }
  const InputSources& sources() const { return *sources_; }
  // Directory of the node's file (for resolving relative paths), with a trailing '/'.
  std::string directory() const;
  // Resolves a path given in this node's file: absolute, or relative to the file's folder.
  std::string resolve_path(const std::string& relative) const;
  // The path given by the string value of 'key', resolved relative to the
  // file that value was written in.
  std::string path_value(const std::string& key) const;
  // path_value(key), checked: fails naming the key when the file is missing, a
  // folder or unreadable.
  std::string get_file_path(const std::string& key) const;
  // Loads the YAML file named by the string value of 'key' (get_file_path),
  // composed (base, set) and with the overrides that address it through this
  // key (e.g. --set catenary.design.spans.count=20). InputError naming 'key'
  // if the file cannot be opened.
  InputNode load_referenced(const std::string& key) const;

  bool has(const std::string& key) const;
  bool is_map() const { return node_.IsMap(); }
  bool is_sequence() const { return node_.IsSequence(); }
  bool is_scalar() const { return node_.IsScalar(); }
  std::size_t size() const { return node_.size(); }

  // Required child (throws if missing).
  InputNode operator[](const std::string& key) const;
  // Element of a sequence.
  InputNode at(std::size_t index) const;
  // Keys of a map, in file order.
  std::vector<std::string> keys() const;

  // Rejects any key not in 'allowed'. Records the allowed keys of this key
  // path (allowed_keys_seen) for the test that compares them with the docs.
  void allow_only(std::initializer_list<const char*> allowed) const;

  // Typed scalar access (this node).
  double as_double() const;
  long as_int() const;
  bool as_bool() const;
  std::string as_string() const;
  std::vector<double> as_doubles() const;
  std::array<double, 3> as_vec3() const;

  // Typed access of a child, required or with a default.
  double get_double(const std::string& key) const { return (*this)[key].as_double(); }
  double get_double(const std::string& key, double fallback) const;
  long get_int(const std::string& key) const { return (*this)[key].as_int(); }
  long get_int(const std::string& key, long fallback) const;
  bool get_bool(const std::string& key, bool fallback) const;
  std::string get_string(const std::string& key) const { return (*this)[key].as_string(); }
  std::string get_string(const std::string& key, const std::string& fallback) const;
  // Range-checked reals: value > 0, value >= 0.
  double get_positive(const std::string& key) const;
  double get_positive(const std::string& key, double fallback) const;
  double get_nonnegative(const std::string& key) const;
  double get_nonnegative(const std::string& key, double fallback) const;
  // The same, and within the limit's bounds (pcsim/core/limits.hpp); get_real
  // only bounds the magnitude of a value of either sign.
  double get_positive(const std::string& key, const Limit& limit) const;
  double get_positive(const std::string& key, const Limit& limit, double fallback) const;
  double get_nonnegative(const std::string& key, const Limit& limit) const;
  double get_nonnegative(const std::string& key, const Limit& limit, double fallback) const;
  double get_real(const std::string& key, const Limit& limit) const;
  double get_real(const std::string& key, const Limit& limit, double fallback) const;
  // Enumerated strings.
  std::string get_choice(const std::string& key, std::initializer_list<const char*> choices,
                         const std::string& fallback) const;

  // Error about this node (or one of its keys), naming where its value came from.
  [[noreturn]] void fail(const std::string& reason) const;
  [[noreturn]] void fail_key(const std::string& key, const std::string& reason) const;
  // Rethrows an InputError raised about this tree (e.g. by a geometry builder
  // given the tree's file) naming the override that set the key, if one did.
  [[noreturn]] void rethrow_with_origin(const InputError& error) const;

  const YAML::Node& raw() const { return node_; }

 private:
  std::string child_path(const std::string& key) const;
  const InputOrigin& origin() const { return sources_->origin_of(path_); }
  YAML::Node node_;
  std::string path_;
  std::shared_ptr<const InputSources> sources_;
};

// The allowed keys of every map that allow_only() checked so far:
// root file -> key path (list indices written "[]") -> keys.
using AllowedKeys = std::map<std::string, std::map<std::string, std::set<std::string>>>;
const AllowedKeys& allowed_keys_seen();

}  // namespace pcsim::scene
