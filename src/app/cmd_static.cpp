// `pcsim static SCENE.yaml`: form-finding and static configuration of the
// catenary (thesis 3.1.3).
#include <algorithm>
#include <cmath>

#include "command.hpp"
#include "exit_status.hpp"
#include "inputs.hpp"
#include "pcsim/output/catenary_results.hpp"
#include "pcsim/simulation/elasticity.hpp"
#include "pcsim/simulation/statics.hpp"

namespace {

using namespace pcsim;

// The contact wires' lateral positions under wind against the permissible
// excursion (docs/conditions.md, "Blow-off").
void print_blow_off(const app::CommandContext& ctx, const catenary::BlowOff& b) {
  if (b.empty()) return;
  double support = 0, mid = 0;
  for (std::size_t i = 0; i < b.x.size(); ++i)
    (b.at_support[i] ? support : mid) =
        std::max(b.at_support[i] ? support : mid, std::abs(b.lateral[i]));
  app::print0(ctx,
              "  blow-off: contact wire up to %.1f mm from the track centre at a support, %.1f "
              "mm at a mid-span, %.1f mm at x = %.1f m; permissible %.1f mm: %s\n",
              1e3 * support, 1e3 * mid, 1e3 * b.max_excursion_m, b.max_excursion_x,
              1e3 * b.permissible_m,
              b.max_excursion_m <= b.permissible_m ? "inside the working width"
                                                   : "OUTSIDE the working width");
}

int run_static(const app::CommandContext& ctx) {
  const app::StaticInputs in = app::read_static_inputs(ctx);
  const scene::InputNode& scene = in.scene;
  const auto& cat = in.catenary;
  output::OutputDir out(ctx.comm, ctx.output_request(scene));
  app::print0(ctx, "pcsim static: scene '%s', design %s\n", ctx.scene_name(scene).c_str(),
              cat.design_path.c_str());
  const auto statics = simulation::static_configuration(ctx.comm, cat.mesh, cat.form_finding);
  app::print0(ctx, "  %d catenary DOFs on %d rank(s); form-finding %s\n",
              static_cast<int>(statics.catenary_dofs), ctx.size, cat.form_finding ? "on" : "off");
  app::print_static_summary(ctx, statics.mesh, statics.result);
  const std::string conditions = simulation::conditions_summary(statics);
  if (!conditions.empty()) app::print0(ctx, "  %s\n", conditions.c_str());
  print_blow_off(ctx, statics.result.blow_off);
  simulation::on_rank0(ctx, [&] {  // a failed write stops every rank at once
    output::write_static_results(out, statics.mesh, statics.result,
                                 {ctx.scene_name(scene), static_cast<long>(statics.catenary_dofs),
                                  ctx.size, cat.form_finding});
  });
  if (cat.elasticity) {
    const auto e = simulation::static_elasticity(ctx.comm, statics, cat.elasticity->stations(),
                                                 cat.elasticity->force);
    const auto [lo, hi] = std::minmax_element(e.uplift.begin(), e.uplift.end());
    app::print0(ctx,
                "  elasticity (%g N at %zu points): uplift %.2f .. %.2f mm per 100 N, "
                "non-uniformity (max - min) / (max + min) = %.1f%%\n",
                e.force, e.x.size(), 1e5 * *lo / e.force, 1e5 * *hi / e.force,
                100.0 * (*hi - *lo) / (*hi + *lo));
    simulation::on_rank0(ctx, [&] { output::write_elasticity(out, e); });
  }
  out.commit();
  app::print0(ctx, "  results in %s/\n", out.final_dir().c_str());
  return 0;
}

}  // namespace

PCSIM_COMMAND_HELP(
    static_help, "static",
    "scene sections (docs/scene-format.md, \"Catenary scenes\"):\n"
    "  name         scene name: results go to out/<name>/ (default: the file name)\n"
    "  description  free text\n"
    "  catenary     design: FILE (docs/design-format.md), form_finding: true|false\n"
    "  conditions   ice, temperature, wind (docs/conditions.md); with a wind, the\n"
    "               contact wire's blow-off against the working width\n"
    "  base, set    composition: a base scene, keys set by path\n"
    "results: static.h5 (with a wind: /blow_off), static_mesh.h5 + static.xdmf (ParaView),\n"
    "  summary.json\n");
PCSIM_COMMAND("static", "form-finding and static configuration of the catenary", run_static);
