// Strict, self-describing access to YAML input files.
//
// Every value read through an InputNode knows the file and the key path it
// came from, so that errors read "meshes/x.yaml: key 'wires.contact.tension':
// must be positive (got -5)". Unknown keys are rejected with
// InputNode::allow_only(), so that a typo never goes unnoticed.
#pragma once

#include <yaml-cpp/yaml.h>

#include <array>
#include <initializer_list>
#include <string>
#include <vector>

#include "pcsim/core/error.hpp"

namespace pcsim {

// Why 'path' cannot be read as an input file ("" if it can): missing, a
// folder, not a regular file, or unreadable.
std::string unreadable_file_reason(const std::string& path);

class InputNode {
 public:
  // Loads a YAML file; throws InputError if it is missing or malformed.
  static InputNode load_file(const std::string& path);
  // Parses YAML text (for tests); 'file' names it in messages.
  static InputNode load_string(const std::string& text, const std::string& file);

  InputNode(YAML::Node node, std::string file, std::string path)
      : node_(std::move(node)), file_(std::move(file)), path_(std::move(path)) {}

  const std::string& file() const { return file_; }
  const std::string& path() const { return path_; }
  // Directory of the file (for resolving relative paths), with a trailing '/'.
  std::string directory() const;
  // Resolves a path given in this file: absolute, or relative to the file's folder.
  std::string resolve_path(const std::string& relative) const;
  // The file named by key 'key' (resolved as above); fails naming the key when it
  // is missing, a folder or unreadable.
  std::string get_file_path(const std::string& key) const;

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

  // Rejects any key not in 'allowed'.
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
  // Enumerated strings.
  std::string get_choice(const std::string& key, std::initializer_list<const char*> choices,
                         const std::string& fallback) const;

  // Error about this node (or one of its keys).
  [[noreturn]] void fail(const std::string& reason) const;
  [[noreturn]] void fail_key(const std::string& key, const std::string& reason) const;

  const YAML::Node& raw() const { return node_; }

 private:
  std::string child_path(const std::string& key) const;
  YAML::Node node_;
  std::string file_;
  std::string path_;
};

}  // namespace pcsim
