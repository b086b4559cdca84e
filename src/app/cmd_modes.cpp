// `pcsim modes SCENE.yaml`: catenary modes about the static configuration.
//   modes: {count: 20}            # or {max_frequency_hz: 20}
// -eps_nev overrides count; -modes_fmax overrides max_frequency_hz.
#include <petscsys.h>

#include "catenary_output.hpp"
#include "command.hpp"
#include "pcsim/catenary/catenary_scene.hpp"
#include "pcsim/catenary/modes.hpp"
#include "pcsim/catenary/statics.hpp"

namespace {

using namespace pcsim;

int run_modes(const app::CommandContext& ctx) {
  const InputNode scene = InputNode::load_file(ctx.scene_path);
  auto cat = catenary::load_catenary_scene(scene);
  long count = 20;
  double fmax = 0;
  if (scene.has("modes")) {
    const InputNode m = scene["modes"];
    m.allow_only({"count", "max_frequency_hz"});
    count = m.get_int("count", 20);
    if (count < 1) m.fail_key("count", "must be at least 1");
    fmax = m.get_positive("max_frequency_hz", 0.0);
  }
  PetscInt nev = count;
  PetscReal fmax_opt = fmax;
  PetscOptionsGetInt(nullptr, nullptr, "-eps_nev", &nev, nullptr);
  PetscOptionsGetReal(nullptr, nullptr, "-modes_fmax", &fmax_opt, nullptr);
  OutputDir out(ctx.comm, ctx.output_request(scene));

  app::print0(ctx, "pcsim modes: scene '%s', design %s\n", ctx.scene_name(scene).c_str(),
              cat.design_path.c_str());
  // 1. Static configuration (with form-finding if the scene asks for it).
  const PetscInt extra = cat.form_finding ? catenary::form_finding_unknowns(cat.mesh) : 0;
  auto statics_system = std::make_unique<assembly::CatenarySystem>(ctx.comm, cat.mesh, extra);
  Vec xs = statics_system->create_vector();
  statics_system->design_state(xs);
  const auto statics = catenary::solve_static(*statics_system, xs, cat.form_finding);
  app::print_static_summary(ctx, *statics_system, statics);
  // 2. Modes on the catenary DOFs alone, with the found unstressed lengths.
  assembly::CatenarySystem system(ctx.comm, statics_system->mesh());
  VecDestroy(&xs);
  statics_system.reset();
  Vec x = system.create_vector();
  catenary::set_state_from_node_values(system, statics.node_values, x);
  const auto modes = catenary::compute_modes(system, x, static_cast<int>(nev), fmax_opt, true);
  app::print0(ctx, "  %zu modes (SLEPc, %d converged, max relative residual %.1e) in %.3f s\n",
              modes.frequencies_hz.size(), modes.converged, modes.max_relative_residual,
              modes.wall_time_s);
  app::print0(ctx, "   mode  frequency [Hz]\n");
  for (std::size_t i = 0; i < modes.frequencies_hz.size(); ++i)
    app::print0(ctx, "   %4zu  %12.6f\n", i + 1, modes.frequencies_hz[i]);
  app::write_modes_results(ctx, out, system, statics, modes, ctx.scene_name(scene));
  VecDestroy(&x);
  out.commit();
  app::print0(ctx, "  results in %s/\n", out.final_dir().c_str());
  return 0;
}

}  // namespace

PCSIM_COMMAND("modes", "catenary modes about the static configuration (SLEPc)", run_modes);
