// pcsim: pantograph-catenary dynamic interaction simulator.
//
//   pcsim <command> SCENE.yaml [-o DIR] [--set KEY=VALUE]... [options] [PETSc options]
//
// The scene (YAML, docs/scene-format.md) gives the physics; numerics come from
// PETSc's options database (-snes_*, -ksp_*, -ts_*, -eps_*, -log_view, ...).
#include <hdf5.h>
#include <slepcsys.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "command.hpp"
#include "exit_status.hpp"
#include "pcsim/core/blas_kernels.hpp"
#include "pcsim/core/error.hpp"
#include "pcsim/core/version.hpp"
#include "pcsim/simulation/accuracy_pilot.hpp"
#include "pcsim/simulation/run_session.hpp"
#include "rerun.hpp"

namespace {

using pcsim::app::Command;
using pcsim::app::CommandContext;

// The common options; %s: the command's default output folder.
const char* const kCommonOptions =
    "  -o DIR           output folder (default %s)\n"
    "  --overwrite      replace an earlier result made from other inputs in that folder\n"
    "  --set KEY=VALUE  sets a scene key by its path, e.g. simulation.speed_kmh=320 or\n"
    "                   pantographs[0].static_force=100; a path through a key that names a\n"
    "                   file sets a key of that file, e.g. catenary.design.spans.count=20\n"
    "                   (repeatable, applied in order, checked like the file's keys)\n"
    "  --cache DIR      cache of reduced (modal) catenary bases (default out/.pcsim-cache)\n"
    "  -h, --help       this text\n";

// The common options of a command that takes no scene (Command::operands).
const char* const kOperandCommonOptions =
    "  -o DIR           output folder (default %s)\n"
    "  -h, --help       this text\n";

void print_usage() {
  std::printf(
      "pcsim %s - parallel pantograph-catenary interaction simulator\n\n"
      "usage: pcsim <command> SCENE.yaml [-o DIR] [--set KEY=VALUE]... [PETSc options]\n",
      pcsim::version());
  for (const auto& [name, command] : pcsim::app::command_registry())
    if (!command.operands.empty())
      std::printf("       pcsim %s %s [-o DIR]\n", name.c_str(), command.operands.c_str());
  std::printf(
      "       pcsim <command> --help     the scene sections and options of a command\n"
      "       pcsim --version\n\n"
      "commands:\n");
  for (const auto& [name, command] : pcsim::app::command_registry())
    std::printf("  %-12s %s\n", name.c_str(), command.summary.c_str());
  std::printf("\noptions:\n");
  std::printf(kCommonOptions, "out/<scene name>/");
  std::printf(
      "Options with a single dash go to PETSc's options database, e.g. -snes_monitor,\n"
      "-snes_test_jacobian, -ksp_type, -ts_dt, -eps_nev, -log_view, -options_left;\n"
      "-help lists every option a run reads (and stops before the time loop); an option\n"
      "no PETSc or pcsim object can read is an error, one no solver read a warning.\n"
      "pcsim's own, checked before any work:\n"
      "  -ts_dt, -ts_type hht|alpha2, -ts_hht_alpha [0, 1/3], -pcsim_path auto|full|cheap (run);\n"
      "  -ts_max_steps N >= 1, -ts_max_time T > 0: cut a run short (run; within the scene's\n"
      "  run, and past a restart's checkpoint);\n"
      "  -pcsim_accuracy_pilot auto|true|false: the pilot runs of the accuracy estimate\n"
      "  (run; auto: runs of the modal level; docs/fidelity.md);\n"
      "  -pcsim_record_batches auto|true|false: a modal run's records in batches (run);\n"
      "  -pcsim_record_thread auto|true|false: a batch's product on its own thread (run;\n"
      "  auto: where every rank has a core to spare);\n"
      "  -pcsim_pilot_process auto|true|false: the accuracy pilot's linear FE runs in a\n"
      "  second process beside its other runs (run; auto: one rank, a core to spare);\n"
      "  -pc_type pcsimwoodbury|pcsimschur: pcsim's step solvers as PETSc PC types (run;\n"
      "  pcsimwoodbury is the cheap path's; docs/architecture.md);\n"
      "  -eps_nev N, -modes_fmax F (modes); -pcsim_debug_* (tests).\n"
      "Scene files: docs/scene-format.md; catenary designs: docs/design-format.md.\n");
}

// Where a command's results go without -o.
std::string default_output(const std::string& command) {
  if (command == "sweep") return "out/<scene name>-sweep/";
  if (command == "study") return "out/<scene name>-accuracy/";
  if (command == "check") return "none: check writes nothing";
  if (command == "compare") return "out/compare-<A>-<B>/, the names of what is compared";
  return "out/<scene name>/";
}

void print_command_help(const std::string& name, const Command& command) {
  std::string own;
  for (const auto& o : command.options)
    own += " [" + o.name + (o.value.empty() ? "" : " " + o.value) + "]";
  if (command.operands.empty())
    std::printf(
        "usage: pcsim %s%s SCENE.yaml [-o DIR] [--set KEY=VALUE]...%s [PETSc options]\n  %s\n",
        name.c_str(), command.has_subcommand ? " SUBCOMMAND" : "", own.c_str(),
        command.summary.c_str());
  else
    std::printf("usage: pcsim %s %s [-o DIR]%s\n  %s\n", name.c_str(), command.operands.c_str(),
                own.c_str(), command.summary.c_str());
  if (!command.help.empty()) std::printf("\n%s", command.help.c_str());
  std::printf("\noptions:\n");
  std::printf(command.operands.empty() ? kCommonOptions : kOperandCommonOptions,
              default_output(name).c_str());
  for (const auto& o : command.options) {
    const std::string left = o.name + (o.value.empty() ? "" : " " + o.value);
    std::printf("  %-16s %s\n", left.c_str(), o.help.c_str());
  }
  std::printf("PETSc options: add -help to a run to list every option it reads.\n");
}

bool is_help(const char* arg) {
  return !std::strcmp(arg, "-h") || !std::strcmp(arg, "--help") || !std::strcmp(arg, "help");
}

const pcsim::app::CommandOption* own_option(const Command& command, const char* arg) {
  for (const auto& o : command.options)
    if (o.name == arg) return &o;
  return nullptr;
}

// Splits the arguments after the command into pcsim's and PETSc's; returns
// -1 to go on, else the exit status (help printed, or a usage error).
int parse_arguments(int argc, char** argv, const Command& command, CommandContext& ctx) {
  auto needs = [&](int i, const char* what) {
    if (i + 1 < argc && argv[i + 1][0] != '-') return true;
    std::fprintf(stderr, "pcsim: error: option %s needs %s%s\n", argv[i], what,
                 i + 1 < argc ? (std::string(", not the option ") + argv[i + 1]).c_str() : "");
    return false;
  };
  const bool takes_operands = !command.operands.empty();
  for (int i = 2; i < argc; ++i) {
    const char* arg = argv[i];
    if (takes_operands && (!std::strncmp(arg, "--set", 5) || !std::strcmp(arg, "--cache") ||
                           !std::strcmp(arg, "--overwrite"))) {
      std::fprintf(stderr, "pcsim: error: pcsim %s takes no %s (pcsim %s --help)\n",
                   ctx.command.c_str(), arg, ctx.command.c_str());
      return 2;
    }
    if (!std::strcmp(arg, "-o") || !std::strcmp(arg, "--output")) {
      if (!needs(i, "a folder")) return 2;
      ctx.output_dir = argv[++i];
    } else if (!std::strcmp(arg, "--cache")) {
      if (!needs(i, "a folder")) return 2;
      ctx.cache_dir = argv[++i];
    } else if (command.has_subcommand && ctx.subcommand.empty() && ctx.scene_path.empty() &&
               arg[0] != '-' && !is_help(arg)) {
      ctx.subcommand = arg;
    } else if (!std::strcmp(arg, "--set")) {
      if (!needs(i, "KEY=VALUE")) return 2;
      ctx.overrides.push_back(argv[++i]);
    } else if (!std::strncmp(arg, "--set=", 6)) {
      ctx.overrides.push_back(arg + 6);
    } else if (is_help(arg)) {
      print_command_help(ctx.command, command);
      return 0;
    } else if (const auto* o = own_option(command, arg)) {
      if (!o->value.empty() && !needs(i, o->value.c_str())) return 2;
      ctx.options[o->name] = o->value.empty() ? "" : argv[++i];
    } else if (!std::strcmp(arg, "--overwrite")) {
      ctx.overwrite = true;
    } else if (takes_operands && arg[0] != '-') {
      ctx.operands.push_back(arg);
    } else if (ctx.scene_path.empty() && arg[0] != '-') {
      ctx.scene_path = arg;
    } else if (arg[0] != '-' && !(i > 2 && ctx.petsc_arguments.size() &&
                                  ctx.petsc_arguments.back() == argv[i - 1])) {
      std::fprintf(stderr, "pcsim: error: '%s': one scene only (the scene is %s)\n", arg,
                   ctx.scene_path.c_str());
      return 2;
    } else if (arg[1] == '-') {  // PETSc reads no "--" option
      std::fprintf(stderr, "pcsim: error: unknown option %s (pcsim %s --help lists them)\n", arg,
                   ctx.command.c_str());
      return 2;
    } else {
      ctx.petsc_arguments.push_back(arg);
    }
  }
  if (ctx.options.count("--rerun")) {
    std::vector<std::string> recorded;
    const std::string why = pcsim::app::prepare_rerun(ctx.options["--rerun"], ctx, recorded);
    if (!why.empty()) {
      std::fprintf(stderr, "pcsim: error: command line: key '--rerun': %s\n", why.c_str());
      return 2;
    }
    ctx.petsc_arguments.insert(ctx.petsc_arguments.begin(), recorded.begin(), recorded.end());
  }
  if (ctx.scene_path.empty() && !takes_operands) {
    for (const auto& a : ctx.petsc_arguments)
      if (a == "-help") {
        print_command_help(ctx.command, command);
        return 0;
      }
    std::fprintf(stderr, "pcsim: error: '%s' needs a scene file (pcsim %s SCENE.yaml)\n",
                 ctx.command.c_str(), ctx.command.c_str());
    return 2;
  }
  return -1;
}

// Refused input: its one message is the last thing said. PETSc's summaries
// at finalisation (-log_view, -options_left) would follow it with a page
// about a run that did not start.
void drop_finalize_summaries() {
  for (const char* name : {"-log_view", "-options_left"}) PetscOptionsClearValue(nullptr, name);
}

}  // namespace

