// `pcsim modes SCENE.yaml`: catenary modes about the static configuration.
//   modes: {count: 20}            # or {max_frequency_hz: 20}
// -eps_nev overrides count; -modes_fmax overrides max_frequency_hz.
#include "command.hpp"
#include "exit_status.hpp"
#include "inputs.hpp"
#include "pcsim/output/catenary_results.hpp"
#include "pcsim/scene/catenary_scene.hpp"
#include "pcsim/simulation/statics.hpp"

namespace {

using namespace pcsim;

int run_modes(const app::CommandContext& ctx) {
  const app::ModesInputs in = app::read_modes_inputs(ctx);
  const scene::InputNode& scene = in.statics.scene;
  const auto& cat = in.statics.catenary;
  const auto& request = in.request;
  output::OutputDir out(ctx.comm, ctx.output_request(scene));
  app::print0(ctx, "pcsim modes: scene '%s', design %s\n", ctx.scene_name(scene).c_str(),
              cat.design_path.c_str());
  // 1. Static configuration (with form-finding if the scene asks for it).
  const auto statics = simulation::static_configuration(ctx.comm, cat.mesh, cat.form_finding);
  app::print_static_summary(ctx, statics.mesh, statics.result);
  // 2. Modes on the catenary DOFs alone, with the found unstressed lengths.
  const auto modes =
      simulation::catenary_modes(ctx.comm, statics, request.count, request.max_frequency_hz, true);
  app::print0(ctx, "  %zu modes (SLEPc, %d converged, max relative residual %.1e) in %.3f s\n",
              modes.frequencies_hz.size(), modes.converged, modes.max_relative_residual,
              modes.wall_time_s);
  app::print0(ctx, "   mode  frequency [Hz]\n");
  for (std::size_t i = 0; i < modes.frequencies_hz.size(); ++i)
    app::print0(ctx, "   %4zu  %12.6f\n", i + 1, modes.frequencies_hz[i]);
  app::on_rank0(ctx, [&] {
    output::write_modes_results(out, statics.mesh, statics.result, modes,
                                {ctx.scene_name(scene), static_cast<long>(statics.catenary_dofs),
                                 ctx.size, cat.form_finding});
  });
  out.commit();
  app::print0(ctx, "  results in %s/\n", out.final_dir().c_str());
  return 0;
}

}  // namespace

PCSIM_COMMAND_HELP(modes_help, "modes",
                   "scene sections (docs/scene-format.md, \"Catenary scenes\"):\n"
                   "  name         scene name: results go to out/<name>/ (default: the file name)\n"
                   "  description  free text\n"
                   "  catenary     design: FILE (docs/design-format.md), form_finding: true|false\n"
                   "  modes        count: N (20), max_frequency_hz: F (-eps_nev, -modes_fmax)\n"
                   "  base, set    composition: a base scene, keys set by path\n"
                   "results: modes.h5 + modes.xdmf, static.h5, static_mesh.h5, summary.json\n");
PCSIM_COMMAND("modes", "catenary modes about the static configuration (SLEPc)", run_modes);
