// Subcommands of the pcsim executable. Each file cmd_*.cpp registers one
// command with PCSIM_COMMAND (and its --help text and own options with
// PCSIM_COMMAND_HELP); main.cpp dispatches on the first argument.
#pragma once

#include <mpi.h>

#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "pcsim/catenary/mesh.hpp"
#include "pcsim/catenary/results.hpp"
#include "pcsim/output/output_dir.hpp"
#include "pcsim/scene/yaml_input.hpp"
#include "pcsim/simulation/context.hpp"

namespace pcsim::app {

// The command line of one command; comm, rank, size, cache_dir (--cache DIR)
// and quiet come from the simulation part's context.
struct CommandContext : simulation::Context {
  std::string command;                 // the command being run ("run", "static", ...)
  std::string scene_path;              // SCENE.yaml as given
  std::string output_dir;              // from -o, or "" for the default out/<scene name>
  std::string subcommand;              // commands with a subcommand: `pcsim study accuracy SCENE`
  std::vector<std::string> arguments;  // the whole command line (argv)
  std::vector<std::string> overrides;  // --set KEY=VALUE, in order
  std::vector<std::string> operands;   // commands without a scene: what they take instead
  bool overwrite = false;              // --overwrite: replace a result of other inputs
  bool cleanup_on_signal = true;       // output::OutputRequest::cleanup_on_signal (false: MPI sweep cases)
  std::vector<std::string> petsc_arguments;    // what went to PETSc's options database
  std::map<std::string, std::string> options;  // the command's own options ("" for a flag)
  bool has_option(const std::string& name) const { return options.count(name) > 0; }
  // The scene: the file with its base files and 'set' entries, then the --set
  // overrides (pcsim/scene/composition.hpp).
  scene::InputNode load_scene() const;
  // Scene name: 'name' key of the scene, else the file name without extension.
  // InputError (scene file, key 'name') if it cannot name a folder.
  std::string scene_name(const scene::InputNode& scene) const;
  // What produced the results (output/provenance.hpp): version, command line,
  // scene text and its composed form, PETSc options, ranks, date, host.
  nlohmann::json provenance(const scene::InputNode& scene) const;
  // The output folder (-o, or out/<scene name>) with who gave it, for output::OutputDir.
  output::OutputRequest output_request(const scene::InputNode& scene) const;
};

struct CommandOption {
  std::string name;   // "-j", "--no-report"
  std::string value;  // what the value is ("N"), "" for a flag
  std::string help;
};

struct Command {
  std::string summary;  // one line for `pcsim --help`
  std::string help;     // `pcsim <command> --help`: the scene sections it reads
  std::vector<CommandOption> options;
  std::function<int(const CommandContext&)> run;
  bool has_subcommand = false;  // the first argument names a subcommand
  // What a command takes instead of a scene, for its usage line ("RUN_A RUN_B
  // [RUN ...]"); "" for the commands of one scene file.
  std::string operands;
};

std::map<std::string, Command>& command_registry();

struct CommandRegistrar {
  CommandRegistrar(const std::string& name, std::string summary,
                   std::function<int(const CommandContext&)> run, bool has_subcommand = false) {
    command_registry()[name].summary = std::move(summary);
    command_registry()[name].run = std::move(run);
    command_registry()[name].has_subcommand = has_subcommand;
  }
};

struct CommandHelpRegistrar {
  CommandHelpRegistrar(const std::string& name, std::string help,
                       std::vector<CommandOption> options) {
    command_registry()[name].help = std::move(help);
    command_registry()[name].options = std::move(options);
  }
};

struct CommandOperandsRegistrar {
  CommandOperandsRegistrar(const std::string& name, std::string operands) {
    command_registry()[name].operands = std::move(operands);
  }
};

using simulation::on_rank0;
using simulation::peak_memory_mb;
using simulation::print0;
using simulation::print_warnings;
using simulation::total_peak_memory_mb;

// Single-dash options (option_check.cpp): an option no PETSc, SLEPc or pcsim
// object can read is an input error before any work; after the command, the
// options no solver read are warned about.
void refuse_unknown_options(const CommandContext& ctx);
void warn_unread_options(const CommandContext& ctx);

// `pcsim run` with this command line (cmd_run.cpp): the cases of a sweep
// under mpirun run through it in-process, each on its group's communicator.
int run_scene_command(const CommandContext& ctx);

// Newton history, form-finding errors and dropper forces of a static solution.
void print_static_summary(const CommandContext& ctx, const catenary::CatenaryMesh& mesh,
                          const catenary::StaticResult& result);

}  // namespace pcsim::app

#define PCSIM_COMMAND(name, summary, function) \
  static ::pcsim::app::CommandRegistrar pcsim_command_registrar_##function(name, summary, function)
#define PCSIM_COMMAND_WITH_SUBCOMMAND(name, summary, function)                            \
  static ::pcsim::app::CommandRegistrar pcsim_command_registrar_##function(name, summary, \
                                                                           function, true)
// --help text (scene sections, docs) and the command's own options.
#define PCSIM_COMMAND_HELP(tag, name, help, ...) \
  static ::pcsim::app::CommandHelpRegistrar pcsim_command_help_##tag(name, help, {__VA_ARGS__})
// A command that takes 'operands' (its usage line) instead of a scene file.
#define PCSIM_COMMAND_OPERANDS(tag, name, operands) \
  static ::pcsim::app::CommandOperandsRegistrar pcsim_command_operands_##tag(name, operands)
