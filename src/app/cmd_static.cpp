// `pcsim static SCENE.yaml`: form-finding and static configuration of the
// catenary (thesis 3.1.3).
#include "command.hpp"
#include "exit_status.hpp"
#include "inputs.hpp"
#include "pcsim/output/catenary_results.hpp"
#include "pcsim/solvers/statics.hpp"

namespace {

using namespace pcsim;

int run_static(const app::CommandContext& ctx) {
  const app::StaticInputs in = app::read_static_inputs(ctx);
  const InputNode& scene = in.scene;
  const auto& cat = in.catenary;
  OutputDir out(ctx.comm, ctx.output_request(scene));
  app::print0(ctx, "pcsim static: scene '%s', design %s\n", ctx.scene_name(scene).c_str(),
              cat.design_path.c_str());
  const auto statics = solvers::static_configuration(ctx.comm, cat.mesh, cat.form_finding);
  app::print0(ctx, "  %d catenary DOFs on %d rank(s); form-finding %s\n",
              static_cast<int>(statics.catenary_dofs), ctx.size, cat.form_finding ? "on" : "off");
  app::print_static_summary(ctx, statics.mesh, statics.result);
  if (ctx.rank == 0)
    output::write_static_results(out, statics.mesh, statics.result,
                                 {ctx.scene_name(scene), static_cast<long>(statics.catenary_dofs),
                                  ctx.size, cat.form_finding});
  out.commit();
  app::print0(ctx, "  results in %s/\n", out.final_dir().c_str());
  return 0;
}

}  // namespace

PCSIM_COMMAND("static", "form-finding and static configuration of the catenary", run_static);
