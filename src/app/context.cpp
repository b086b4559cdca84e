// What every command gets from the command line: the scene (composed, with
// the --set overrides), its name, the output folder and the provenance.
#include <cstdio>
#include <fstream>
#include <sstream>

#include "command.hpp"
#include "pcsim/output/provenance.hpp"
#include "pcsim/scene/composition.hpp"
#include "pcsim/simulation/run_checkpoint.hpp"

namespace pcsim::app {

std::map<std::string, Command>& command_registry() {
  static std::map<std::string, Command> registry;
  return registry;
}

scene::InputNode CommandContext::load_scene() const {
  std::vector<scene::InputOverride> parsed;
  for (const auto& o : overrides)
    parsed.push_back(scene::parse_override(o, {"", "command line --set " + o}));
  return scene::load_composed(scene_path, parsed);
}

std::string CommandContext::scene_name(const scene::InputNode& scene) const {
  if (scene.has("name")) {
    const std::string name = scene.get_string("name");
    const std::string why = output::invalid_folder_name_reason(name);
    if (!why.empty()) scene.fail_key("name", why);
    return name;
  }
  std::string base = scene_path.substr(scene_path.find_last_of('/') + 1);
  auto dot = base.find_last_of('.');
  base = dot == std::string::npos ? base : base.substr(0, dot);
  if (!output::invalid_folder_name_reason(base).empty())
    throw InputError(scene_path, "name", "missing, and the file name gives no usable name");
  return base;
}

nlohmann::json CommandContext::provenance(const scene::InputNode& scene) const {
  output::ProvenanceInputs in;
  in.command = command;
  in.arguments = arguments;
  in.scene_file = scene_path;
  std::ostringstream text;
  text << std::ifstream(scene_path).rdbuf();
  in.scene_text = text.str();
  in.overrides = overrides;
  in.ranks = size;
  simulation::record_inputs(in, command + " " + subcommand, scene_path, scene);
  return output::make_provenance(in);
}

output::OutputRequest CommandContext::output_request(const scene::InputNode& scene) const {
  const std::string name = scene_name(scene);  // validated even when -o is given
  output::OutputRequest request;
  request.dir = output_dir.empty() ? "out/" + name : output_dir;
  request.given_in = output_dir.empty() ? scene_path : "command line";
  request.given_by = output_dir.empty() ? "name" : "-o";
  request.command = command;
  request.scene_file = scene_path;
  request.scene_name = name;
  request.provenance = provenance(scene);
  request.overwrite = overwrite;
  request.cleanup_on_signal = cleanup_on_signal;
  return request;
}

}  // namespace pcsim::app
