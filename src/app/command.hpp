// Subcommands of the pcsim executable. Each file cmd_*.cpp registers one
// command with PCSIM_COMMAND; main.cpp dispatches on the first argument.
#pragma once

#include <mpi.h>

#include <functional>
#include <map>
#include <string>

#include "pcsim/catenary/mesh.hpp"
#include "pcsim/catenary/results.hpp"
#include "pcsim/output/output_dir.hpp"
#include "pcsim/scene/yaml_input.hpp"

namespace pcsim::app {

struct CommandContext {
  MPI_Comm comm = MPI_COMM_WORLD;
  int rank = 0;
  int size = 1;
  std::string command;      // the command being run ("run", "static", ...)
  std::string scene_path;   // SCENE.yaml as given
  std::string output_dir;   // from -o, or "" for the default out/<scene name>
  std::string restart_dir;  // from --restart (pcsim run only), or ""
  // Scene name: 'name' key of the scene, else the file name without extension.
  // InputError (scene file, key 'name') if it cannot name a folder.
  std::string scene_name(const InputNode& scene) const;
  // The output folder (-o, or out/<scene name>) with who gave it, for OutputDir.
  OutputRequest output_request(const InputNode& scene) const;
};

struct Command {
  std::string summary;  // one line for `pcsim --help`
  std::function<int(const CommandContext&)> run;
};

std::map<std::string, Command>& command_registry();

struct CommandRegistrar {
  CommandRegistrar(const std::string& name, std::string summary,
                   std::function<int(const CommandContext&)> run) {
    command_registry()[name] = Command{std::move(summary), std::move(run)};
  }
};

// Prints on rank 0 only.
void print0(const CommandContext& ctx, const char* format, ...);

// Newton history, form-finding errors and dropper forces of a static solution.
void print_static_summary(const CommandContext& ctx, const catenary::CatenaryMesh& mesh,
                          const catenary::StaticResult& result);

// Largest peak resident memory of any rank [MB] (collective).
double peak_memory_mb(MPI_Comm comm);

}  // namespace pcsim::app

#define PCSIM_COMMAND(name, summary, function) \
  static ::pcsim::app::CommandRegistrar pcsim_command_registrar_##function(name, summary, function)
