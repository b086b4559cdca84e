// Single-dash options: PETSc's options database silently ignores an option no
// object reads, so a typo (-ts_dtt, -foo_bar) would run the default case.
//  - Before any work, an option whose name no PETSc, SLEPc or pcsim object
//    can read (none of their prefixes, and not read by PETSc's start-up) is an
//    input error (exit 2).
//  - After a command that ran solvers, an option with a known prefix that no
//    object read is reported as a warning (PETSc's -options_left, on by
//    default for the options the user gave).
#include <petscsys.h>

#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "command.hpp"
#include "pcsim/core/error.hpp"

namespace pcsim::app {
namespace {

// Prefixes of the options that solver objects read (PETSc's, SLEPc's and
// pcsim's: static_, start_, start_load_, modal_, modal_static_, cheap_,
// pantograph_, pcsim_dd_, elasticity_; study_, modes_fmax and sweep_: commands;
// redundant_ and sub_: the inner solvers of -pc_type redundant, bjacobi and asm
// on a solver without a prefix). After a command, such an option that nothing
// read is warned about.
const char* const kObjectPrefixes[] = {
    "ts_",    "snes_",       "ksp_",   "pc_",         "mat_",       "vec_",   "eps_",
    "st_",    "bv_",         "ds_",    "rg_",         "fn_",        "svd_",   "sf_",
    "dm_",    "pcsim_",      "study_", "modes_",      "static_",    "start_", "modal_",
    "cheap_", "pantograph_", "sweep_", "elasticity_", "redundant_", "sub_"};
// PETSc's own (start-up, viewers, finalisation: -log_view, -options_left,
// -malloc_dump, ...): known, but read outside any command's objects.
const char* const kSystemPrefixes[] = {"viewer_",
                                       "draw_",
                                       "log",
                                       "info",
                                       "malloc",
                                       "memory_",
                                       "options_",
                                       "help",
                                       "version",
                                       "on_error",
                                       "fp_trap",
                                       "objects_",
                                       "mpi",
                                       "petsc",
                                       "slepc",
                                       "skip_petscrc",
                                       "no_signal_handler",
                                       "start_in_debugger",
                                       "debugger",
                                       "stop_for_debugger",
                                       "check_pointer_intensity",
                                       "use_gpu_aware_mpi",
                                       "nox",
                                       "display",
                                       "history",
                                       "citations"};

template <std::size_t N>
bool has_prefix(const std::string& name, const char* const (&prefixes)[N]) {
  for (const char* prefix : prefixes)
    if (name.compare(1, std::strlen(prefix), prefix) == 0) return true;
  return false;
}

bool is_number(const std::string& arg) {
  char* end = nullptr;
  std::strtod(arg.c_str(), &end);
  return end && *end == '\0' && end != arg.c_str();
}

// The option names among the arguments given to PETSc (values skipped).
std::vector<std::string> option_names(const CommandContext& ctx) {
  std::vector<std::string> names;
  for (const auto& arg : ctx.petsc_arguments)
    if (arg.size() > 1 && arg[0] == '-' && !is_number(arg)) names.push_back(arg);
  return names;
}

bool was_read(const std::string& name) {
  PetscBool used = PETSC_FALSE;
  PetscOptionsUsed(nullptr, name.c_str() + 1, &used);  // the database's names lack the dash
  return used == PETSC_TRUE;
}

}  // namespace

void refuse_unknown_options(const CommandContext& ctx) {
  for (const auto& name : option_names(ctx))
    if (!has_prefix(name, kObjectPrefixes) && !has_prefix(name, kSystemPrefixes) && !was_read(name))
      throw InputError("command line", name,
                       "unknown option: neither pcsim nor PETSc reads it (pcsim " + ctx.command +
                           " --help lists pcsim's options; add -help to list the PETSc options "
                           "a run reads)");
}

void warn_unread_options(const CommandContext& ctx) {
  if (ctx.command == "check" || ctx.command == "sweep") return;  // no solver here
  for (const auto& name : option_names(ctx))
    if (has_prefix(name, kObjectPrefixes) && !was_read(name) && ctx.rank == 0)
      std::fprintf(stderr,
                   "pcsim: warning: option %s was not read by any solver of this run "
                   "(misspelt? -help lists the options a run reads)\n",
                   name.c_str());
}

}  // namespace pcsim::app
