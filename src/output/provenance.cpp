#include "pcsim/output/provenance.hpp"

#include <petscsys.h>
#include <unistd.h>

#include "output_guard.hpp"
#include "pcsim/core/version.hpp"

namespace pcsim::output {

namespace {

std::string petsc_options() {
  PetscBool initialized = PETSC_FALSE;
  PetscInitialized(&initialized);
  if (!initialized) return "";
  char* all = nullptr;
  if (PetscOptionsGetAll(nullptr, &all) != 0 || !all) return "";
  std::string text = all;
  PetscFree(all);
  while (!text.empty() && text.back() == ' ') text.pop_back();
  return text;
}

std::string host() {
  char name[256] = {};
  gethostname(name, sizeof name - 1);
  return name;
}

std::string shell_quoted(const std::string& word) {
  if (!word.empty() && word.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                              "0123456789_-+=.,/:@%") == std::string::npos)
    return word;
  std::string out = "'";
  for (char c : word) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

}  // namespace

std::string quoted_command_line(const std::vector<std::string>& arguments) {
  std::string line;
  for (const auto& a : arguments) line += (line.empty() ? "" : " ") + shell_quoted(a);
  return line;
}

nlohmann::json make_provenance(const ProvenanceInputs& in) {
  return {{"pcsim_version", version()},
          {"git_commit", git_commit()},
          {"command", in.command},
          {"command_line", quoted_command_line(in.arguments)},
          {"scene_file", in.scene_file},
          {"scene_text", in.scene_text},
          {"resolved_scene", in.resolved_scene},
          {"overrides", in.overrides},
          {"petsc_options", petsc_options()},
          {"ranks", in.ranks},
          {"date", output_guard::utc_now()},
          {"host", host()}};
}

void stamp_provenance(H5File& h5, const nlohmann::json& provenance) {
  if (!provenance.is_object()) return;
  for (const auto& [key, value] : provenance.items()) {
    if (value.is_number()) {
      h5.attribute("/", key, value.get<double>());
    } else if (value.is_string()) {
      h5.attribute("/", key, value.get<std::string>());
    } else if (value.is_array() && !value.empty()) {
      std::vector<std::string> items;
      for (const auto& v : value) items.push_back(v.is_string() ? v.get<std::string>() : v.dump());
      h5.attribute("/", key, items);
    } else if (value.is_array()) {
      h5.attribute("/", key, std::string());
    } else {
      h5.attribute("/", key, value.dump());
    }
  }
}

}  // namespace pcsim::output