int main(int argc, char** argv) {
  using namespace pcsim::app;
  if (argc < 2) {
    std::fprintf(stderr, "pcsim: error: no command (pcsim --help lists them)\n");
    return 2;
  }
  if (is_help(argv[1])) {
    print_usage();
    return 0;
  }
  if (!std::strcmp(argv[1], "--version") || !std::strcmp(argv[1], "version")) {
    std::printf("pcsim %s (git %s)\n", pcsim::version(), pcsim::git_commit());
    pcsim::select_blas_kernels();
    std::printf("BLAS: %s\n", pcsim::blas_kernels().text().c_str());
    return 0;
  }
  const std::string command_name = argv[1];
  auto it = command_registry().find(command_name);
  if (it == command_registry().end() || !it->second.run) {
    std::fprintf(stderr, "pcsim: error: unknown command '%s' (see pcsim --help)\n",
                 command_name.c_str());
    return 2;
  }
  CommandContext ctx;
  ctx.command = command_name;
  ctx.arguments.assign(argv, argv + argc);
  const int early = parse_arguments(argc, argv, it->second, ctx);
  if (early >= 0) return early;
  std::vector<char*> petsc_argv = {argv[0]};
  for (auto& a : ctx.petsc_arguments) petsc_argv.push_back(a.data());
  int petsc_argc = static_cast<int>(petsc_argv.size());
  petsc_argv.push_back(nullptr);
  char** petsc_args = petsc_argv.data();
  // HDF5 before MPI, and without its own shutdown: HDF5 1.10 crashes when it
  // ends with a file whose close failed (a full disk); pcsim closes every
  // file it writes itself (output/h5_file.hpp, run_stream.hpp).
  // Open MPI's hwloc would open X displays (its GL component probes :0, ...)
  // and Xlib ends the process when such a server goes away mid-run (an Xvfb
  // of another job): pcsim needs no GPU topology.
  setenv("HWLOC_COMPONENTS", "-gl", 0);
  pcsim::select_blas_kernels();  // before any BLAS call (core/blas_kernels.hpp)
  H5dont_atexit();
  H5open();
  if (SlepcInitialize(&petsc_argc, &petsc_args, nullptr, nullptr) != 0) return 4;
  // Failures become pcsim's own one-line messages (exit_status.hpp): no PETSc
  // traceback with its configure line, no HDF5 error stack.
  PetscPushErrorHandler(PetscReturnErrorHandler, nullptr);
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  ctx.comm = PETSC_COMM_WORLD;
  MPI_Comm_rank(ctx.comm, &ctx.rank);
  MPI_Comm_size(ctx.comm, &ctx.size);
  pcsim::simulation::count_node_processes(ctx.comm);  // before a sweep splits the ranks

  // Exit status agreed by all ranks (exit_status.hpp); may MPI_Abort.
  MPI_Comm agreement_comm;
  MPI_Comm_dup(ctx.comm, &agreement_comm);
  int status = 0;
  std::string message;
  bool failed = false;
  try {
    refuse_unknown_options(ctx);
    pcsim::simulation::accuracy_pilot_choice();  // checked (exit 2) and read by every command
    pcsim::simulation::record_batches_choice();
    pcsim::simulation::record_thread_choice();
    pcsim::simulation::pilot_process_choice();
    pcsim::simulation::step_cpu_choice(ctx.size);
    debug_fail_if_asked(ctx);
    status = it->second.run(ctx);
    if (status == 0) warn_unread_options(ctx);
  } catch (...) {
    failed = true;
    status = exit_status_of(std::current_exception(), ctx, message);
  }
  status = agree_exit_status(agreement_comm, status, message, failed);
  MPI_Comm_free(&agreement_comm);
  if (status == 2) drop_finalize_summaries();
  SlepcFinalize();
  return status;
}
