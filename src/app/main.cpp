// pcsim: pantograph-catenary dynamic interaction simulator.
//
//   pcsim <command> SCENE.yaml [-o DIR] [PETSc options]
//
// The scene (YAML) gives the physics; numerics come from PETSc's options
// database (-snes_*, -ksp_*, -ts_*, -eps_*, -log_view, ...).
#include <slepcsys.h>

#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "command.hpp"
#include "exit_status.hpp"
#include "pcsim/core/error.hpp"

namespace pcsim::app {

std::map<std::string, Command>& command_registry() {
  static std::map<std::string, Command> registry;
  return registry;
}

void print0(const CommandContext& ctx, const char* format, ...) {
  if (ctx.rank != 0) return;
  va_list args;
  va_start(args, format);
  std::vfprintf(stdout, format, args);
  va_end(args);
  std::fflush(stdout);
}

std::string CommandContext::scene_name(const InputNode& scene) const {
  if (scene.has("name")) {
    const std::string name = scene.get_string("name");
    const std::string why = invalid_folder_name_reason(name);
    if (!why.empty()) throw InputError(scene_path, "name", why);
    return name;
  }
  std::string base = scene_path.substr(scene_path.find_last_of('/') + 1);
  auto dot = base.find_last_of('.');
  base = dot == std::string::npos ? base : base.substr(0, dot);
  if (!invalid_folder_name_reason(base).empty())
    throw InputError(scene_path, "name", "missing, and the file name gives no usable name");
  return base;
}

OutputRequest CommandContext::output_request(const InputNode& scene) const {
  const std::string name = scene_name(scene);  // validated even when -o is given
  if (output_dir.empty()) return {"out/" + name, scene_path, "name", command, scene_path, name};
  return {output_dir, "command line", "-o", command, scene_path, name};
}

}  // namespace pcsim::app

namespace {

void print_usage() {
  std::printf(
      "pcsim - parallel pantograph-catenary interaction simulator\n\n"
      "usage: pcsim <command> SCENE.yaml [-o DIR] [PETSc options]\n\n"
      "commands:\n");
  for (const auto& [name, command] : pcsim::app::command_registry())
    std::printf("  %-12s %s\n", name.c_str(), command.summary.c_str());
  std::printf(
      "\noptions:\n"
      "  -o DIR       output folder (default out/<scene name>/)\n"
      "  --restart DIR  (run) continue the run whose checkpoint is in DIR, into a new folder\n"
      "  -h, --help   this text\n"
      "Any other option goes to PETSc's options database, e.g. -snes_monitor,\n"
      "-snes_test_jacobian, -ksp_type, -ts_dt, -eps_nev, -log_view, -options_left.\n");
}

}  // namespace

int main(int argc, char** argv) {
  using namespace pcsim::app;
  if (argc < 2 || !std::strcmp(argv[1], "-h") || !std::strcmp(argv[1], "--help") ||
      !std::strcmp(argv[1], "help")) {
    print_usage();
    return argc < 2 ? 1 : 0;
  }
  const std::string command_name = argv[1];
  auto it = command_registry().find(command_name);
  if (it == command_registry().end()) {
    std::fprintf(stderr, "pcsim: error: unknown command '%s' (see pcsim --help)\n",
                 command_name.c_str());
    return 2;
  }
  CommandContext ctx;
  ctx.command = command_name;
  // Split our own arguments from PETSc's.
  std::vector<char*> petsc_argv = {argv[0]};
  for (int i = 2; i < argc; ++i) {
    if (!std::strcmp(argv[i], "-o") || !std::strcmp(argv[i], "--output")) {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "pcsim: error: option -o needs a folder\n");
        return 2;
      }
      ctx.output_dir = argv[++i];
    } else if (!std::strcmp(argv[i], "--restart")) {
      if (command_name != "run" || i + 1 >= argc) {
        std::fprintf(stderr, "pcsim: error: %s\n",
                     command_name != "run" ? "only 'pcsim run' takes --restart"
                                           : "option --restart needs a result folder");
        return 2;
      }
      ctx.restart_dir = argv[++i];
    } else if (!std::strcmp(argv[i], "-h") || !std::strcmp(argv[i], "--help")) {
      std::printf("usage: pcsim %s SCENE.yaml [-o DIR]%s [PETSc options]\n  %s\n",
                  command_name.c_str(), command_name == "run" ? " [--restart DIR]" : "",
                  it->second.summary.c_str());
      return 0;
    } else if (ctx.scene_path.empty() && argv[i][0] != '-') {
      ctx.scene_path = argv[i];
    } else {
      petsc_argv.push_back(argv[i]);
    }
  }
  if (ctx.scene_path.empty()) {
    std::fprintf(stderr, "pcsim: error: '%s' needs a scene file (pcsim %s SCENE.yaml)\n",
                 command_name.c_str(), command_name.c_str());
    return 2;
  }
  int petsc_argc = static_cast<int>(petsc_argv.size());
  petsc_argv.push_back(nullptr);
  char** petsc_args = petsc_argv.data();
  if (SlepcInitialize(&petsc_argc, &petsc_args, nullptr, nullptr) != 0) return 4;
  ctx.comm = PETSC_COMM_WORLD;
  MPI_Comm_rank(ctx.comm, &ctx.rank);
  MPI_Comm_size(ctx.comm, &ctx.size);

  // Exit status agreed by all ranks (exit_status.hpp); may MPI_Abort.
  MPI_Comm agreement_comm;
  MPI_Comm_dup(ctx.comm, &agreement_comm);
  int status = 0;
  std::string message;
  bool failed = false;
  try {
    debug_fail_if_asked(ctx);
    status = it->second.run(ctx);
  } catch (...) {
    failed = true;
    status = exit_status_of(std::current_exception(), ctx, message);
  }
  status = agree_exit_status(agreement_comm, status, message, failed);
  MPI_Comm_free(&agreement_comm);
  SlepcFinalize();
  return status;
}
