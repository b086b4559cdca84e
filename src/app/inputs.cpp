#include "inputs.hpp"

#include <cstdio>

#include "pcsim/catenary/geometry.hpp"
#include "pcsim/core/format.hpp"
#include "pcsim/scene/design_reader.hpp"
#include "pcsim/scene/pantograph_scene.hpp"
#include "pcsim/simulation/run.hpp"
#include "pcsim/simulation/run_checkpoint.hpp"
#include "pcsim/simulation/run_session.hpp"
#include "pcsim/solvers/dynamics.hpp"
#include "pcsim/solvers/spectrum.hpp"

namespace pcsim::app {

namespace {

// Refuses, before it is built, a mesh that would not fit in this machine's
// memory (what the job's ranks on this machine hold, up to all of the run's:
// on a cluster each node holds its ranks' share); keeps the estimate for the
// reports.
scene::MeshSizeCheck memory_check(const CommandContext& ctx, simulation::MemoryUse use,
                                  simulation::MemoryEstimate& estimate, int modes = 20) {
  return [&ctx, use, &estimate, modes](const catenary::MeshSize& size) {
    simulation::check_memory(size, use, ctx.size, simulation::machine_memory_bytes(), modes,
                             simulation::counted_node_processes());
    estimate = simulation::estimate_memory(size, use, modes);
  };
}

solvers::ModesRequest scene_modes(const scene::InputNode& scene) {
  const auto section = scene::load_modes_section(scene);
  solvers::ModesRequest r;
  r.count = section.count;
  r.max_frequency_hz = section.max_frequency_hz;
  return r;
}

// -ts_max_time cuts a run short. Past the scene's end the pantographs would
// run on beyond simulation.end_x, off the line at last (a solver failure that
// blames the time step).
void check_max_time(const solvers::TimeIntegrationOptions& numerics, const scene::RunScene& run) {
  const double duration = run.duration();
  if (numerics.max_time && *numerics.max_time > duration * (1 + 1e-12))
    throw InputError("command line", "-ts_max_time",
                     format_number(*numerics.max_time) +
                         " s is past the scene's end: its run lasts " + format_number(duration) +
                         " s (pantographs[0].start_x to simulation.end_x at simulation.speed_kmh); "
                         "-ts_max_time can only cut a run short (raise simulation.end_x to "
                         "run further)");
}

}  // namespace

StaticInputs read_static_inputs(const CommandContext& ctx) {
  StaticInputs in{ctx.load_scene(), "", {}, {}};
  in.name = ctx.scene_name(in.scene);
  in.catenary = scene::load_catenary_scene(
      in.scene, memory_check(ctx, simulation::MemoryUse::statics, in.memory));
  return in;
}

ModesInputs read_modes_inputs(const CommandContext& ctx) {
  const scene::InputNode scene = ctx.load_scene();
  // The count decides the eigensolver's memory: read it first.
  const auto request = solvers::modes_request_from_options(ctx.comm, scene_modes(scene));
  solvers::slicing_parts(ctx.comm, nullptr);  // -eps_krylovschur_partitions, before any work
  ModesInputs in{{scene, ctx.scene_name(scene), {}, {}}, request};
  const int modes = request.max_frequency_hz > 0 ? 20 : request.count;
  in.statics.catenary = scene::load_catenary_scene(
      scene, memory_check(ctx, simulation::MemoryUse::modes, in.statics.memory, modes));
  return in;
}

RunInputs read_run_inputs(const CommandContext& ctx) {
  return read_run_inputs(ctx, ctx.load_scene());
}

RunInputs read_run_inputs(const CommandContext& ctx, const scene::InputNode& scene) {
  RunInputs in{scene, "", {}, {}, false, {}};
  in.name = ctx.scene_name(in.scene);
  in.numerics = solvers::read_time_integration_options(ctx.comm);
  solvers::slicing_parts(ctx.comm, "modal_");  // -modal_eps_krylovschur_partitions, before any work
  scene::RunSceneOptions options;
  options.size_check = memory_check(ctx, simulation::MemoryUse::run, in.memory);
  options.command_line_dt = in.numerics.dt;
  in.run = scene::load_run_scene(in.scene, options);
  if ((in.run.checkpoint_every > 0 || !restart_dir(ctx).empty()) && in.numerics.ts_type != "hht")
    throw InputError("command line", "-ts_type",
                     "checkpoints and restarts need the TS type hht, not " + in.numerics.ts_type);
  check_max_time(in.numerics, in.run);
  in.cheap_path = solvers::choose_cheap_path(ctx.comm, simulation::cheap_path_possible(in.run));
  const auto& design = in.run.catenary.mesh;
  const double c = catenary::wave_speed(design.wires[design.contact_wire]);
  if (in.run.speed > 0.7 * c)
    in.run.warnings.push_back(
        {in.scene.file(), "simulation.speed_kmh",
         "speed " + format_number(in.run.speed * 3.6) +
             " km/h is above 70% of the contact "
             "wire's wave speed (" +
             format_number(c * 3.6) +
             " km/h): the contact force rises "
             "steeply towards the wave speed (design practice stays below 70%)"});
  return in;
}

PantographInputs read_pantograph_inputs(const CommandContext& ctx) {
  PantographInputs in{ctx.load_scene(), "", {}};
  in.name = ctx.scene_name(in.scene);
  in.study = scene::load_pantograph_study_scene(in.scene);
  return in;
}

DesignInputs read_design_inputs(const CommandContext& ctx) {
  DesignInputs in;
  const scene::InputNode design = ctx.load_scene();
  try {
    in.mesh = scene::build_catenary_design(
        design, memory_check(ctx, simulation::MemoryUse::statics, in.memory));
  } catch (const InputError& e) {
    design.rethrow_with_origin(e);
  }
  in.mesh.source_file = ctx.scene_path;
  return in;
}

std::string restart_dir(const CommandContext& ctx) {
  const auto it = ctx.options.find("--restart");
  return it == ctx.options.end() ? "" : it->second;
}

}  // namespace pcsim::app
