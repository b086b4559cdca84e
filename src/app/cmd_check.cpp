// `pcsim check SCENE.yaml [--as CMD] [-o DIR] [--set KEY=VALUE]... [options]`: runs every reader
// and check of the command the scene is for (inputs.hpp: the same functions
// the command calls) and the output folder's check, and solves nothing. Exit 0
// only if the command would start. The command is the one given by --as, else
// the scene's sections decide: 'pantographs' -> run, 'pantograph' ->
// pantograph, 'modes' -> modes, else static. A catenary design file (top-level
// 'type') or a pantograph model file ('kind') is checked alone.
#include <cstdio>

#include "command.hpp"
#include "inputs.hpp"
#include "pcsim/scene/pantograph_reader.hpp"

namespace {

using namespace pcsim;

std::string command_for(const app::CommandContext& ctx, const scene::InputNode& file) {
  if (ctx.has_option("--as")) {
    const std::string& as = ctx.options.at("--as");
    for (const char* known : {"static", "modes", "run", "pantograph"})
      if (as == known) return known;
    throw InputError("command line", "--as",
                     "must be static, modes, run or pantograph (got '" + as + "')");
  }
  if (file.has("type") && !file.has("catenary")) return "design";
  if (file.has("kind") && !file.has("pantograph")) return "model";
  if (file.has("pantographs")) return "run";
  if (file.has("pantograph")) return "pantograph";
  if (file.has("modes")) return "modes";
  return "static";
}

std::string why(const app::CommandContext& ctx, const std::string& command) {
  if (ctx.has_option("--as")) return "as asked by --as";
  if (command == "run") return "the scene has 'pantographs'";
  if (command == "pantograph") return "the scene has 'pantograph'";
  if (command == "modes") return "the scene has 'modes'";
  return "the scene has no 'pantographs', 'pantograph' or 'modes'";
}

// The catenary's unknowns as `pcsim run` and `pcsim static` count them (the
// form-finding unknowns of the static solution apart).
std::string memory_text(const simulation::MemoryEstimate& m, int ranks) {
  char text[240];
  std::snprintf(text, sizeof text,
                "%ld nodes, %ld catenary unknowns (+%ld form-finding unknowns in the static "
                "solution), estimated memory %.2f GB on %d rank(s) (machine %.1f GB)",
                m.nodes, m.dofs - m.form_finding_unknowns, m.form_finding_unknowns,
                m.total_bytes(ranks) / 1e9, ranks, simulation::machine_memory_bytes() / 1e9);
  return text;
}

// The command's own inputs; returns a one-line summary.
std::string check_command(const app::CommandContext& ctx, const std::string& command) {
  if (command == "static") {
    const auto in = app::read_static_inputs(ctx);
    output::check_output_request(ctx.comm, ctx.output_request(in.scene));
    return "design " + in.catenary.design_path + ": " + memory_text(in.memory, ctx.size);
  }
  if (command == "modes") {
    const auto in = app::read_modes_inputs(ctx);
    output::check_output_request(ctx.comm, ctx.output_request(in.statics.scene));
    return "design " + in.statics.catenary.design_path + ": " +
           memory_text(in.statics.memory, ctx.size);
  }
  if (command == "run") {
    const auto in = app::read_run_inputs(ctx);
    app::print_warnings(ctx, in.run.warnings);
    output::check_output_request(ctx.comm, ctx.output_request(in.scene));
    char text[160];
    std::snprintf(text, sizeof text,
                  "%zu pantograph(s), %.0f time steps of %g s (TS %s, %s path); ",
                  in.run.pantographs.size(), in.run.duration() / in.run.dt, in.run.dt,
                  in.numerics.ts_type.c_str(), in.cheap_path ? "cheap" : "full");
    const std::string method =
        in.run.modal_method_note.empty() ? "" : "modal method " + in.run.modal_method_note + "; ";
    // The modal basis's memory needs its modes' count (the run checks it
    // then: simulation::check_modal_memory).
    const bool modal = in.run.catenary.fidelity == catenary::CatenaryFidelity::modal;
    return text + method +
           ("design " + in.run.catenary.design_path + ": " + memory_text(in.memory, ctx.size)) +
           (modal ? ", the modal basis apart (the run checks it once its modes are counted)" : "");
  }
  if (command == "pantograph") {
    const auto in = app::read_pantograph_inputs(ctx);
    output::check_output_request(ctx.comm, ctx.output_request(in.scene));
    return in.study.model->kind() + " model, study " + in.study.study_type;
  }
  if (command == "model")
    return scene::load_pantograph_model(ctx.load_scene(), nullptr, 0.0)->kind() + " model";
  const auto in = app::read_design_inputs(ctx);
  return memory_text(in.memory, ctx.size);
}

int check_scene(const app::CommandContext& ctx) {
  const scene::InputNode file = ctx.load_scene();
  const std::string command = command_for(ctx, file);
  const std::string summary = check_command(ctx, command);
  if (command == "design" || command == "model")
    app::print0(ctx, "%s: %s checked (use it from a scene): %s\n", ctx.scene_path.c_str(),
                command == "design" ? "catenary design" : "pantograph model", summary.c_str());
  else
    app::print0(ctx, "%s: checked as `pcsim %s` (%s): %s; the command would start\n",
                ctx.scene_path.c_str(), command.c_str(), why(ctx, command).c_str(),
                summary.c_str());
  return 0;
}

}  // namespace

PCSIM_COMMAND_HELP(
    check_help, "check",
    "Reads SCENE.yaml (or a catenary design or pantograph model file) with every\n"
    "reader and check of the command it is for, as that command would, and solves\n"
    "nothing: the scene's sections decide the command ('pantographs' -> run,\n"
    "'pantograph' -> pantograph, 'modes' -> modes, else static; docs/scene-format.md).\n"
    "Exit 0 only if the command would start; 2 on bad input (file, key, reason).\n",
    {"--as", "CMD", "check the scene for CMD (static, modes, run, pantograph)"});
PCSIM_COMMAND("check",
              "run every reader and check of the scene's command (--as CMD to choose it), solve "
              "nothing",
              check_scene);
