// `pcsim static SCENE.yaml`: form-finding and static configuration of the
// catenary (thesis 3.1.3).
#include <fstream>
#include <nlohmann/json.hpp>

#include "catenary_output.hpp"
#include "command.hpp"
#include "pcsim/assembly/catenary_system.hpp"
#include "pcsim/catenary/catenary_scene.hpp"
#include "pcsim/catenary/statics.hpp"
#include "pcsim/output/output_dir.hpp"

namespace {

using namespace pcsim;

int run_static(const app::CommandContext& ctx) {
  const InputNode scene = InputNode::load_file(ctx.scene_path);
  auto cat = catenary::load_catenary_scene(scene);
  OutputDir out(ctx.comm, ctx.output_request(scene));

  const PetscInt extra = cat.form_finding ? catenary::form_finding_unknowns(cat.mesh) : 0;
  assembly::CatenarySystem system(ctx.comm, cat.mesh, extra);
  Vec x = system.create_vector();
  system.design_state(x);
  app::print0(ctx, "pcsim static: scene '%s', design %s\n", ctx.scene_name(scene).c_str(),
              cat.design_path.c_str());
  app::print0(ctx, "  %d catenary DOFs on %d rank(s); form-finding %s\n",
              static_cast<int>(system.layout().catenary_dofs()), ctx.size,
              cat.form_finding ? "on" : "off");
  const auto result = catenary::solve_static(system, x, cat.form_finding);
  app::print_static_summary(ctx, system, result);
  app::write_static_results(ctx, out, system, result, ctx.scene_name(scene));
  VecDestroy(&x);
  out.commit();
  app::print0(ctx, "  results in %s/\n", out.final_dir().c_str());
  return 0;
}

}  // namespace

PCSIM_COMMAND("static", "form-finding and static configuration of the catenary", run_static);
